// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Image-locked pixels from two motion hypotheses per pixel (overlay_mask.h). Every step is one of
// OpenCV's vectorised whole-image operations on 8-bit images (saturating arithmetic keeps the
// score within 0..255 without branches).
#include "obstacle_tracker/core/overlay_mask.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace obstacle_tracker {
namespace core {

namespace {

// Largest displacement of the motion over the frame's corners (working px).
double largestShift(const cv::Matx23d& a, cv::Size size) {
  double best = 0.0;
  for (const cv::Point2d p : {cv::Point2d(0, 0), cv::Point2d(size.width - 1, 0), cv::Point2d(0, size.height - 1),
                              cv::Point2d(size.width - 1, size.height - 1)}) {
    const double dx = a(0, 0) * p.x + a(0, 1) * p.y + a(0, 2) - p.x;
    const double dy = a(1, 0) * p.x + a(1, 1) * p.y + a(1, 2) - p.y;
    best = std::max(best, std::hypot(dx, dy));
  }
  return best;
}

}  // namespace

OverlayMask::OverlayMask(const OverlayMaskSettings& settings) : settings_(settings) {
  if (settings_.min_separation < 1 || !(settings_.locked_error_share > 0.0f && settings_.locked_error_share < 1.0f) ||
      settings_.moved_penalty < 1 || settings_.mask_score < 1 || settings_.max_score < settings_.mask_score ||
      settings_.max_score > 255 || !(settings_.min_background_shift >= 0.0)) {
    throw std::invalid_argument("OverlayMaskSettings: out of range");
  }
}

void OverlayMask::reset() {
  score_.release();
  mask_.release();
}

void OverlayMask::update(const cv::Mat& previous, const cv::Mat& current, const cv::Matx23d& previous_to_current) {
  if (previous.type() != CV_8UC1 || current.type() != CV_8UC1 || previous.size() != current.size() ||
      current.empty()) {
    throw std::invalid_argument("OverlayMask::update: two CV_8UC1 frames of one size");
  }
  if (score_.size() != current.size()) {
    score_ = cv::Mat::zeros(current.size(), CV_8U);
    mask_ = cv::Mat::zeros(current.size(), CV_8U);
  }
  if (largestShift(previous_to_current, current.size()) < settings_.min_background_shift) return;

  // The background hypothesis' prediction of the current frame. Pixels whose source lies outside
  // the previous frame, or next to its edge (bilinear interpolation there mixes in the border),
  // get no vote.
  cv::warpAffine(previous, warped_, previous_to_current, current.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  scratch_.create(previous.size(), CV_8U);
  scratch_.setTo(255);
  cv::warpAffine(scratch_, valid_, previous_to_current, current.size(), cv::INTER_NEAREST, cv::BORDER_CONSTANT);
  cv::erode(valid_, valid_, cv::Mat(), cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));

  cv::absdiff(warped_, previous, separation_);
  cv::absdiff(current, previous, locked_error_);
  cv::absdiff(current, warped_, moved_error_);
  cv::compare(separation_, settings_.min_separation, separable_, cv::CMP_GE);
  cv::bitwise_and(separable_, valid_, separable_);

  // Explained by the image-locked hypothesis: its error well under the background's error and
  // under the separation.
  const double share = settings_.locked_error_share;
  moved_error_.convertTo(scratch_, CV_8U, share);
  cv::compare(locked_error_, scratch_, locked_, cv::CMP_LT);
  separation_.convertTo(scratch_, CV_8U, share);
  cv::compare(locked_error_, scratch_, scratch_, cv::CMP_LT);
  cv::bitwise_and(locked_, scratch_, locked_);
  cv::bitwise_and(locked_, separable_, locked_);
  cv::bitwise_xor(separable_, locked_, separable_);  // now: the "moved" votes
  // A locked vote counts only on an edge of the current frame. Inside a uniform region, e.g. a
  // plain target sliding along its long axis or held centred by a following camera, "unchanged"
  // says nothing about how the region moves (the aperture problem); an overlay's strokes and
  // lines are edges throughout.
  cv::morphologyEx(current, scratch_, cv::MORPH_GRADIENT, cv::Mat());
  cv::compare(scratch_, settings_.min_separation, edges_, cv::CMP_GE);
  cv::bitwise_and(locked_, edges_, locked_);

  cv::add(score_, cv::Scalar(1), score_, locked_);
  cv::subtract(score_, cv::Scalar(settings_.moved_penalty), score_, separable_);
  cv::min(score_, cv::Scalar(settings_.max_score), score_);
  cv::compare(score_, settings_.mask_score, mask_, cv::CMP_GE);
  // Grown by a pixel: an overlay's anti-aliased rim separates less than its core.
  cv::dilate(mask_, mask_, cv::Mat());
}

double OverlayMask::share(const cv::Rect& box) const {
  if (mask_.empty()) return 0.0;
  const cv::Rect r = box & cv::Rect(0, 0, mask_.cols, mask_.rows);
  if (r.area() <= 0) return 0.0;
  return static_cast<double>(cv::countNonZero(mask_(r))) / r.area();
}

}  // namespace core
}  // namespace obstacle_tracker
