// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/looming.h"

#include <cmath>

namespace obstacle_tracker {
namespace core {

namespace {

double sizeOf(const cv::Rect2f& b) { return std::sqrt(static_cast<double>(b.width) * b.height); }

cv::Point2f centreOf(const cv::Rect2f& b) { return {b.x + 0.5f * b.width, b.y + 0.5f * b.height}; }

}  // namespace

void LoomingEstimator::setParams(double rate_noise, bool use_pixels) {
  filter_.setRateNoise(rate_noise);
  use_pixels_ = use_pixels;
  if (!use_pixels_) meter_.reset();
}

void LoomingEstimator::start(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
  filter_.reset(stamp, sizeOf(box), kStartSigma);
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
  if (use_pixels_) m = meter_.measure(frame, centreOf(box));
  // The box size stands in for an expansion that was not measured or was dropped as an outlier.
  if (!m.valid || !filter_.updateExpansion(m.log_ratio, m.sigma)) filter_.updateSize(sizeOf(box), kBoxSizeSigma);
  if (use_pixels_) meter_.setReference(frame, box);
}

void LoomingEstimator::restart(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
  if (!filter_.initialized()) {
    start(frame, stamp, box);
    return;
  }
  filter_.predict(stamp);
  filter_.restartSize(sizeOf(box), kStartSigma);
  if (use_pixels_) meter_.setReference(frame, box);
}

}  // namespace core
}  // namespace obstacle_tracker
