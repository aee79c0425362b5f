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
  filter_.predict(stamp);
  ExpansionMeasurement m;
  if (use_pixels_) m = meter_.measure(frame, centreOf(box));
  if (m.valid) {
    filter_.updateExpansion(m.log_ratio, m.sigma);
  } else {
    filter_.updateSize(sizeOf(box), kFilterSigma);
  }
  if (use_pixels_) meter_.setReference(frame, box);
}

void LoomingEstimator::restart(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
  filter_.predict(stamp);
  filter_.restartSize(sizeOf(box), kStartSigma);
  if (use_pixels_) meter_.setReference(frame, box);
}

}  // namespace core
}  // namespace obstacle_tracker
