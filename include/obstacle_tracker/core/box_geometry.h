// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Box geometry the core shares: centre, a box of a size centred at a point, intersection over
// union (float, as the tracking loop compares boxes; the evaluation's own iou in metrics.h is the
// OTB toolkit's double-precision one), the test a box must pass before its pixels are read, and
// the pixels around a box.
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

inline float boxIou(const cv::Rect2f& a, const cv::Rect2f& b) {
  const float inter = (a & b).area();
  const float uni = a.area() + b.area() - inter;
  return uni > 0.0f ? inter / uni : 0.0f;
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
