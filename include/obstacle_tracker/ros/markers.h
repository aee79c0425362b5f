// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// ~markers: each obstacle's bearing as an rviz arrow from the camera's origin in the array's
// target_frame, coloured by how soon it would reach the camera, so that an operator sees in the
// 3D view where the threats are and which is urgent. The bearing is a direction only (a
// monocular camera gives no range), so every arrow has the same length.
// Colours (RGB), so that a screenshot test can find them:
//   time to contact below kUrgentSeconds      red     (1, 0, 0)
//   below kCloseSeconds                      orange  (1, 0.5, 0)
//   not closing, or further away in time     cyan    (0, 1, 1)
// An obstacle that is not confirmed, or below confidence 0.5, is drawn at a third of the opacity.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include "obstacle_tracker/ObstacleArray.h"

namespace obstacle_tracker {
namespace bridge {

constexpr double kUrgentSeconds = 3.0;   // time to contact that calls for avoiding now
constexpr double kCloseSeconds = 10.0;   // closing, but with time to plan
constexpr double kArrowLength = 5.0;     // m in target_frame; display length only

// Fills `out` for `obstacles`: a DELETEALL marker that clears the previous frame's arrows, then
// one ARROW per obstacle with a bearing (namespace "bearings", id = the obstacle's id), with the
// array's header and a lifetime of `lifetime` seconds (so arrows vanish when frames stop coming).
void bearingMarkers(const ObstacleArray& obstacles, double lifetime,
                    visualization_msgs::MarkerArray& out);

}  // namespace bridge
}  // namespace obstacle_tracker
