// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/looming.h"

#include <algorithm>
#include <cmath>

namespace obstacle_tracker {
namespace core {

namespace {
constexpr double kMinRate = 1e-6;  // 1/s; below this the box is steady (tau > 11 days)
constexpr double kMinTau = 1e-3;   // s
}  // namespace

LoomingEstimator::LoomingEstimator(int window) { setWindow(window); }

void LoomingEstimator::setWindow(int window) {
  capacity_ = static_cast<std::size_t>(std::max(window, 3));
  ring_.assign(capacity_, Sample{0.0, 0.0, 0});
  reset();
}

void LoomingEstimator::reset() {
  head_ = 0;
  count_ = 0;
  segment_ = 0;
  new_segment_ = false;
  rate_ = 0.0;
}

void LoomingEstimator::markDiscontinuity() { new_segment_ = count_ > 0; }

void LoomingEstimator::add(double stamp, const cv::Rect2f& box) {
  if (!(box.width > 0.0f) || !(box.height > 0.0f)) return;
  addSize(stamp, std::sqrt(static_cast<double>(box.width) * static_cast<double>(box.height)));
}

void LoomingEstimator::addSize(double stamp, double size) {
  if (!std::isfinite(stamp) || !std::isfinite(size) || !(size > 0.0)) return;
  if (count_ > 0) {
    const std::size_t last = (head_ + capacity_ - 1) % capacity_;
    if (stamp < ring_[last].t) {
      reset();
    } else if (stamp == ring_[last].t) {
      head_ = last;  // replace the last sample
      --count_;
    }
  }
  if (new_segment_) {
    ++segment_;
    new_segment_ = false;
  }
  ring_[head_] = Sample{stamp, std::log(size), segment_};
  head_ = (head_ + 1) % capacity_;
  count_ = std::min(count_ + 1, capacity_);
  refit();
}

void LoomingEstimator::refit() {
  // Common slope, one intercept per segment: slope = sum (t - tbar_seg)(y - ybar_seg) /
  // sum (t - tbar_seg)^2. Samples are in time order and segments are contiguous runs.
  const std::size_t first = (head_ + capacity_ - count_) % capacity_;
  double sxy = 0.0, sxx = 0.0, t_weighted = 0.0, t_last = 0.0;
  std::size_t i = 0;
  while (i < count_) {
    const int seg = ring_[(first + i) % capacity_].segment;
    std::size_t j = i;
    double st = 0.0, sy = 0.0;
    while (j < count_ && ring_[(first + j) % capacity_].segment == seg) {
      st += ring_[(first + j) % capacity_].t;
      sy += ring_[(first + j) % capacity_].log_size;
      ++j;
    }
    const double n = static_cast<double>(j - i);
    const double tbar = st / n, ybar = sy / n;
    double seg_sxx = 0.0;
    for (std::size_t k = i; k < j; ++k) {
      const Sample& s = ring_[(first + k) % capacity_];
      sxy += (s.t - tbar) * (s.log_size - ybar);
      seg_sxx += (s.t - tbar) * (s.t - tbar);
    }
    sxx += seg_sxx;
    t_weighted += seg_sxx * tbar;  // each segment's slope counts with weight seg_sxx
    i = j;
  }
  t_last = ring_[(first + count_ - 1) % capacity_].t;
  // At least 3 samples and some time spread inside segments; otherwise no estimate.
  const double slope = (count_ >= 3 && sxx > 1e-12) ? sxy / sxx : 0.0;
  if (slope > kMinRate) {
    // The slope is the rate at the samples' mean time (segments weighted as in the fit). Under a constant closing speed the time
    // to contact falls by exactly 1 s per s (tau-dot = -1, Lee 1976), so carry it to the newest
    // sample; this removes the half-window lag (0.23 s for 15 frames at 30 Hz).
    const double tau = 1.0 / slope - (t_last - t_weighted / sxx);
    rate_ = tau > kMinTau ? 1.0 / tau : 1.0 / kMinTau;
  } else {
    rate_ = std::abs(slope) > kMinRate ? slope : 0.0;
  }
}

}  // namespace core
}  // namespace obstacle_tracker
