// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// core::Pipeline wrapped as an EvalTracker (see pipeline_tracker.h).
#include "obstacle_tracker/eval/pipeline_tracker.h"

#include "obstacle_tracker/core/pipeline.h"

namespace obstacle_tracker {
namespace eval {

namespace {

class PipelineTracker : public EvalTracker {
 public:
  PipelineTracker(bool auto_init, const core::Params& params) : auto_init_(auto_init), pipeline_(params) {}
  bool needsInitBox() const override { return !auto_init_; }
  TrackerReport start(const cv::Mat& frame, double stamp, const cv::Rect2f& init_box) override {
    pipeline_.reset();
    if (auto_init_) return best(pipeline_.process(frame, stamp));
    return best(pipeline_.startTrack(frame, stamp, init_box));
  }
  TrackerReport update(const cv::Mat& frame, double stamp) override {
    return best(pipeline_.process(frame, stamp));
  }

 private:
  static TrackerReport best(const std::vector<core::Obstacle>& obstacles) {
    if (obstacles.empty()) return {};  // no target: the zero box, confidence 0
    return {obstacles.front().box, obstacles.front().confidence};
  }
  bool auto_init_;
  core::Pipeline pipeline_;
};

}  // namespace

std::vector<std::string> pipelineTrackerNames() { return {"ours-auto", "ours-gt"}; }

std::unique_ptr<EvalTracker> makePipelineTracker(const std::string& name, const core::Params& params) {
  if (name == "ours-auto") return std::make_unique<PipelineTracker>(true, params);
  if (name == "ours-gt") return std::make_unique<PipelineTracker>(false, params);
  return nullptr;
}

}  // namespace eval
}  // namespace obstacle_tracker
