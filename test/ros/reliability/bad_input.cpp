// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Rostest (bad_input.test): a real nodelet manager with two ObstacleTrackerNodelets, fed every
// kind of bad input: unsupported encodings, empty / tiny / thin / 8000x8000 images,
// data shorter than step x height, step shorter than a row, sizes whose step x height overflows
// 32 bits, odd 16-bit steps, duplicate / backward / jumping / zero stamps, flat frames, 32FC1
// full of NaN; bad parameters at startup (launch file) and through dynamic_reconfigure; bad
// camera_info and a missing tf (bad_geometry.cpp). After each bad input the next good frame must
// give an ObstacleArray and the manager must still be alive; refusals must be logged and counted
// in the diagnostics. The harness (connections, logs, checks) is bad_input_harness.h.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <ros/topic.h>
#include <sensor_msgs/Image.h>

#include "bad_input_harness.h"
#include "obstacle_tracker/core/params.h"

namespace rel = obstacle_tracker::reliability;
using rel::ctx;
using rel::diagnosticValue;
using rel::Expect;
using rel::goodFrameProcessed;
using rel::kInf;
using rel::kNan;
using rel::managerAlive;
using rel::rawImage;
using rel::sendBad;
using rel::waitForTrackers;
using rel::waitLogged;

TEST(BadInput, ManagerAndTrackersAreUp) {
  waitForTrackers();
  ASSERT_GT(ctx->image_pub.getNumSubscribers(), 0u);
  ASSERT_GT(ctx->out_sub.getNumPublishers(), 0u);
  ASSERT_GT(ctx->manager_pid, 0) << "cannot get the manager's pid through XML-RPC getPid";
  ASSERT_TRUE(managerAlive());
  ASSERT_TRUE(goodFrameProcessed("start"));
}

TEST(BadInput, StartupParametersWereValidated) {
  // bad_input.test sets NaN, -5, 1e9, inf, a string and 1e12 on the parameter server. The values
  // in use are published (latched) by dynamic_reconfigure.
  auto config = ros::topic::waitForMessage<dynamic_reconfigure::Config>("/tracker/parameter_updates", *ctx->nh,
                                                                         ros::Duration(10.0));
  ASSERT_TRUE(config != nullptr);
  std::map<std::string, double> v;
  for (const auto& d : config->doubles) v[d.name] = d.value;
  for (const auto& i : config->ints) v[i.name] = i.value;
  const obstacle_tracker::core::Params defaults;
  EXPECT_DOUBLE_EQ(v["peak_threshold"], defaults.peak_threshold) << "NaN must be refused (default kept)";
  EXPECT_DOUBLE_EQ(v["search_window_scale"], 1.0) << "-5 must be clamped to the minimum";
  EXPECT_EQ(v["max_obstacles"], 16) << "1e9 must be clamped to the maximum";
  EXPECT_DOUBLE_EQ(v["kcf_lambda"], 1.0) << "inf must be clamped to the maximum";
  EXPECT_EQ(v["detection_interval"], defaults.detection_interval) << "a string must be refused (default kept)";
  EXPECT_EQ(v["saliency_max_side"], 4096) << "1e12 must be clamped to the maximum";
  EXPECT_DOUBLE_EQ(v["merge_iou"], 0.0) << "-inf must be clamped to the minimum";
  EXPECT_TRUE(goodFrameProcessed("startup parameters"));
}

TEST(BadInput, UnsupportedEncodingsAreRefused) {
  // 32FC1 full of NaN (a depth or radiometric thermal image).
  sensor_msgs::Image f32 = rawImage(64, 48, "32FC1", 64 * 4, 64 * 48 * 4);
  for (std::size_t i = 0; i < f32.data.size(); i += 4) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&f32.data[i], &nan, 4);
  }
  sendBad("32FC1 NaN", f32, Expect::kRefused);
  sendBad("32FC3", rawImage(64, 48, "32FC3", 64 * 12, 64 * 48 * 12), Expect::kRefused);
  sendBad("64FC1", rawImage(64, 48, "64FC1", 64 * 8, 64 * 48 * 8), Expect::kRefused);
  sendBad("16SC1", rawImage(64, 48, "16SC1", 64 * 2, 64 * 48 * 2), Expect::kRefused);
  sendBad("8SC1", rawImage(64, 48, "8SC1", 64, 64 * 48), Expect::kRefused);
  sendBad("8UC2", rawImage(64, 48, "8UC2", 128, 64 * 48 * 2), Expect::kRefused);
  sendBad("misspelt", rawImage(64, 48, "mono_8", 64, 64 * 48), Expect::kRefused);
  sendBad("upper case", rawImage(64, 48, "MONO8", 64, 64 * 48), Expect::kRefused);
  sendBad("empty encoding", rawImage(64, 48, "", 64, 64 * 48), Expect::kRefused);
  sendBad("jpeg", rawImage(64, 48, "jpeg", 64, 64 * 48), Expect::kRefused);
  EXPECT_TRUE(waitLogged({"unsupported image encoding"}, 5.0)) << "no /rosout message for an unsupported encoding";
}

TEST(BadInput, DegenerateSizesAreRefusedOrProcessed) {
  sendBad("mono8 0x0", rawImage(0, 0, "mono8", 0, 0), Expect::kRefused);
  sendBad("mono8 0x48", rawImage(0, 48, "mono8", 0, 0), Expect::kRefused);
  sendBad("mono8 1x1", rawImage(1, 1, "mono8", 1, 1, 200), Expect::kProcessed);
  sendBad("mono8 2x2", rawImage(2, 2, "mono8", 2, 4, 7), Expect::kProcessed);
  sendBad("bgr8 2x2", rawImage(2, 2, "bgr8", 6, 12, 250), Expect::kProcessed);
  sendBad("mono8 4000x1", rawImage(4000, 1, "mono8", 4000, 4000, 90), Expect::kProcessed);
  sendBad("mono8 1x4000", rawImage(1, 4000, "mono8", 1, 4000, 90), Expect::kProcessed);
  sendBad("bgr8 4000x2", rawImage(4000, 2, "bgr8", 12000, 24000, 90), Expect::kProcessed);
  sendBad("bayer_rggb8 1x1", rawImage(1, 1, "bayer_rggb8", 1, 1), Expect::kEither);
  sendBad("bayer_rggb8 3x3", rawImage(3, 3, "bayer_rggb8", 3, 9), Expect::kProcessed);
  sendBad("rgba16 2x2", rawImage(2, 2, "rgba16", 16, 32), Expect::kProcessed);
  sensor_msgs::Image huge = rel::squareImage(8000, 8000, 3900, 3900, 200);
  huge.header.frame_id = "camera";
  sendBad("mono8 8000x8000", huge, Expect::kProcessed, false, 60.0);
  sendBad("mono8 70000x1 (too large)", rawImage(70000, 1, "mono8", 70000, 70000), Expect::kRefused);
}

TEST(BadInput, InconsistentStepAndDataAreRefused) {
  sendBad("data shorter than step x height", rawImage(64, 48, "mono8", 64, 64 * 48 - 1), Expect::kRefused);
  sendBad("no data at all", rawImage(64, 48, "bgr8", 192, 0), Expect::kRefused);
  sendBad("step shorter than a row", rawImage(64, 48, "bgr8", 100, 100 * 48), Expect::kRefused);
  sendBad("step 0", rawImage(64, 48, "mono8", 0, 64 * 48), Expect::kRefused);
  // 65536 x 65536 with step 65536: step x height is 2^32, 0 in 32-bit arithmetic.
  sendBad("step x height overflowing 32 bits", rawImage(65536, 65536, "mono8", 65536, 0), Expect::kRefused);
  sendBad("huge step", rawImage(64, 2, "mono8", 0xFFFFFFFFu, 256), Expect::kRefused);
  sendBad("yuv422 odd width", rawImage(3, 2, "yuv422", 6, 12), Expect::kRefused);
  // A 16-bit image whose step is not a multiple of 2 bytes: refused (or converted), never a crash.
  sendBad("mono16 odd step", rawImage(64, 48, "mono16", 129, 129 * 48), Expect::kEither);
  sendBad("data longer than step x height", rawImage(64, 48, "mono8", 64, 64 * 48 + 1000), Expect::kEither);
  EXPECT_TRUE(waitLogged({"malformed"}, 5.0)) << "no /rosout message for a malformed image";
}

TEST(BadInput, FlatAndBigEndianFramesAreProcessed) {
  sendBad("all black 640x480", rawImage(640, 480, "mono8", 640, 640 * 480, 0), Expect::kProcessed);
  sendBad("saturated 640x480", rawImage(640, 480, "mono8", 640, 640 * 480, 255), Expect::kProcessed);
  sendBad("saturated bgr8", rawImage(320, 240, "bgr8", 960, 960 * 240, 255), Expect::kProcessed);
  sensor_msgs::Image flat16 = rawImage(64, 48, "mono16", 128, 128 * 48, 0xFF);
  flat16.is_bigendian = 1;
  sendBad("flat big-endian mono16", flat16, Expect::kProcessed);
  sendBad("flat 16UC1 zero", rawImage(64, 48, "16UC1", 128, 128 * 48, 0), Expect::kProcessed);
}

TEST(BadInput, DuplicateBackwardJumpingAndZeroStamps) {
  sensor_msgs::Image img = rel::squareImage(160, 120, 60, 50, 20);
  img.header.frame_id = "camera";
  img.header.stamp = ros::Time::now();
  ctx->image_pub.publish(img);
  ASSERT_TRUE(ctx->out.waitFor(img.header.stamp, 5.0) != nullptr);
  // The same image again with the same stamp (a republished frame; roscpp gives it a new seq).
  ctx->image_pub.publish(img);
  ros::WallDuration(0.4).sleep();
  EXPECT_TRUE(goodFrameProcessed("a duplicate stamp"));
  // Time going backwards by an hour (a looping bag): tracks restart, frames go on.
  img.header.stamp = ros::Time::now() - ros::Duration(3600.0);
  sendBad("stamp an hour back", img, Expect::kProcessed, true);
  // A jump of three hours forwards.
  img.header.stamp = ros::Time::now() + ros::Duration(3 * 3600.0);
  sendBad("stamp three hours ahead", img, Expect::kProcessed, true);
  // No stamp at all: the arrival time is used.
  img.header.stamp = ros::Time(0);
  ctx->image_pub.publish(img);
  ros::WallDuration(0.4).sleep();
  EXPECT_TRUE(goodFrameProcessed("a zero stamp"));
  // Stamps near the end of ROS time.
  img.header.stamp = ros::Time(4294967295u, 999999999u);
  sendBad("stamp at the end of ROS time", img, Expect::kProcessed, true);
}

TEST(BadInput, DynamicReconfigureRefusesOrClampsBadValues) {
  ros::ServiceClient client = ctx->nh->serviceClient<dynamic_reconfigure::Reconfigure>("/tracker/set_parameters");
  ASSERT_TRUE(client.waitForExistence(ros::Duration(10.0)));
  struct Case {
    const char* name;
    double value;
    bool is_int;
    double expected;  // value in use afterwards; NaN = unchanged
  };
  const Case cases[] = {
      {"peak_threshold", kNan, false, kNan},          {"peak_threshold", kInf, false, 1.0},
      {"search_window_scale", -kInf, false, 1.0},     {"search_window_scale", -7.0, false, 1.0},
      {"kcf_lambda", 1e300, false, 1.0},              {"learning_rate", -1e-300, false, 0.0},
      {"max_obstacles", -100, true, 1},               {"max_obstacles", 2147483647.0, true, 16},
      {"saliency_max_side", -2147483648.0, true, 32}, {"max_redetect_failures", 2147483647.0, true, 10000},
      {"scale_step", kNan, false, kNan},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.name) + " = " + std::to_string(c.value));
    // The value in use before (from the latched config).
    auto before_cfg = ros::topic::waitForMessage<dynamic_reconfigure::Config>("/tracker/parameter_updates",
                                                                              *ctx->nh, ros::Duration(5.0));
    ASSERT_TRUE(before_cfg != nullptr);
    double before = kNan;
    for (const auto& d : before_cfg->doubles) if (d.name == c.name) before = d.value;
    for (const auto& i : before_cfg->ints) if (i.name == c.name) before = i.value;
    dynamic_reconfigure::Reconfigure srv;
    if (c.is_int) {
      dynamic_reconfigure::IntParameter p;
      p.name = c.name;
      p.value = static_cast<int>(c.value);
      srv.request.config.ints.push_back(p);
    } else {
      dynamic_reconfigure::DoubleParameter p;
      p.name = c.name;
      p.value = c.value;
      srv.request.config.doubles.push_back(p);
    }
    ASSERT_TRUE(client.call(srv)) << "set_parameters failed";
    double after = kNan;
    for (const auto& d : srv.response.config.doubles) if (d.name == c.name) after = d.value;
    for (const auto& i : srv.response.config.ints) if (i.name == c.name) after = i.value;
    if (std::isnan(c.expected)) {
      EXPECT_EQ(after, before) << "NaN must be refused, keeping the old value";
      EXPECT_TRUE(waitLogged({c.name, "NaN"}, 5.0)) << "no /rosout message naming " << c.name;
    } else {
      EXPECT_EQ(after, c.expected);
    }
    EXPECT_TRUE(goodFrameProcessed(std::string("dynamic_reconfigure ") + c.name));
  }
  // Back to the defaults for the tests that follow.
  const obstacle_tracker::core::Params defaults;
  dynamic_reconfigure::Reconfigure srv;
  for (const char* name : {"peak_threshold", "search_window_scale", "kcf_lambda", "learning_rate", "scale_step"}) {
    dynamic_reconfigure::DoubleParameter p;
    p.name = name;
    p.value = obstacle_tracker::core::getParam(defaults, name);
    srv.request.config.doubles.push_back(p);
  }
  for (const char* name : {"max_obstacles", "saliency_max_side", "max_redetect_failures"}) {
    dynamic_reconfigure::IntParameter p;
    p.name = name;
    p.value = static_cast<int>(obstacle_tracker::core::getParam(defaults, name));
    srv.request.config.ints.push_back(p);
  }
  EXPECT_TRUE(client.call(srv));
  EXPECT_TRUE(goodFrameProcessed("dynamic_reconfigure reset"));
}

TEST(BadInput, RefusalsAreCountedInDiagnostics) {
  // The diagnostics period is about a second; wait for a status that includes every refusal.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);
  double refused = -1.0;
  while (ros::WallTime::now() < end) {
    refused = diagnosticValue("tracker:", "refused frames (total)");
    if (refused >= ctx->refused_expected) break;
    ros::WallDuration(0.2).sleep();
  }
  EXPECT_GE(refused, ctx->refused_expected) << "diagnostics 'refused frames (total)' of tracker";
  EXPECT_TRUE(managerAlive());
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "reliability_bad_input");
  rel::Context context;
  rel::connect(context);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  rel::ctx = nullptr;
  return result;
}
