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
  next_ = count_ = 0;
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
  intervals_[static_cast<std::size_t>(next_)] = last_;
  next_ = (next_ + 1) % kWindow;
  count_ = std::min(count_ + 1, kWindow);
  // Median of the kept intervals (the upper one of an even count), by a partial sort of a copy
  // on the stack.
  std::array<double, kWindow> sorted = intervals_;
  std::nth_element(sorted.begin(), sorted.begin() + count_ / 2, sorted.begin() + count_);
  usual_ = sorted[static_cast<std::size_t>(count_ / 2)];
}

double FrameInterval::dropped() const {
  if (!(usual_ > 0.0) || last_ < kDroppedFrom * usual_) return 0.0;
  return last_ - usual_;
}

}  // namespace core
}  // namespace obstacle_tracker
