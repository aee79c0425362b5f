// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The debug overlay of ~debug_image: each obstacle's box, id, confidence and state drawn on the
// frame. Colours (BGR) by state, so a screenshot test can find them:
//   tracking    pure green   (0, 255, 0)
//   redetecting orange       (0, 165, 255)
//   lost        red          (0, 0, 255)
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/types.h"

namespace obstacle_tracker {
namespace bridge {

cv::Scalar stateColour(core::TrackState state);

// frame: CV_8UC1 or CV_8UC3 (BGR). out: CV_8UC3 copy of the frame with the overlay drawn (the
// buffer is reused between calls). `status` is written in the top-left corner.
void drawOverlay(const cv::Mat& frame, const std::vector<core::Obstacle>& obstacles,
                 const std::string& status, cv::Mat& out);

}  // namespace bridge
}  // namespace obstacle_tracker
