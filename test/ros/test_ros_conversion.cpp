// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known-answer tests of the ROS adapter's pure functions (no master needed): image encodings to
// the core's CV_8UC1 / CV_8UC3, the 16-bit stretch (the same as the tools'), Bayer patterns,
// malformed messages, camera geometry, parameters <-> dynamic_reconfigure, obstacle messages.
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/eval/sequence.h"
#include "obstacle_tracker/ros/camera_geometry.h"
#include "obstacle_tracker/ros/conversions.h"
#include "obstacle_tracker/ros/image_conversion.h"
#include "synthetic_frames.h"

using obstacle_tracker::bridge::CameraGeometry;
using obstacle_tracker::bridge::FrameConverter;
using obstacle_tracker::bridge::MalformedImage;
using obstacle_tracker::testing::imageMessage;
using obstacle_tracker::testing::maxAbsDiff;
using obstacle_tracker::bridge::UnsupportedEncoding;
namespace core = obstacle_tracker::core;

TEST(ImageConversion, EightBitEncodingsGiveTheSameBgrFrame) {
  const cv::Mat bgr = obstacle_tracker::testing::skyFrame(3, 64, 48);
  FrameConverter conv;
  cv::Mat rgb, bgra, rgba, grey;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  const std::vector<std::pair<const cv::Mat*, const char*>> cases = {
      {&bgr, "bgr8"}, {&bgr, "8UC3"}, {&rgb, "rgb8"}, {&bgra, "bgra8"}, {&bgra, "8UC4"}, {&rgba, "rgba8"}};
  for (const auto& c : cases) {
    const cv::Mat& out = conv.convert(imageMessage(*c.first, c.second));
    ASSERT_EQ(out.type(), CV_8UC3) << c.second;
    EXPECT_EQ(maxAbsDiff(out, bgr), 0.0) << c.second;
  }
  for (const char* enc : {"mono8", "8UC1"}) {
    const cv::Mat& out = conv.convert(imageMessage(grey, enc));
    ASSERT_EQ(out.type(), CV_8UC1) << enc;
    EXPECT_EQ(maxAbsDiff(out, grey), 0.0) << enc;
  }
}

TEST(ImageConversion, ResultDoesNotAliasTheMessage) {
  const cv::Mat bgr = obstacle_tracker::testing::skyFrame(0, 32, 24);
  FrameConverter conv;
  sensor_msgs::Image msg = imageMessage(bgr, "bgr8");
  const cv::Mat& out = conv.convert(msg);
  const cv::Mat copy = out.clone();
  std::fill(msg.data.begin(), msg.data.end(), 0);
  EXPECT_EQ(maxAbsDiff(out, copy), 0.0);
}

TEST(ImageConversion, RowPaddingIsHonoured) {
  const cv::Mat grey = (cv::Mat_<uchar>(2, 3) << 1, 2, 3, 4, 5, 6);
  sensor_msgs::Image msg;
  msg.width = 3;
  msg.height = 2;
  msg.encoding = "mono8";
  msg.step = 8;  // 5 bytes of padding per row
  msg.data = {1, 2, 3, 99, 99, 99, 99, 99, 4, 5, 6, 99, 99, 99, 99, 99};
  FrameConverter conv;
  EXPECT_EQ(maxAbsDiff(conv.convert(msg), grey), 0.0);
}

TEST(ImageConversion, Mono16IsStretchedBetweenPercentiles) {
  // Thermal-like: 1000..1255 counts in a ramp; percentiles 0 and 100 map it exactly onto 0..255.
  cv::Mat m16(16, 16, CV_16UC1);
  for (int i = 0; i < 256; ++i) m16.at<std::uint16_t>(i / 16, i % 16) = static_cast<std::uint16_t>(1000 + i);
  FrameConverter conv;
  conv.stretch().setPercentiles(0.0, 100.0);
  for (bool big_endian : {false, true}) {
    for (const char* enc : {"mono16", "16UC1"}) {
      const cv::Mat& out = conv.convert(imageMessage(m16, enc, big_endian));
      ASSERT_EQ(out.type(), CV_8UC1);
      EXPECT_EQ(conv.stretch().lastLow(), 1000);
      EXPECT_EQ(conv.stretch().lastHigh(), 1255);
      for (int i = 0; i < 256; ++i) EXPECT_EQ(out.at<uchar>(i / 16, i % 16), i) << enc << " big " << big_endian;
    }
  }
}

TEST(ImageConversion, NodeletAndToolsStretchSixteenBitAlike) {
  // The nodelet's converter (messages) and the tools' (decoded files) share core::IntensityStretch
  // and its defaults, so an offline score on 16-bit frames describes the nodelet: the same frames,
  // smoothed range and all, must come out byte for byte the same. Thermal-like frames whose gain
  // drifts, with a hot pixel, in 1, 3 and 4 channels.
  const std::vector<std::pair<int, const char*>> layouts = {
      {CV_16UC1, "mono16"}, {CV_16UC3, "bgr16"}, {CV_16UC4, "bgra16"}};
  for (const auto& layout : layouts) {
    FrameConverter nodelet;
    obstacle_tracker::eval::FrameConverter tools;
    cv::RNG rng(11);
    for (int i = 0; i < 20; ++i) {
      cv::Mat frame(48, 64, layout.first);
      const double gain = 1.0 + 0.05 * std::sin(0.7 * i);
      rng.fill(frame, cv::RNG::NORMAL, cv::Scalar::all(5000.0 * gain), cv::Scalar::all(300.0));
      cv::rectangle(frame, cv::Rect(20 + i, 15, 8, 6), cv::Scalar::all(9000.0 * gain), -1);
      frame.at<std::uint16_t>(3, 3) = 65535;
      for (bool big_endian : {false, true}) {
        if (big_endian && i % 5 != 0) continue;  // a few big-endian messages on the way
        const cv::Mat& from_message = nodelet.convert(imageMessage(frame, layout.second, big_endian));
        const cv::Mat& from_file = tools.convert(frame);
        ASSERT_EQ(from_message.type(), from_file.type()) << layout.second;
        ASSERT_EQ(maxAbsDiff(from_message, from_file), 0.0) << layout.second << " frame " << i;
        EXPECT_EQ(nodelet.stretch().lastLow(), tools.lastLow());
        EXPECT_EQ(nodelet.stretch().lastHigh(), tools.lastHigh());
      }
    }
  }
}

TEST(ImageConversion, BayerPatternsDemosaicToTheRightColour) {
  // A uniform colour mosaicked with each ROS pattern must come back as that colour.
  const cv::Vec3b bgr(30, 120, 220);  // B, G, R
  struct Case { const char* encoding; char tl, tr, bl, br; };
  const Case cases[] = {{"bayer_rggb8", 'R', 'G', 'G', 'B'}, {"bayer_bggr8", 'B', 'G', 'G', 'R'},
                        {"bayer_gbrg8", 'G', 'B', 'R', 'G'}, {"bayer_grbg8", 'G', 'R', 'B', 'G'}};
  auto value = [&](char c) { return c == 'B' ? bgr[0] : c == 'G' ? bgr[1] : bgr[2]; };
  FrameConverter conv;
  for (const Case& c : cases) {
    cv::Mat mosaic(32, 32, CV_8UC1);
    for (int r = 0; r < 32; ++r) {
      for (int col = 0; col < 32; ++col) {
        const char which = r % 2 == 0 ? (col % 2 == 0 ? c.tl : c.tr) : (col % 2 == 0 ? c.bl : c.br);
        mosaic.at<uchar>(r, col) = value(which);
      }
    }
    const cv::Mat& out = conv.convert(imageMessage(mosaic, c.encoding));
    ASSERT_EQ(out.type(), CV_8UC3);
    const cv::Vec3b centre = out.at<cv::Vec3b>(16, 16);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(centre[ch], bgr[ch], 2) << c.encoding << " channel " << ch;
  }
  // 16-bit Bayer: demosaiced, then stretched to 8 bits.
  cv::Mat mosaic16(32, 32, CV_16UC1);
  cv::randu(mosaic16, 0, 4096);
  const cv::Mat& out16 = conv.convert(imageMessage(mosaic16, "bayer_rggb16"));
  EXPECT_EQ(out16.type(), CV_8UC3);
}

TEST(ImageConversion, Yuv422AndSixteenBitColour) {
  cv::Mat uyvy(8, 8, CV_8UC2, cv::Scalar(128, 200));  // neutral chroma, luma 200
  FrameConverter conv;
  const cv::Mat& out = conv.convert(imageMessage(uyvy, "yuv422"));
  ASSERT_EQ(out.type(), CV_8UC3);
  // BT.601 video range: Y = 200 is (200 - 16) * 255 / 219 = 214 on every channel.
  EXPECT_NEAR(out.at<cv::Vec3b>(4, 4)[1], 214, 2);
  cv::Mat rgb16(8, 8, CV_16UC3, cv::Scalar(100, 2000, 4000));
  rgb16(cv::Rect(0, 0, 4, 8)).setTo(cv::Scalar(0, 0, 0));
  const cv::Mat& out16 = conv.convert(imageMessage(rgb16, "rgb16"));
  ASSERT_EQ(out16.type(), CV_8UC3);
  EXPECT_GT(out16.at<cv::Vec3b>(4, 6)[0], out16.at<cv::Vec3b>(4, 6)[2]);  // B = 4000 (third in RGB) is channel 0 of BGR
}

TEST(ImageConversion, UnsupportedEncodingsAreRefusedByName) {
  FrameConverter conv;
  cv::Mat f32(4, 4, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5));
  for (const char* enc : {"32FC3", "16SC1", "64FC1", "garbage", ""}) {
    try {
      conv.convert(imageMessage(f32, enc));
      FAIL() << "accepted " << enc;
    } catch (const UnsupportedEncoding& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + enc + "'"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(obstacle_tracker::bridge::isSupportedEncoding("bayer_gbrg16"));
  EXPECT_FALSE(obstacle_tracker::bridge::isSupportedEncoding("32FC1"));
}

TEST(ImageConversion, MalformedMessagesNeverReadOutside) {
  FrameConverter conv;
  sensor_msgs::Image msg = imageMessage(obstacle_tracker::testing::skyFrame(0, 16, 16), "bgr8");
  sensor_msgs::Image short_data = msg;
  short_data.data.resize(msg.data.size() - 1);
  EXPECT_THROW(conv.convert(short_data), MalformedImage);
  sensor_msgs::Image short_step = msg;
  short_step.step = 16 * 3 - 1;
  EXPECT_THROW(conv.convert(short_step), MalformedImage);
  sensor_msgs::Image empty = msg;
  empty.width = 0;
  EXPECT_THROW(conv.convert(empty), MalformedImage);
  sensor_msgs::Image huge = msg;
  huge.width = 4000000000u;
  huge.height = 4000000000u;
  huge.step = 4000000000u;
  EXPECT_THROW(conv.convert(huge), MalformedImage);
  sensor_msgs::Image odd_yuv = imageMessage(cv::Mat(4, 5, CV_8UC2, cv::Scalar(0)), "yuv422");
  EXPECT_THROW(conv.convert(odd_yuv), MalformedImage);
  // The converter still works afterwards.
  EXPECT_EQ(conv.convert(msg).type(), CV_8UC3);
}

TEST(CameraGeometry, PrincipalPointAndKnownAngles) {
  sensor_msgs::CameraInfo info;
  info.width = 640;
  info.height = 480;
  info.K = {500.0, 0.0, 319.5, 0.0, 500.0, 239.5, 0.0, 0.0, 1.0};
  CameraGeometry cam;
  std::string error;
  ASSERT_TRUE(cam.setCameraInfo(info, &error)) << error;
  // The pixel whose centre is the principal point: corner coordinates (320, 240).
  const cv::Vec3d centre = cam.ray(320.0, 240.0);
  EXPECT_NEAR(centre[0], 0.0, 1e-12);
  EXPECT_NEAR(centre[1], 0.0, 1e-12);
  EXPECT_NEAR(centre[2], 1.0, 1e-12);
  // A box from x = cx - 500 to cx + 500 subtends 2 * atan(1) = 90 degrees; its centre row is the
  // principal row, so the bearing has no y component and points along z.
  const auto g = cam.box(cv::Rect2f(320.0f - 500.0f, 240.0f - 50.0f, 1000.0f, 100.0f));
  EXPECT_NEAR(g.angular_width, M_PI / 2.0, 1e-9);
  EXPECT_NEAR(g.angular_height, 2.0 * std::atan(50.0 / 500.0), 1e-9);
  EXPECT_NEAR(cv::norm(g.bearing), 1.0, 1e-12);
  EXPECT_NEAR(g.bearing[2], 1.0, 1e-12);
  // Right of the centre is +x, below is +y (optical frame).
  const cv::Vec3d r = cam.ray(320.0 + 500.0, 240.0 + 500.0);
  EXPECT_NEAR(r[0], 1.0 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(r[1], 1.0 / std::sqrt(3.0), 1e-12);
}

TEST(CameraGeometry, DistortionIsUndoneAndBinningHonoured) {
  sensor_msgs::CameraInfo info;
  info.K = {400.0, 0.0, 200.0, 0.0, 400.0, 150.0, 0.0, 0.0, 1.0};
  info.distortion_model = "plumb_bob";
  info.D = {-0.2, 0.05, 0.0, 0.0, 0.0};
  CameraGeometry cam;
  std::string error;
  ASSERT_TRUE(cam.setCameraInfo(info, &error)) << error;
  // Distort a known normalised point with the same model, then look it up.
  const cv::Point2d xn(0.3, -0.2);
  const double r2 = xn.x * xn.x + xn.y * xn.y, k = 1.0 - 0.2 * r2 + 0.05 * r2 * r2;
  const double u = 400.0 * xn.x * k + 200.0 + 0.5, v = 400.0 * xn.y * k + 150.0 + 0.5;
  const cv::Vec3d ray = cam.ray(u, v);
  EXPECT_NEAR(ray[0] / ray[2], xn.x, 1e-6);
  EXPECT_NEAR(ray[1] / ray[2], xn.y, 1e-6);

  sensor_msgs::CameraInfo binned;
  binned.K = {400.0, 0.0, 199.5, 0.0, 400.0, 149.5, 0.0, 0.0, 1.0};
  binned.binning_x = binned.binning_y = 2;
  ASSERT_TRUE(cam.setCameraInfo(binned, &error)) << error;
  const cv::Vec3d c = cam.ray(100.0, 75.0);  // binned pixel corner (100, 75) = full (200, 150)
  EXPECT_NEAR(c[0], 0.0, 1e-12);
  EXPECT_NEAR(c[1], 0.0, 1e-12);
}

TEST(CameraGeometry, UnusableCameraInfoIsRefused) {
  CameraGeometry cam;
  std::string error;
  sensor_msgs::CameraInfo zero;  // all-zero K (an uncalibrated driver)
  EXPECT_FALSE(cam.setCameraInfo(zero, &error));
  EXPECT_FALSE(error.empty());
  EXPECT_FALSE(cam.valid());
  sensor_msgs::CameraInfo unknown;
  unknown.K = {400.0, 0.0, 200.0, 0.0, 400.0, 150.0, 0.0, 0.0, 1.0};
  unknown.distortion_model = "mystery";
  unknown.D = {0.1};
  EXPECT_FALSE(cam.setCameraInfo(unknown, &error));
  unknown.D = {0.0};  // no distortion: the model name does not matter
  EXPECT_TRUE(cam.setCameraInfo(unknown, &error)) << error;
  unknown.K[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(cam.setCameraInfo(unknown, &error));
}

TEST(Parameters, ConfigRoundTripCoversEveryCoreParameter) {
  EXPECT_TRUE(obstacle_tracker::bridge::paramsMissingFromConfig().empty());
  core::Params p;
  for (const core::ParamInfo& info : core::paramTable()) {
    // A value inside the range that differs from the default.
    const double v = std::string(info.type) == "bool" ? (info.default_value != 0.0 ? 0.0 : 1.0)
                     : std::string(info.type) == "int" ? std::floor(0.5 * (info.min_value + info.max_value))
                                                        : 0.25 * info.min_value + 0.75 * info.max_value;
    ASSERT_TRUE(core::setParam(p, info.name, v));
  }
  const obstacle_tracker::ObstacleTrackerConfig config =
      obstacle_tracker::bridge::configFromParams(p, obstacle_tracker::ObstacleTrackerConfig::__getDefault__());
  std::vector<std::string> messages;
  const core::Params back = obstacle_tracker::bridge::paramsFromConfig(config, core::Params(), &messages);
  EXPECT_TRUE(messages.empty());
  for (const core::ParamInfo& info : core::paramTable()) {
    EXPECT_DOUBLE_EQ(core::getParam(back, info.name), core::getParam(p, info.name)) << info.name;
  }
}

TEST(Parameters, OutOfRangeConfigValuesAreClampedWithAMessage) {
  obstacle_tracker::ObstacleTrackerConfig config = obstacle_tracker::ObstacleTrackerConfig::__getDefault__();
  config.peak_threshold = 7.0;  // max 1
  std::vector<std::string> messages;
  const core::Params p = obstacle_tracker::bridge::paramsFromConfig(config, core::Params(), &messages);
  EXPECT_DOUBLE_EQ(p.peak_threshold, 1.0);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("peak_threshold"), std::string::npos);
}

TEST(Messages, ObstacleFieldsAndStates) {
  core::Obstacle o;
  o.id = 7;
  o.box = cv::Rect2f(1.5f, 2.5f, 30.0f, 20.0f);
  o.confidence = 0.8f;
  o.peak = 0.6f;
  o.psr = 12.0f;
  o.state = core::TrackState::kRedetecting;
  o.expansion_rate = 0.5;
  o.expansion_rate_sigma = 0.1;
  o.time_to_contact = 2.0;
  o.time_to_contact_sigma = 0.4;
  obstacle_tracker::Obstacle msg;
  obstacle_tracker::bridge::toMessage(o, msg);
  EXPECT_EQ(msg.id, 7u);
  EXPECT_FLOAT_EQ(msg.x, 1.5f);
  EXPECT_FLOAT_EQ(msg.height, 20.0f);
  EXPECT_EQ(msg.state, obstacle_tracker::Obstacle::STATE_REDETECTING);
  EXPECT_FALSE(msg.has_bearing);
  EXPECT_FLOAT_EQ(msg.time_to_contact, 2.0f);
  EXPECT_FLOAT_EQ(msg.expansion_rate_sigma, 0.1f);
  EXPECT_FLOAT_EQ(msg.time_to_contact_sigma, 0.4f);
  o.time_to_contact = std::numeric_limits<double>::infinity();
  o.time_to_contact_sigma = std::numeric_limits<double>::quiet_NaN();
  obstacle_tracker::bridge::toMessage(o, msg);
  EXPECT_TRUE(std::isinf(msg.time_to_contact));
  EXPECT_TRUE(std::isinf(msg.time_to_contact_sigma));
  EXPECT_EQ(obstacle_tracker::bridge::toMessageState(core::TrackState::kTracking), obstacle_tracker::Obstacle::STATE_TRACKING);
  EXPECT_EQ(obstacle_tracker::bridge::toMessageState(core::TrackState::kLost), obstacle_tracker::Obstacle::STATE_LOST);
}
