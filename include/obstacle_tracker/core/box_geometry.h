// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Box geometry the core shares: centre, a box of a size centred at a point, intersection over
// union (float, as the tracking loop compares boxes; the evaluation's own iou in metrics.h is the
// OTB toolkit's double-precision one).
#pragma once

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

}  // namespace core
}  // namespace obstacle_tracker
