// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Running one tracker over (part of) one sequence, the unit of work of the `evaluate` tool.
// Trackers: our pipeline ("ours-auto": it finds the target by itself; "ours-gt": started from the
// first ground-truth box with Pipeline::startTrack) and OpenCV's contrib trackers ("KCF", "CSRT",
// "MIL", "MOSSE", "MedianFlow"), the latter started from the ground-truth box; when their
// update() fails they keep the last box (with confidence 0), the convention the published OpenCV baselines use.
// Timing covers the tracker's own per-frame call only (decode and colour conversion excluded).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/eval/sequence.h"

namespace obstacle_tracker {
namespace eval {

// What a tracker reports for one frame; an absent box (isAbsent) means "no target".
struct TrackerReport {
  cv::Rect2f box;
  float confidence = 0.0f;
};

class EvalTracker {
 public:
  virtual ~EvalTracker() = default;
  // True when the tracker must be started from a ground-truth box (frames before the first
  // present box are then reported as "no target").
  virtual bool needsInitBox() const = 0;
  // First frame of a run. `init_box` is the ground truth of that frame (absent for ours-auto).
  // frame is the core frame (CV_8UC1 or CV_8UC3 BGR).
  virtual TrackerReport start(const cv::Mat& frame, double stamp, const cv::Rect2f& init_box) = 0;
  virtual TrackerReport update(const cv::Mat& frame, double stamp) = 0;
};

// Names accepted by makeTracker, in the order the tool lists them by default.
std::vector<std::string> knownTrackers();

// Throws std::invalid_argument for an unknown name. params is used by the ours-* trackers.
std::unique_ptr<EvalTracker> makeTracker(const std::string& name,
                                         const core::Params& params = core::Params());

// One run of one tracker from frame `start_frame` to the end of the sequence.
struct RunResult {
  std::string sequence, tracker;
  int start_frame = 0;
  std::vector<cv::Rect2f> boxes;    // one per frame from start_frame on
  std::vector<float> confidence;    // same length
  std::vector<cv::Rect2f> gt;       // the ground truth of those frames (absent past its end)
  double update_seconds = 0.0;      // time spent in start() for ours-auto, update() for all
  int timed_frames = 0;             // frames counted in update_seconds
  std::vector<float> frame_ms;      // each timed call, milliseconds (for percentiles and spikes)
  std::string error;                // non-empty when the run had to stop (message)
  double fps() const { return update_seconds > 0.0 ? timed_frames / update_seconds : 0.0; }
};

// Runs `tracker_name` on the sequence at `path` (opened here, so runs can go in parallel) from
// `start_frame`; a tracker that needs a box starts on the first frame >= start_frame whose ground
// truth is present. progress (optional) is advanced by one per decoded frame.
RunResult runTracker(const std::string& path, const std::string& tracker_name,
                     const core::Params& params, int start_frame = 0,
                     std::atomic<int>* progress = nullptr,
                     const std::string& ground_truth_path = "");

// OTB's temporal robustness evaluation: `count` start frames evenly spaced over the sequence
// (floor(i * n / count), i = 0..count-1), each moved forward to the next frame whose ground
// truth is present; duplicates removed. The first is the OPE start (frame 0 or the first present).
std::vector<int> treStartFrames(const std::vector<cv::Rect2f>& gt, int count = 20);

// The "flying" subset of the shared sequences: names starting with antiuav_ or lasot_airplane.
bool isFlyingSequence(const std::string& name);

}  // namespace eval
}  // namespace obstacle_tracker
