// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// A salient region as the saliency detector (saliency.h), the region extractor
// (region_extractor.h) and the auto-initialiser (auto_init.h) report it.
#pragma once

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

struct SalientRegion {
  cv::Rect2f box;               // full-frame pixel coordinates
  float area = 0.0f;            // region pixels, in full-frame pixels^2
  float mean_saliency = 0.0f;   // [0, 1]
  float score = 0.0f;           // ranking score, higher is better (documented in region_extractor.cpp)
  bool touches_border = false;  // touches the frame (or window) border
};

}  // namespace core
}  // namespace obstacle_tracker
