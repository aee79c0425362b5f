// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/frame_interval.h"

#include <algorithm>
#include <cmath>

namespace obstacle_tracker {
namespace core {

namespace {
// A gap counts as dropped frames from 1.5 usual intervals on: camera stamps jitter by far less.
constexpr double kDroppedFrom = 1.5;
}  // namespace

void FrameInterval::reset() {
  count_ = 0;
  have_stamp_ = false;
  stamp_ = last_ = usual_ = 0.0;
}

void FrameInterval::add(double stamp) {
  if (!std::isfinite(stamp)) return;
  if (have_stamp_ && stamp < stamp_) reset();
  last_ = have_stamp_ ? stamp - stamp_ : 0.0;
  stamp_ = stamp;
  have_stamp_ = true;
  if (!(last_ > 0.0)) return;  // the first frame, or a repeated stamp: no interval
  intervals_[static_cast<std::size_t>(count_ % kWindow)] = last_;
  ++count_;
  // Median of the kept intervals (the upper one of an even count): a copy, sorted in place on
  // the stack.
  const int n = std::min(count_, kWindow);
  std::array<double, kWindow> sorted = intervals_;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.begin() + n);
  usual_ = sorted[static_cast<std::size_t>(n / 2)];
}

double FrameInterval::dropped() const {
  if (!(usual_ > 0.0) || last_ < kDroppedFrom * usual_) return 0.0;
  return last_ - usual_;
}

}  // namespace core
}  // namespace obstacle_tracker
