// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Part of the bad-input rostest (bad_input.test, node reliability_bad_input): bad camera_info
// (zeros, NaN, 100 distortion coefficients, an unknown model, binning and roi beyond the image)
// and a missing tf into the tracker that computes bearings (tracker_geo). Frames must keep
// flowing, with bearings left out, until a valid camera_info and the transform arrive.
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Header.h>
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

namespace {

// The camera_info every phase starts from: principal point (160, 120), not the pixel-centre image
// centre (159.5, 119.5).
sensor_msgs::CameraInfo goodInfo(const ros::Time& stamp) {
  sensor_msgs::CameraInfo info = obstacle_tracker::bridge::pinholeCameraInfo(320, 240, 300.0, 160.0, 120.0);
  info.header.stamp = stamp;
  info.header.frame_id = "camera";
  return info;
}

// What one phase received: outputs, outputs with obstacles, obstacles with a bearing.
struct PhaseCounts {
  int outputs = 0;
  int with_obstacles = 0;
  int with_bearing = 0;
};

// Frames of a generated scene (an aircraft crossing the sky, which the tracker finds, so bearings
// can be checked), sent with a camera_info each to tracker_geo, played in a loop.
class GeometryPhases {
 public:
  GeometryPhases() {
    auto gen = obstacle_tracker::scene::makeScenario("crossing", 3, 120, cv::Size(320, 240));
    cv::Mat frame;
    std_msgs::Header header;
    header.frame_id = "camera";
    for (int i = 0; i < gen.frameCount(); ++i) {
      gen.renderFrame(i, frame);
      scene_.push_back(*cv_bridge::CvImage(header, "bgr8", frame).toImageMsg());
    }
  }

  // `frames` synchronised pairs whose camera_info `spoil` changed.
  PhaseCounts run(const std::string& what, int frames, const std::function<void(sensor_msgs::CameraInfo&)>& spoil) {
    PhaseCounts counts;
    for (int i = 0; i < frames; ++i) {
      sensor_msgs::Image img = scene_[next_frame_++ % scene_.size()];
      img.header.stamp = ros::Time::now();
      sensor_msgs::CameraInfo info = goodInfo(img.header.stamp);
      spoil(info);
      ctx->geo_info_pub.publish(info);
      ctx->geo_image_pub.publish(img);
      auto out = ctx->geo_out.waitFor(img.header.stamp, 2.0);
      if (!out) continue;
      ++counts.outputs;
      EXPECT_EQ(rel::checkOutput(*out), "") << what;
      if (!out->obstacles.empty()) ++counts.with_obstacles;
      for (const auto& o : out->obstacles) counts.with_bearing += o.has_bearing ? 1 : 0;
    }
    EXPECT_TRUE(managerAlive()) << what;
    std::printf("camera_info phase '%s': %d frames, %d outputs, %d with obstacles, %d bearings\n", what.c_str(),
                frames, counts.outputs, counts.with_obstacles, counts.with_bearing);
    return counts;
  }

 private:
  std::vector<sensor_msgs::Image> scene_;
  std::size_t next_frame_ = 0;
};

void publishWorldToCamera(tf2_ros::StaticTransformBroadcaster& broadcaster) {
  geometry_msgs::TransformStamped tf;
  tf.header.stamp = ros::Time(0);
  tf.header.frame_id = "world";
  tf.child_frame_id = "camera";
  tf.transform.rotation.w = 1.0;
  broadcaster.sendTransform(tf);
}

}  // namespace

TEST(BadGeometry, BadCameraInfoAndMissingTfLeaveBearingsOutWithoutBlocking) {
  ASSERT_TRUE(waitForTrackers()) << "the trackers did not come up";
  // tracker_geo: use_camera_info true, target_frame "world" (no tf until the end of this test).
  GeometryPhases phases;
  const int n = 40;
  const PhaseCounts zeros = phases.run("camera_info of zeros", n, [](sensor_msgs::CameraInfo& i) {
    i.K = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    i.P = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    i.D.clear();
    i.width = i.height = 0;
  });
  EXPECT_GE(zeros.outputs, n / 2) << "outputs stopped with a zero camera_info";
  EXPECT_EQ(zeros.with_bearing, 0) << "bearings from a zero camera_info";
  const std::size_t nan_logs = logCount();
  const PhaseCounts nans = phases.run("camera_info with NaN", n, [](sensor_msgs::CameraInfo& i) {
    i.K[0] = kNan;
    i.K[4] = kNan;
    i.D[0] = kNan;
  });
  EXPECT_GE(nans.outputs, n / 2);
  EXPECT_EQ(nans.with_bearing, 0) << "bearings from a NaN camera_info";
  // The same bad camera_info on every frame is reported once, not at camera rate.
  EXPECT_LE(logsSince(nan_logs, "camera_info unusable"), 2) << "an unchanged NaN camera_info is re-logged every frame";
  const PhaseCounts bad_d = phases.run("camera_info with 100 distortion coefficients", n / 2,
                                       [](sensor_msgs::CameraInfo& i) { i.D.assign(100, 0.1); });
  EXPECT_GE(bad_d.outputs, n / 4);
  const PhaseCounts odd_model = phases.run("unknown distortion model", n / 2, [](sensor_msgs::CameraInfo& i) {
    i.distortion_model = "no_such_model";
    i.D = {0.1, 0.2, 0.0, 0.0, 0.0};
  });
  EXPECT_GE(odd_model.outputs, n / 4);
  const PhaseCounts binning0 = phases.run("binning and roi beyond the image", n / 2, [](sensor_msgs::CameraInfo& i) {
    i.binning_x = 0;
    i.roi.x_offset = 100000;
    i.roi.width = 5;
  });
  EXPECT_GE(binning0.outputs, n / 4);
  // A valid camera_info but no transform to "world": bearings left out, frames still flow.
  const PhaseCounts no_tf = phases.run("missing tf", n, [](sensor_msgs::CameraInfo&) {});
  EXPECT_GE(no_tf.outputs, n / 2) << "a missing tf blocked the outputs";
  EXPECT_EQ(no_tf.with_bearing, 0) << "bearings without a transform to target_frame";
  EXPECT_GT(no_tf.with_obstacles + zeros.with_obstacles + nans.with_obstacles, 0)
      << "no obstacle found at all: the checks above prove nothing";
  EXPECT_TRUE(waitLogged({"world"}, 5.0)) << "no /rosout message about the missing transform";
  // Now the transform arrives: bearings appear (the positive control of the checks above).
  tf2_ros::StaticTransformBroadcaster broadcaster;
  publishWorldToCamera(broadcaster);
  ros::WallDuration(1.0).sleep();
  const PhaseCounts with_tf = phases.run("with tf", n, [](sensor_msgs::CameraInfo&) {});
  EXPECT_GE(with_tf.outputs, n / 2);
  EXPECT_GT(with_tf.with_bearing, 0) << "no bearing even with a valid camera_info and tf";
}
