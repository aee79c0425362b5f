// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Part of the bad-input rostest (bad_input.test, node reliability_bad_input): bad camera_info
// (zeros, NaN, 100 distortion coefficients, an unknown model, binning and roi beyond the image)
// and a missing tf into the tracker that computes bearings (tracker_geo). Frames must keep
// flowing, with bearings left out, until a valid camera_info and the transform arrive.
#include <array>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <opencv2/core.hpp>

#include "bad_input_harness.h"
#include "obstacle_tracker/ros/camera_geometry.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace rel = obstacle_tracker::reliability;
using rel::ctx;
using rel::kNan;
using rel::logCount;
using rel::logsSince;
using rel::managerAlive;
using rel::waitForTrackers;
using rel::waitLogged;

TEST(BadGeometry, BadCameraInfoAndMissingTfLeaveBearingsOutWithoutBlocking) {
  ASSERT_TRUE(waitForTrackers()) << "the trackers did not come up";
  // tracker_geo: use_camera_info true, target_frame "world" (no tf until the end of this test).
  auto goodInfo = [](const ros::Time& stamp) {
    // Principal point (160, 120), not the pixel-centre image centre (159.5, 119.5).
    sensor_msgs::CameraInfo info = obstacle_tracker::bridge::pinholeCameraInfo(320, 240, 300.0, 160.0, 120.0);
    info.header.stamp = stamp;
    info.header.frame_id = "camera";
    return info;
  };
  // Frames of a generated scene (an aircraft crossing the sky): the tracker finds
  // it, so bearings can be checked. Played in a loop, one frame per pair.
  std::vector<sensor_msgs::Image> scene;
  {
    auto gen = obstacle_tracker::scene::makeScenario("crossing", 3, 120, cv::Size(320, 240));
    cv::Mat frame;
    for (int i = 0; i < gen.frameCount(); ++i) {
      gen.renderFrame(i, frame);
      sensor_msgs::Image img;
      img.width = 320;
      img.height = 240;
      img.encoding = "bgr8";
      img.step = 320 * 3;
      img.data.assign(frame.data, frame.data + frame.total() * frame.elemSize());
      img.header.frame_id = "camera";
      scene.push_back(img);
    }
  }
  std::size_t next_frame = 0;
  // Runs `frames` synchronised pairs; returns (outputs received, outputs with obstacles, with bearings).
  auto run = [&](const std::string& what, int frames,
                 const std::function<void(sensor_msgs::CameraInfo&)>& spoil) {
    int outputs = 0, with_obstacles = 0, with_bearing = 0;
    for (int i = 0; i < frames; ++i) {
      sensor_msgs::Image img = scene[next_frame++ % scene.size()];
      img.header.stamp = ros::Time::now();
      img.header.frame_id = "camera";
      sensor_msgs::CameraInfo info = goodInfo(img.header.stamp);
      spoil(info);
      ctx->geo_info_pub.publish(info);
      ctx->geo_image_pub.publish(img);
      auto out = ctx->geo_out.waitFor(img.header.stamp, 2.0);
      if (!out) continue;
      ++outputs;
      EXPECT_EQ(rel::checkOutput(*out), "") << what;
      if (!out->obstacles.empty()) ++with_obstacles;
      for (const auto& o : out->obstacles) with_bearing += o.has_bearing ? 1 : 0;
    }
    EXPECT_TRUE(managerAlive()) << what;
    std::printf("camera_info phase '%s': %d frames, %d outputs, %d with obstacles, %d bearings\n", what.c_str(),
                frames, outputs, with_obstacles, with_bearing);
    return std::array<int, 3>{outputs, with_obstacles, with_bearing};
  };
  const int n = 40;
  auto zeros = run("camera_info of zeros", n, [](sensor_msgs::CameraInfo& i) {
    i.K = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    i.P = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    i.D.clear();
    i.width = i.height = 0;
  });
  EXPECT_GE(zeros[0], n / 2) << "outputs stopped with a zero camera_info";
  EXPECT_EQ(zeros[2], 0) << "bearings from a zero camera_info";
  const std::size_t nan_logs = logCount();
  auto nans = run("camera_info with NaN", n, [](sensor_msgs::CameraInfo& i) {
    i.K[0] = kNan;
    i.K[4] = kNan;
    i.D[0] = kNan;
  });
  EXPECT_GE(nans[0], n / 2);
  EXPECT_EQ(nans[2], 0) << "bearings from a NaN camera_info";
  // The same bad camera_info on every frame is reported once, not at camera rate.
  EXPECT_LE(logsSince(nan_logs, "camera_info unusable"), 2) << "an unchanged NaN camera_info is re-logged every frame";
  auto bad_d = run("camera_info with 100 distortion coefficients", n / 2,
                   [](sensor_msgs::CameraInfo& i) { i.D.assign(100, 0.1); });
  EXPECT_GE(bad_d[0], n / 4);
  auto odd_model = run("unknown distortion model", n / 2, [](sensor_msgs::CameraInfo& i) {
    i.distortion_model = "no_such_model";
    i.D = {0.1, 0.2, 0.0, 0.0, 0.0};
  });
  EXPECT_GE(odd_model[0], n / 4);
  auto binning0 = run("binning and roi beyond the image", n / 2, [](sensor_msgs::CameraInfo& i) {
    i.binning_x = 0;
    i.roi.x_offset = 100000;
    i.roi.width = 5;
  });
  EXPECT_GE(binning0[0], n / 4);
  // A valid camera_info but no transform to "world": bearings left out, frames still flow.
  auto no_tf = run("missing tf", n, [](sensor_msgs::CameraInfo&) {});
  EXPECT_GE(no_tf[0], n / 2) << "a missing tf blocked the outputs";
  EXPECT_EQ(no_tf[2], 0) << "bearings without a transform to target_frame";
  EXPECT_GT(no_tf[1] + zeros[1] + nans[1], 0) << "no obstacle found at all: the checks above prove nothing";
  EXPECT_TRUE(waitLogged({"world"}, 5.0)) << "no /rosout message about the missing transform";
  // Now the transform arrives: bearings appear (the positive control of the checks above).
  tf2_ros::StaticTransformBroadcaster broadcaster;
  geometry_msgs::TransformStamped tf;
  tf.header.stamp = ros::Time(0);
  tf.header.frame_id = "world";
  tf.child_frame_id = "camera";
  tf.transform.rotation.w = 1.0;
  broadcaster.sendTransform(tf);
  ros::WallDuration(1.0).sleep();
  auto with_tf = run("with tf", n, [](sensor_msgs::CameraInfo&) {});
  EXPECT_GE(with_tf[0], n / 2);
  EXPECT_GT(with_tf[2], 0) << "no bearing even with a valid camera_info and tf";
}
