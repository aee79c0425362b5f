// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Runs one tracker over one sequence (see runner.h). OpenCV's contrib trackers are wrapped here;
// our pipeline's wrappers live in pipeline_tracker.cpp.
#include "obstacle_tracker/eval/runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include <opencv2/imgproc.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/tracking/tracking_legacy.hpp>

#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/eval/pipeline_tracker.h"

namespace obstacle_tracker {
namespace eval {

namespace {

// OpenCV's trackers are fed 3-channel BGR, as cv::imread's default gives them (grey frames are
// expanded); the conversion happens outside the timed call.
const cv::Mat& toBgr(const cv::Mat& frame, cv::Mat& buffer) {
  if (frame.type() == CV_8UC3) return frame;
  if (frame.type() == CV_8UC1) {
    cv::cvtColor(frame, buffer, cv::COLOR_GRAY2BGR);
    return buffer;
  }
  throw std::invalid_argument("OpenCV tracker: frame must be CV_8UC1 or CV_8UC3");
}

// The ground-truth box as the integer box OpenCV's trackers take, clipped to the image. Empty
// when nothing of it is inside.
cv::Rect initRect(const cv::Rect2f& box, const cv::Size& size) {
  cv::Rect r(static_cast<int>(std::lround(box.x)), static_cast<int>(std::lround(box.y)),
             std::max(1, static_cast<int>(std::lround(box.width))),
             std::max(1, static_cast<int>(std::lround(box.height))));
  return r & cv::Rect(0, 0, size.width, size.height);
}

// OpenCV's trackers behind EvalTracker: cv::Tracker (KCF, CSRT, MIL; integer boxes, init
// returns nothing) and cv::legacy::Tracker (MOSSE, MedianFlow; double boxes, init reports
// failure). A failed or throwing update keeps the last box.
template <class TrackerT, class RectT>
class OpenCvTracker : public EvalTracker {
 public:
  explicit OpenCvTracker(cv::Ptr<TrackerT> (*factory)()) : factory_(factory) {}
  bool needsInitBox() const override { return true; }
  TrackerReport start(const cv::Mat& frame, double, const cv::Rect2f& box) override {
    const cv::Mat& bgr = toBgr(frame, bgr_);
    const cv::Rect r = initRect(box, bgr.size());
    if (r.empty()) throw std::runtime_error("initial box is outside the image");
    tracker_ = factory_();
    if constexpr (std::is_same_v<RectT, cv::Rect>) {
      tracker_->init(bgr, r);
    } else if (!tracker_->init(bgr, RectT(r))) {
      throw std::runtime_error("tracker init failed");
    }
    last_ = box;
    return {box, 1.0f};
  }
  TrackerReport update(const cv::Mat& frame, double) override {
    const cv::Mat& bgr = toBgr(frame, bgr_);
    RectT r;
    bool ok = false;
    try {
      ok = tracker_->update(bgr, r);
    } catch (const cv::Exception&) {
      ok = false;  // e.g. a box that left the image: treated as a failed update
    }
    if (ok && r.width > 0 && r.height > 0 && std::isfinite(static_cast<double>(r.x)) &&
        std::isfinite(static_cast<double>(r.y))) {
      last_ = cv::Rect2f(r);
      return {last_, 1.0f};
    }
    return {last_, 0.0f};
  }

 private:
  cv::Ptr<TrackerT> (*factory_)();
  cv::Ptr<TrackerT> tracker_;
  cv::Mat bgr_;
  cv::Rect2f last_;
};
using ModernTracker = OpenCvTracker<cv::Tracker, cv::Rect>;
using LegacyTracker = OpenCvTracker<cv::legacy::Tracker, cv::Rect2d>;

cv::Ptr<cv::Tracker> makeKcf() { return cv::TrackerKCF::create(); }
cv::Ptr<cv::Tracker> makeCsrt() { return cv::TrackerCSRT::create(); }
cv::Ptr<cv::Tracker> makeMil() { return cv::TrackerMIL::create(); }
cv::Ptr<cv::legacy::Tracker> makeMosse() { return cv::legacy::TrackerMOSSE::create(); }
cv::Ptr<cv::legacy::Tracker> makeMedianFlow() { return cv::legacy::TrackerMedianFlow::create(); }

}  // namespace

std::vector<std::string> knownTrackers() {
  std::vector<std::string> names = pipelineTrackerNames();
  for (const char* n : {"KCF", "CSRT", "MOSSE", "MIL", "MedianFlow"}) names.emplace_back(n);
  return names;
}

std::unique_ptr<EvalTracker> makeTracker(const std::string& name, const core::Params& params) {
  if (name == "KCF") return std::make_unique<ModernTracker>(&makeKcf);
  if (name == "CSRT") return std::make_unique<ModernTracker>(&makeCsrt);
  if (name == "MIL") return std::make_unique<ModernTracker>(&makeMil);
  if (name == "MOSSE") return std::make_unique<LegacyTracker>(&makeMosse);
  if (name == "MedianFlow") return std::make_unique<LegacyTracker>(&makeMedianFlow);
  if (auto t = makePipelineTracker(name, params)) return t;
  std::string list;
  for (const auto& n : knownTrackers()) list += (list.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown tracker '" + name + "' (known: " + list + ")");
}

RunResult runTracker(const std::string& path, const std::string& tracker_name,
                     const core::Params& params, int start_frame, std::atomic<int>* progress,
                     const std::string& ground_truth_path) {
  using Clock = std::chrono::steady_clock;
  RunResult res;
  res.tracker = tracker_name;
  Sequence seq(path, ground_truth_path);
  res.sequence = seq.name();
  const int n = seq.frameCount();
  if (start_frame < 0 || start_frame >= n) {
    throw std::out_of_range("runTracker: start frame " + std::to_string(start_frame) + " of " +
                            std::to_string(n));
  }
  res.start_frame = start_frame;
  std::unique_ptr<EvalTracker> tracker = makeTracker(tracker_name, params);
  FrameConverter converter;
  const double fps = seq.fps() > 0.0 ? seq.fps() : 30.0;
  seq.seek(start_frame);
  cv::Mat raw;
  bool started = false;
  res.boxes.reserve(n - start_frame);
  res.confidence.reserve(n - start_frame);
  res.frame_ms.reserve(n - start_frame);
  res.gt.reserve(n - start_frame);
  for (int i = start_frame; seq.read(raw); ++i) {
    if (progress) progress->fetch_add(1, std::memory_order_relaxed);
    const cv::Rect2f gt = seq.groundTruthAt(i);
    res.gt.push_back(gt);
    TrackerReport rep;
    if (res.error.empty()) {
      const cv::Mat& frame = converter.convert(raw);
      const double stamp = i / fps;
      try {
        if (!started) {
          if (!tracker->needsInitBox()) {
            const auto t0 = Clock::now();
            rep = tracker->start(frame, stamp, cv::Rect2f());
            const double sec = std::chrono::duration<double>(Clock::now() - t0).count();
            res.update_seconds += sec;
            res.frame_ms.push_back(static_cast<float>(1e3 * sec));
            ++res.timed_frames;
            started = true;
          } else if (!isAbsent(gt)) {
            rep = tracker->start(frame, stamp, gt);  // initialisation is not timed
            started = true;
          }
        } else {
          const auto t0 = Clock::now();
          rep = tracker->update(frame, stamp);
          const double sec = std::chrono::duration<double>(Clock::now() - t0).count();
          res.update_seconds += sec;
          res.frame_ms.push_back(static_cast<float>(1e3 * sec));
          ++res.timed_frames;
        }
      } catch (const std::exception& e) {
        // Stop this run (the rest of its frames count as "no target") but keep the others going.
        res.error = "frame " + std::to_string(i) + ": " + e.what();
        rep = TrackerReport();
      }
    }
    res.boxes.push_back(rep.box);
    res.confidence.push_back(rep.confidence);
  }
  return res;
}

std::vector<int> treStartFrames(const std::vector<cv::Rect2f>& gt, int count) {
  if (count < 1) throw std::invalid_argument("treStartFrames: count < 1");
  const int n = static_cast<int>(gt.size());
  std::vector<int> starts;
  for (int k = 0; k < count; ++k) {
    int s = static_cast<int>((static_cast<long long>(k) * n) / count);
    while (s < n && isAbsent(gt[s])) ++s;
    if (s < n && (starts.empty() || starts.back() != s)) starts.push_back(s);
  }
  return starts;
}

bool isFlyingSequence(const std::string& name) {
  return name.rfind("antiuav_", 0) == 0 || name.rfind("lasot_airplane", 0) == 0;
}

}  // namespace eval
}  // namespace obstacle_tracker
