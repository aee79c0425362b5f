// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/ros/markers.h"

#include <cmath>

namespace obstacle_tracker {
namespace bridge {

namespace {

std_msgs::ColorRGBA colourOf(const Obstacle& o) {
  std_msgs::ColorRGBA c;
  const double ttc = o.time_to_contact;
  const bool closing = std::isfinite(ttc) && ttc > 0.0;
  if (closing && ttc < kUrgentSeconds) {
    c.r = 1.0f, c.g = 0.0f, c.b = 0.0f;
  } else if (closing && ttc < kCloseSeconds) {
    c.r = 1.0f, c.g = 0.5f, c.b = 0.0f;
  } else {
    c.r = 0.0f, c.g = 1.0f, c.b = 1.0f;
  }
  // A planner acts on confirmed obstacles with confidence >= 0.5 (Obstacle.msg): the others are
  // shown, but faintly.
  c.a = o.confirmed && o.confidence >= 0.5f ? 1.0f : 0.33f;
  return c;
}

}  // namespace

void bearingMarkers(const ObstacleArray& obstacles, double lifetime,
                    visualization_msgs::MarkerArray& out) {
  out.markers.clear();
  visualization_msgs::Marker clear;
  clear.header = obstacles.header;
  clear.header.frame_id = obstacles.target_frame;
  clear.ns = "bearings";
  clear.action = visualization_msgs::Marker::DELETEALL;
  out.markers.push_back(clear);
  for (const Obstacle& o : obstacles.obstacles) {
    if (!o.has_bearing) continue;
    visualization_msgs::Marker m;
    m.header = clear.header;
    m.ns = clear.ns;
    m.id = static_cast<int>(o.id);
    m.type = visualization_msgs::Marker::ARROW;
    m.action = visualization_msgs::Marker::ADD;
    m.pose.orientation.w = 1.0;
    geometry_msgs::Point from, to;
    to.x = kArrowLength * o.bearing.x;
    to.y = kArrowLength * o.bearing.y;
    to.z = kArrowLength * o.bearing.z;
    m.points = {from, to};
    m.scale.x = 0.05;  // shaft diameter, m
    m.scale.y = 0.15;  // head diameter, m
    m.scale.z = 0.3;   // head length, m
    m.color = colourOf(o);
    m.lifetime = ros::Duration(lifetime);
    out.markers.push_back(m);
  }
}

}  // namespace bridge
}  // namespace obstacle_tracker
