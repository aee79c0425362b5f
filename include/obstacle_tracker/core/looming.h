// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Looming: the expansion rate of a tracked box and its time to contact.
//
// s(t) = sqrt(w * h). For an object closing at constant speed, s(t) = s0 * T / (T - t) and
// d ln s / dt = 1 / (T - t): the expansion rate is the inverse of the time left before contact
// (Lee, "A theory of visual control of braking based on information about time-to-collision",
// Perception 1976). One frame pair is useless (a 2 % size step at 30 Hz alone means 1.7 s), so
// the rate is the least-squares slope of ln s over the last `window` samples. That slope is the
// rate at the samples' mean time; when closing, the time to contact 1/slope is carried forward to
// the newest sample with d tau/dt = -1 (exact for a constant closing speed), which removes the
// half-window lag, and the reported rate is 1/tau at the newest sample.
//
// Re-detections restart the filter on a box of the object's current size and shape, which can
// step the size abruptly (the filter's box was too tight, or the region is segmented
// differently). Such a step is not motion, so the history is split into segments at every
// `markDiscontinuity()`: all segments share one slope but each has its own intercept (a
// least-squares fit with per-segment offsets). The history is kept, the step is ignored.
#pragma once

#include <limits>
#include <vector>

#include <opencv2/core/types.hpp>

namespace obstacle_tracker {
namespace core {

class LoomingEstimator {
 public:
  explicit LoomingEstimator(int window = 15);

  // Number of samples kept (>= 3). Clears the history. Allocates here only.
  void setWindow(int window);
  int window() const { return static_cast<int>(capacity_); }

  void reset();

  // Adds the box of the frame at `stamp` (s). A box without positive area or a non-finite
  // stamp is ignored; a stamp equal to the last one replaces the last sample; a stamp that goes
  // backwards resets the history first.
  void add(double stamp, const cv::Rect2f& box);
  void addSize(double stamp, double size);

  // The next sample starts a new segment (its size may step against the previous one).
  void markDiscontinuity();

  // d ln s / dt in 1/s at the newest sample (positive when the box grows); 0 while fewer than 3
  // samples span time.
  double expansionRate() const { return rate_; }

  // 1 / expansionRate() when closing (rate > 0), +inf otherwise.
  double timeToContact() const {
    return rate_ > 0.0 ? 1.0 / rate_ : std::numeric_limits<double>::infinity();
  }

  int samples() const { return static_cast<int>(count_); }

 private:
  struct Sample {
    double t;
    double log_size;
    int segment;
  };
  void refit();

  std::vector<Sample> ring_;
  std::size_t capacity_ = 15, head_ = 0, count_ = 0;
  int segment_ = 0;
  bool new_segment_ = false;
  double rate_ = 0.0;
};

}  // namespace core
}  // namespace obstacle_tracker
