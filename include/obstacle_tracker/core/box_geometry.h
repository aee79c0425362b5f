// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Box geometry the core and the evaluation share: centre, a box of a size centred at a point,
// whether a box stands for "no target", intersection over union, whether a box is near the frame's
// edge, the test a box must pass before its pixels are read, and the pixels around a box.
#pragma once

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

inline cv::Point2f boxCentre(const cv::Rect2f& b) { return {b.x + 0.5f * b.width, b.y + 0.5f * b.height}; }

inline cv::Rect2f boxCentredAt(const cv::Point2f& c, const cv::Size2f& s) {
  return {c.x - 0.5f * s.width, c.y - 0.5f * s.height, s.width, s.height};
}

// The same in double, for code whose arithmetic is double (evaluation, camera rays, image
// alignment): pass cv::Rect2d(box) so each coordinate is widened before the sum and the float
// rounding of the helpers above does not enter. An integer cv::Rect matches neither overload
// exactly and does not compile: say which precision is meant.
inline cv::Point2d boxCentre(const cv::Rect2d& b) { return {b.x + 0.5 * b.width, b.y + 0.5 * b.height}; }

inline cv::Rect2d boxCentredAt(const cv::Point2d& c, const cv::Size2d& s) {
  return {c.x - 0.5 * s.width, c.y - 0.5 * s.height, s.width, s.height};
}

// True when a box stands for "no target": a NaN or an infinity anywhere, or a width or height <= 0.
inline bool boxIsAbsent(const cv::Rect2f& b) {
  // NaN compares false, so "!(w > 0)" also catches a NaN size.
  return std::isnan(b.x) || std::isnan(b.y) || !(b.width > 0.0f) || !(b.height > 0.0f) ||
         std::isinf(b.x) || std::isinf(b.y) || std::isinf(b.width) || std::isinf(b.height);
}

// Intersection over union in [0, 1]; 0 when either box is absent. Real is the arithmetic: float
// where the tracking loop compares boxes (its decisions follow these bits), double for the
// evaluation, whose scores must be the OTB toolkit's to stand beside published ones. Continuous
// boxes: the toolkit's pixel-inclusive formula (right = x + w - 1, width = right - left + 1)
// gives the same intersection and union.
template <typename Real = float>
Real boxIou(const cv::Rect2f& a, const cv::Rect2f& b) {
  if (boxIsAbsent(a) || boxIsAbsent(b)) return Real(0);
  const cv::Rect_<Real> ra(a), rb(b);
  const Real inter = (ra & rb).area();
  const Real uni = ra.area() + rb.area() - inter;
  return uni > Real(0) ? inter / uni : Real(0);
}

// True when the box is closer to a frame edge than its own size along that axis (its width from
// the left or right edge, its height from the top or bottom). The visible part of an object there
// may be cut by the edge, so a change of its size is not a change of the object's: a structure
// entering the view during a pan "grows" while it does not come closer.
inline bool boxNearFrameEdge(const cv::Rect2f& b, const cv::Size& frame) {
  return b.x < b.width || b.y < b.height || static_cast<float>(frame.width) - (b.x + b.width) < b.width ||
         static_cast<float>(frame.height) - (b.y + b.height) < b.height;
}

// Finite, and at least a pixel on each side.
inline bool boxHasPixels(const cv::Rect2f& b) {
  return std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.width) && std::isfinite(b.height) &&
         b.width >= 1.0f && b.height >= 1.0f;
}

// The pixels of box b grown by `margin` on every side, clipped to a frame of `size`: the low
// edges floored, the high ones ceiled, clamped in float first (a box far outside must not
// overflow an int).
inline cv::Rect grownPixelRect(const cv::Rect2f& b, float margin, const cv::Size& size) {
  const float fw = static_cast<float>(size.width), fh = static_cast<float>(size.height);
  auto clampX = [&](float v) { return static_cast<int>(std::min(std::max(v, 0.0f), fw)); };
  auto clampY = [&](float v) { return static_cast<int>(std::min(std::max(v, 0.0f), fh)); };
  return cv::Rect(cv::Point(clampX(std::floor(b.x - margin)), clampY(std::floor(b.y - margin))),
                  cv::Point(clampX(std::ceil(b.x + b.width + margin)), clampY(std::ceil(b.y + b.height + margin))));
}

}  // namespace core
}  // namespace obstacle_tracker
