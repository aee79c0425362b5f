// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/looming.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "obstacle_tracker/core/box_geometry.h"

namespace obstacle_tracker {
namespace core {

namespace {

double sizeOf(const cv::Rect2f& b) { return std::sqrt(static_cast<double>(b.width) * b.height); }

}  // namespace

void LoomingEstimator::setParams(double rate_noise, bool use_pixels) {
  filter_.setRateNoise(rate_noise);
  use_pixels_ = use_pixels;
  if (!use_pixels_) meter_.reset();
}

void LoomingEstimator::start(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
  filter_.reset(stamp, sizeOf(box), kStartSigma);
  recent_count_ = 0;
  meter_.reset();
  if (use_pixels_) meter_.setReference(frame, box);
}

void LoomingEstimator::track(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
  if (!filter_.initialized()) {  // never started, or its state stopped being finite
    start(frame, stamp, box);
    return;
  }
  filter_.predict(stamp);
  ExpansionMeasurement m;
  if (use_pixels_) m = meter_.measure(frame, boxCentre(box));
  recordExpansion(m);
  // The box size stands in for an expansion that was not measured or was dropped as an outlier.
  if (!m.valid || !filter_.updateExpansion(m.log_ratio, m.sigma)) filter_.updateSize(sizeOf(box), kBoxSizeSigma);
  if (use_pixels_) meter_.setReference(frame, box);
}

void LoomingEstimator::recordExpansion(const ExpansionMeasurement& m) {
  const bool usable = m.valid && std::isfinite(m.log_ratio);
  recent_[static_cast<std::size_t>(recent_count_ % kTrendFrames)] =
      usable ? m.log_ratio : std::numeric_limits<double>::quiet_NaN();
  ++recent_count_;
}

// The trend needs at least two measured frames (half of kTrendFrames) for the expansions'
// standard deviation below.
static_assert(LoomingEstimator::kTrendFrames >= 4, "sizeTrend's t test needs two measured frames");

int LoomingEstimator::sizeTrend() const {
  const int frames = std::min(recent_count_, kTrendFrames);
  double sum = 0.0;
  int measured = 0;
  for (int i = 0; i < frames; ++i) {
    const double v = recent_[static_cast<std::size_t>(i)];
    if (std::isnan(v)) continue;
    sum += v;
    ++measured;
  }
  if (2 * measured < kTrendFrames) return 0;
  // The mean expansion must stand out of the expansions' own scatter (a one-sample t statistic).
  const double mean = sum / measured;
  double squares = 0.0;
  for (int i = 0; i < frames; ++i) {
    const double v = recent_[static_cast<std::size_t>(i)];
    if (!std::isnan(v)) squares += (v - mean) * (v - mean);
  }
  const double standard_error = std::sqrt(squares / (measured - 1) / measured);
  if (!(std::abs(mean) >= kTrendStandardErrors * standard_error)) return 0;
  return sum > kTrendLogSize ? 1 : (sum < -kTrendLogSize ? -1 : 0);
}

void LoomingEstimator::restart(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
  if (!filter_.initialized()) {
    start(frame, stamp, box);
    return;
  }
  filter_.predict(stamp);
  filter_.restartSize(sizeOf(box), kStartSigma);
  recent_count_ = 0;  // no expansion is measured across the gap
  if (use_pixels_) meter_.setReference(frame, box);
}

}  // namespace core
}  // namespace obstacle_tracker
