// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// obstacle_tracker_node: the ObstacleTrackerNodelet in its own process (no nodelet manager, no
// pluginlib lookup). Same topics, parameters and remappings as the nodelet:
//   rosrun obstacle_tracker obstacle_tracker_node image:=/camera/image_raw _use_camera_info:=true
#include <ros/ros.h>

#include "obstacle_tracker/ros/obstacle_tracker_nodelet.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "obstacle_tracker");
  obstacle_tracker::ObstacleTrackerNodelet nodelet;
  // Remappings given on the command line apply to the nodelet's handles as they would in a
  // manager; the nodelet's private namespace is this node's.
  nodelet.init(ros::this_node::getName(), ros::names::getRemappings(), nodelet::V_string());
  // Image, camera_info, dynamic_reconfigure and diagnostics callbacks on separate threads: a
  // parameter change never waits for a frame in the queue.
  ros::MultiThreadedSpinner spinner(2);
  spinner.spin();
  return 0;
}
