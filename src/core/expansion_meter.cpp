// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/expansion_meter.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/box_geometry.h"

namespace obstacle_tracker {
namespace core {

ExpansionMeter::ExpansionMeter() { sampler_.reserve(kPatchSide, kPatchSide, CV_8UC3, kPatchSide); }

void ExpansionMeter::toGrey(const cv::Mat& sampled, cv::Mat& grey) const {
  if (sampled.channels() == 1) {
    sampled.copyTo(grey);
  } else {
    cv::cvtColor(sampled, grey, cv::COLOR_BGR2GRAY);
  }
}

void ExpansionMeter::setReference(const cv::Mat& frame, const cv::Rect2f& box) {
  have_reference_ = false;
  const uchar* measured_frame = measured_frame_;  // valid for this call only
  measured_frame_ = nullptr;
  if (!boxHasPixels(box) || !(std::max(box.width, box.height) >= kMinBoxSide)) {
    return;
  }
  // Buffers for this frame's width and type (a large box is box-filtered from a frame row).
  sampler_.reserve(kPatchSide, kPatchSide, frame.type(), frame.cols);
  const float side = kContext * std::max(box.width, box.height);
  window_ = cv::Size2f(side, side);
  reference_size_ = std::sqrt(box.width * box.height);
  const float k = kPatchSide / side;
  const float rw = std::max(box.width * k * kRegionMargin, kMinRegionSide);
  const float rh = std::max(box.height * k * kRegionMargin, kMinRegionSide);
  const float c = 0.5f * kPatchSide;
  // The aligner reads one pixel around the region (gradients, bilinear steps).
  region_ = cv::Rect(cvRound(c - 0.5f * rw), cvRound(c - 0.5f * rh), cvRound(rw), cvRound(rh)) &
            cv::Rect(2, 2, kPatchSide - 4, kPatchSide - 4);
  const cv::Point2f centre = boxCentre(box);
  if (frame.data == measured_frame && centre == measured_centre_ && window_ == measured_window_) {
    // The box did not change size since measure(): its patch of this frame is the reference.
    cv::swap(reference_grey_, current_grey_);
  } else {
    sampler_.sample(frame, centre, window_, kPatchSide, kPatchSide, sampled_);
    toGrey(sampled_, reference_grey_);
  }
  have_reference_ = true;
}

ExpansionMeasurement ExpansionMeter::measure(const cv::Mat& frame, cv::Point2f centre) {
  ExpansionMeasurement m;
  if (!have_reference_ || !std::isfinite(centre.x) || !std::isfinite(centre.y)) return m;
  sampler_.sample(frame, centre, window_, kPatchSide, kPatchSide, sampled_);
  toGrey(sampled_, current_grey_);
  measured_frame_ = frame.data;
  measured_centre_ = centre;
  measured_window_ = window_;
  const ScaleEstimate e = align_.estimate(reference_grey_, current_grey_, region_);
  if (!e.valid) return m;
  m.valid = true;
  m.log_ratio = e.log_scale;
  m.sigma = std::max({kMinSigma, e.sigma, kOutlinePx / reference_size_});
  return m;
}

}  // namespace core
}  // namespace obstacle_tracker
