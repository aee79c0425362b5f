// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// ~markers without a master: one arrow per obstacle with a bearing, in the array's target_frame
// and stamp, after a DELETEALL; colour by time to contact, faint when not to be acted on.
#include <limits>

#include <gtest/gtest.h>

#include "obstacle_tracker/ros/markers.h"

namespace ob = obstacle_tracker::bridge;
using obstacle_tracker::Obstacle;
using obstacle_tracker::ObstacleArray;
using visualization_msgs::Marker;

namespace {

Obstacle obstacle(unsigned id, float ttc, bool bearing = true) {
  Obstacle o;
  o.id = id;
  o.confirmed = true;
  o.confidence = 0.9f;
  o.has_bearing = bearing;
  o.bearing.x = 0.6;
  o.bearing.y = 0.0;
  o.bearing.z = 0.8;
  o.time_to_contact = ttc;
  return o;
}

}  // namespace

TEST(Markers, OneArrowPerBearingInTheTargetFrameAfterAClear) {
  ObstacleArray a;
  a.header.frame_id = "camera_optical";
  a.header.stamp = ros::Time(12, 500);
  a.target_frame = "base_link";
  a.obstacles = {obstacle(4, std::numeric_limits<float>::infinity()), obstacle(7, 2.0f, false),
                 obstacle(9, 5.0f)};
  visualization_msgs::MarkerArray out;
  ob::bearingMarkers(a, 0.5, out);
  ASSERT_EQ(out.markers.size(), 3u);
  EXPECT_EQ(out.markers[0].action, Marker::DELETEALL);
  for (const Marker& m : out.markers) {
    EXPECT_EQ(m.header.frame_id, "base_link");
    EXPECT_EQ(m.header.stamp, a.header.stamp);
    EXPECT_EQ(m.ns, "bearings");
  }
  const Marker& arrow = out.markers[1];
  EXPECT_EQ(arrow.type, Marker::ARROW);
  EXPECT_EQ(arrow.id, 4);
  ASSERT_EQ(arrow.points.size(), 2u);
  EXPECT_DOUBLE_EQ(arrow.points[0].x, 0.0);
  EXPECT_DOUBLE_EQ(arrow.points[1].x, ob::kArrowLength * 0.6);
  EXPECT_DOUBLE_EQ(arrow.points[1].z, ob::kArrowLength * 0.8);
  EXPECT_DOUBLE_EQ(arrow.lifetime.toSec(), 0.5);
  EXPECT_EQ(out.markers[2].id, 9);  // obstacle 7 has no bearing: no arrow
}

TEST(Markers, ColourSaysHowSoonAndOpacityWhetherToAct) {
  ObstacleArray a;
  a.obstacles = {obstacle(1, 1.5f), obstacle(2, 6.0f), obstacle(3, 40.0f),
                 obstacle(4, std::numeric_limits<float>::infinity()), obstacle(5, -3.0f),
                 obstacle(6, 1.5f), obstacle(7, 1.5f)};
  a.obstacles[5].confirmed = false;
  a.obstacles[6].confidence = 0.4f;
  visualization_msgs::MarkerArray out;
  ob::bearingMarkers(a, 0.5, out);
  ASSERT_EQ(out.markers.size(), 8u);
  auto rgb = [&](int i) {
    const auto& c = out.markers[static_cast<size_t>(i) + 1].color;
    return std::vector<float>{c.r, c.g, c.b};
  };
  EXPECT_EQ(rgb(0), (std::vector<float>{1.0f, 0.0f, 0.0f}));  // urgent
  EXPECT_EQ(rgb(1), (std::vector<float>{1.0f, 0.5f, 0.0f}));  // closing
  for (int i : {2, 3, 4}) EXPECT_EQ(rgb(i), (std::vector<float>{0.0f, 1.0f, 1.0f})) << i;
  EXPECT_FLOAT_EQ(out.markers[1].color.a, 1.0f);
  EXPECT_LT(out.markers[6].color.a, 0.5f);  // not confirmed
  EXPECT_LT(out.markers[7].color.a, 0.5f);  // below the planner's threshold
}

TEST(Markers, NoObstaclesStillClearsTheLastArrows) {
  ObstacleArray a;
  a.target_frame = "camera_optical";
  visualization_msgs::MarkerArray out;
  ob::bearingMarkers(a, 0.5, out);
  ASSERT_EQ(out.markers.size(), 1u);
  EXPECT_EQ(out.markers[0].action, Marker::DELETEALL);
}
