// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Core <-> ROS: parameters (ROS parameter server and dynamic_reconfigure, under the core's names)
// and obstacle messages.
#pragma once

#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "obstacle_tracker/Obstacle.h"
#include "obstacle_tracker/ObstacleTrackerConfig.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/types.h"

namespace obstacle_tracker {
namespace bridge {

// Reads every core parameter that is set in `nh`'s namespace (same names as params.h), on top of
// `base`. Values go through core::setParam: out-of-range values are clamped, NaN / non-numeric
// values are refused; each such case appends a message naming the parameter and its range.
core::Params paramsFromRos(const ros::NodeHandle& nh, const core::Params& base,
                           std::vector<std::string>* messages);

// dynamic_reconfigure config -> Params, by name (every core parameter the config holds), with the
// same checks. Parameters of the config that are not core parameters are ignored.
core::Params paramsFromConfig(const ObstacleTrackerConfig& config, const core::Params& base,
                              std::vector<std::string>* messages);

// Params -> dynamic_reconfigure config, by name, on top of `base`.
ObstacleTrackerConfig configFromParams(const core::Params& params, const ObstacleTrackerConfig& base);

// Core parameter names that the dynamic_reconfigure config does not hold (should be empty:
// config/ObstacleTracker.cfg is generated from params.h).
std::vector<std::string> paramsMissingFromConfig();

std::uint8_t toMessageState(core::TrackState state);

// Box, id, confidence, peak, PSR, state, expansion rate and time to contact. Geometry fields are
// left for the caller (has_bearing = false).
void toMessage(const core::Obstacle& obstacle, obstacle_tracker::Obstacle& msg);

}  // namespace bridge
}  // namespace obstacle_tracker
