// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Publishes synthetic frames (a bright disc drifting over a sky gradient, test/ros/synthetic_frames.h)
// on `image` with a matching `camera_info`, at ~rate Hz (default 10), ~width x ~height (640x480),
// ~frames in all (0: until shut down). Used by the rviz screenshot test.
#include <ros/ros.h>

#include "synthetic_frames.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "sky_publisher");
  ros::NodeHandle nh, pnh("~");
  double rate = 10.0;
  int width = 640, height = 480, frames = 0;
  std::string frame_id;
  pnh.param("rate", rate, rate);
  pnh.param("width", width, width);
  pnh.param("height", height, height);
  pnh.param("frames", frames, frames);
  pnh.param("frame_id", frame_id, std::string("camera_optical"));
  ros::Publisher image_pub = nh.advertise<sensor_msgs::Image>("image", 1);
  ros::Publisher info_pub = nh.advertise<sensor_msgs::CameraInfo>("camera_info", 1);
  ros::Rate loop(rate > 0.0 ? rate : 10.0);
  for (int i = 0; ros::ok() && (frames <= 0 || i < frames); ++i) {
    const sensor_msgs::Image image = obstacle_tracker::testing::toImageMsg(
        obstacle_tracker::testing::skyFrame(i, width, height), frame_id, ros::Time::now().toSec(),
        static_cast<std::uint32_t>(i));
    info_pub.publish(obstacle_tracker::testing::cameraInfo(image));
    image_pub.publish(image);
    ros::spinOnce();
    loop.sleep();
  }
  return 0;
}
