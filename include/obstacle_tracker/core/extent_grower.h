// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// ExtentGrower: from the bright core that saliency finds of a small or blurred object to the
// object's visible extent (extent_contrast).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/mat_arena.h"

namespace obstacle_tracker {
namespace core {

// Grows a box found by saliency to the object's visible extent. Otsu's level lies halfway
// between object and background, so on a small or blurred target (a drone of 10x6 px in
// infrared, the thin wings of an aircraft) the salient region is the bright core, while the
// object (and the box a human draws around it) reaches out to where its contrast fades into the
// background. In a window of the core box plus max(6 px, its longer side) on each side:
//   background = per-channel median of the window's outer 2-pixel ring;
//   contrast c = max over channels of |pixel - background|; noise = 1.4826 x median(c) on the ring;
//   object = the 8-connected pixels with c > max(contrast x the 90th percentile of c in the core,
//            3 x noise, 2 grey levels) that are connected to a core pixel above that level.
// The result is the union of the core box and the object's box. The core box comes back
// unchanged when the object reaches the window's edge (it is joined to background structure or
// leaves the frame), when the result would cover more than 4x the core's area, or when the core
// does not stand out of the noise. No heap allocation once the largest window was seen.
class ExtentGrower {
 public:
  // frame: CV_8UC1 or CV_8UC3; contrast: the share of the core's contrast that still counts as
  // object (extent_contrast; <= 0 returns the core unchanged).
  cv::Rect2f grow(const cv::Mat& frame, const cv::Rect2f& core, double contrast);

 private:
  bool growRegion(cv::Mat& c, const cv::Rect& core, int threshold, cv::Rect& bounds);

  MatArena contrast_arena_;
  std::vector<int> queue_;
};

}  // namespace core
}  // namespace obstacle_tracker
