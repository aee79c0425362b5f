// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The overlay: each obstacle's box, id, confidence, state and time to contact drawn on the frame.
// One drawing for the nodelet's ~debug_image (what rviz shows) and track_sequence --overlay, which
// adds the ground-truth box and its frame number. Colours (BGR) by state, so a screenshot test can
// find them:
//   tracking    pure green   (0, 255, 0)
//   redetecting orange       (0, 165, 255)
//   lost        red          (0, 0, 255)
//   searching   cyan         (255, 255, 0)
// The ground truth is white (255, 255, 255), thinner than the obstacles' boxes and beneath them.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/types.h"

namespace obstacle_tracker {
namespace core {

cv::Scalar stateColour(TrackState state);

// What is drawn beside the obstacles; the defaults draw nothing more.
struct OverlayExtras {
  // White on black in the top-left corner (empty: no banner).
  std::string status;
  // Drawn when present (core::boxIsAbsent is false): the evaluation's ground truth.
  cv::Rect2f ground_truth{0.0f, 0.0f, 0.0f, 0.0f};
};

// frame: CV_8UC1 or CV_8UC3 (BGR). out: CV_8UC3 copy of the frame with the overlay drawn (the
// buffer is reused between calls).
void drawOverlay(const cv::Mat& frame, const std::vector<Obstacle>& obstacles, const OverlayExtras& extras,
                 cv::Mat& out);

}  // namespace core
}  // namespace obstacle_tracker
