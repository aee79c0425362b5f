// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// bridge::FrameConverter over every encoding it accepts, beside test_ros_conversion's known
// colours: each against plain OpenCV (the conversion cv_bridge is expected to make), each 16-bit
// one in both byte orders, none aliasing the message, no allocation per frame on the paths that
// copy into reused buffers, and the refusals cv_bridge would otherwise make with a less clear
// message (or, for sizes beyond 32 bits, not make at all).
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "../core/alloc_counter.h"
#include "obstacle_tracker/core/intensity_stretch.h"
#include "obstacle_tracker/ros/image_conversion.h"
#include "synthetic_frames.h"

using obstacle_tracker::bridge::FrameConverter;
using obstacle_tracker::bridge::MalformedImage;
using obstacle_tracker::testing::imageMessage;
using obstacle_tracker::testing::maxAbsDiff;

namespace {

constexpr int kNone = -1;

// Each accepted encoding: its pixels and the OpenCV conversion to the core's BGR or grey. ROS
// names a Bayer pattern from the top-left pixel, OpenCV from the second row's second and third.
struct Expected {
  const char* encoding;
  int type;
  int code;
};
const Expected kExpected[] = {
    {"mono8", CV_8UC1, kNone},
    {"8UC1", CV_8UC1, kNone},
    {"mono16", CV_16UC1, kNone},
    {"16UC1", CV_16UC1, kNone},
    {"bgr8", CV_8UC3, kNone},
    {"8UC3", CV_8UC3, kNone},
    {"rgb8", CV_8UC3, cv::COLOR_RGB2BGR},
    {"bgra8", CV_8UC4, cv::COLOR_BGRA2BGR},
    {"8UC4", CV_8UC4, cv::COLOR_BGRA2BGR},
    {"rgba8", CV_8UC4, cv::COLOR_RGBA2BGR},
    {"bgr16", CV_16UC3, kNone},
    {"rgb16", CV_16UC3, cv::COLOR_RGB2BGR},
    {"bgra16", CV_16UC4, cv::COLOR_BGRA2BGR},
    {"rgba16", CV_16UC4, cv::COLOR_RGBA2BGR},
    {"bayer_rggb8", CV_8UC1, cv::COLOR_BayerBG2BGR},
    {"bayer_bggr8", CV_8UC1, cv::COLOR_BayerRG2BGR},
    {"bayer_gbrg8", CV_8UC1, cv::COLOR_BayerGR2BGR},
    {"bayer_grbg8", CV_8UC1, cv::COLOR_BayerGB2BGR},
    {"bayer_rggb16", CV_16UC1, cv::COLOR_BayerBG2BGR},
    {"bayer_bggr16", CV_16UC1, cv::COLOR_BayerRG2BGR},
    {"bayer_gbrg16", CV_16UC1, cv::COLOR_BayerGR2BGR},
    {"bayer_grbg16", CV_16UC1, cv::COLOR_BayerGB2BGR},
    {"yuv422", CV_8UC2, cv::COLOR_YUV2BGR_UYVY},
    {"yuv422_yuy2", CV_8UC2, cv::COLOR_YUV2BGR_YUYV},
};

cv::Mat randomPixels(int type, int seed) {
  cv::Mat m(48, 64, type);
  cv::RNG rng(seed);
  if (CV_MAT_DEPTH(type) == CV_16U) {
    rng.fill(m, cv::RNG::UNIFORM, 1000, 5000);  // a thermal camera's narrow band of counts
  } else {
    rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  }
  return m;
}

// The frame the core should get for `pixels` sent as `e`, stretched like a first frame.
cv::Mat reference(const Expected& e, const cv::Mat& pixels) {
  cv::Mat converted = pixels;
  if (e.code != kNone) cv::cvtColor(pixels, converted, e.code);
  if (converted.depth() == CV_8U) return converted;
  obstacle_tracker::core::IntensityStretch stretch;
  cv::Mat stretched;
  stretch.apply(converted, stretched);
  return stretched;
}

}  // namespace

TEST(ImageEncodings, EveryAcceptedEncodingIsConvertedAsOpenCvWould) {
  std::vector<std::string> covered;
  for (const Expected& e : kExpected) {
    const cv::Mat pixels = randomPixels(e.type, static_cast<int>(covered.size()) + 1);
    FrameConverter conv;
    const cv::Mat& out = conv.convert(imageMessage(pixels, e.encoding));
    const cv::Mat expected = reference(e, pixels);
    ASSERT_EQ(out.type(), expected.type()) << e.encoding;
    EXPECT_EQ(maxAbsDiff(out, expected), 0.0) << e.encoding;
    covered.emplace_back(e.encoding);
  }
  EXPECT_EQ(covered, obstacle_tracker::bridge::supportedEncodings());
}

TEST(ImageEncodings, Yuy2NeutralChromaIsGrey) {
  // Y0 U Y1 V with U = V = 128: BT.601 video range, Y = 200 is (200 - 16) * 255 / 219 = 214.
  cv::Mat yuyv(8, 8, CV_8UC2, cv::Scalar(200, 128));
  FrameConverter conv;
  const cv::Mat& out = conv.convert(imageMessage(yuyv, "yuv422_yuy2"));
  ASSERT_EQ(out.type(), CV_8UC3);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(out.at<cv::Vec3b>(4, 4)[ch], 214, 2) << ch;
}

TEST(ImageEncodings, SixteenBitBigEndianGivesTheSameFrame) {
  for (const Expected& e : kExpected) {
    if (CV_MAT_DEPTH(e.type) != CV_16U) continue;
    const cv::Mat pixels = randomPixels(e.type, 3);
    FrameConverter little, big;
    const cv::Mat& from_little = little.convert(imageMessage(pixels, e.encoding, false));
    const cv::Mat& from_big = big.convert(imageMessage(pixels, e.encoding, true));
    ASSERT_EQ(from_big.type(), from_little.type()) << e.encoding;
    EXPECT_EQ(maxAbsDiff(from_big, from_little), 0.0) << e.encoding;
    EXPECT_EQ(big.stretch().lastLow(), little.stretch().lastLow()) << e.encoding;
    EXPECT_EQ(big.stretch().lastHigh(), little.stretch().lastHigh()) << e.encoding;
  }
}

TEST(ImageEncodings, EightBitFlaggedBigEndianIsReadAsIs) {
  // One byte per sample has no byte order: the flag changes nothing.
  for (const char* encoding : {"bgr8", "rgb8", "mono8", "bayer_rggb8", "yuv422"}) {
    const Expected* e = nullptr;
    for (const Expected& x : kExpected) {
      if (std::string(x.encoding) == encoding) e = &x;
    }
    ASSERT_NE(e, nullptr);
    const cv::Mat pixels = randomPixels(e->type, 5);
    FrameConverter conv;
    sensor_msgs::Image msg = imageMessage(pixels, encoding);
    msg.is_bigendian = 1;
    EXPECT_EQ(maxAbsDiff(conv.convert(msg), reference(*e, pixels)), 0.0) << encoding;
  }
}

TEST(ImageEncodings, ResultNeverPointsIntoTheMessage) {
  for (const Expected& e : kExpected) {
    const cv::Mat pixels = randomPixels(e.type, 7);
    sensor_msgs::Image msg = imageMessage(pixels, e.encoding);
    FrameConverter conv;
    const cv::Mat& out = conv.convert(msg);
    const cv::Mat copy = out.clone();
    const std::uint8_t* begin = msg.data.data();
    EXPECT_TRUE(out.datastart >= begin + msg.data.size() || out.dataend <= begin) << e.encoding;
    std::fill(msg.data.begin(), msg.data.end(), 0);
    EXPECT_EQ(maxAbsDiff(out, copy), 0.0) << e.encoding;
  }
}

TEST(ImageEncodings, ReusedBufferPathsAllocateNothingPerFrame) {
  OT_SKIP_UNLESS_COUNTING_ALLOCATIONS();
  ASSERT_GT(probeOpenCvAllocations(), 0);
  const std::vector<std::pair<const char*, bool>> paths = {
      {"mono8", false}, {"8UC1", false},  {"bgr8", false},   {"8UC3", false},
      {"mono16", false}, {"16UC1", false}, {"bgr16", false}, {"mono16", true},
      {"yuv422_yuy2", false}};
  for (const auto& path : paths) {
    const Expected* e = nullptr;
    for (const Expected& x : kExpected) {
      if (std::string(x.encoding) == path.first) e = &x;
    }
    ASSERT_NE(e, nullptr);
    const sensor_msgs::Image msg = imageMessage(randomPixels(e->type, 9), path.first, path.second);
    FrameConverter conv;
    conv.convert(msg);  // sizes the buffers
    g_allocations = 0;
    g_counting = true;
    for (int i = 0; i < 5; ++i) conv.convert(msg);
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0) << path.first << (path.second ? " big-endian" : "");
  }
}

TEST(ImageEncodings, SizesCvBridgeWouldRefuseOrMissAreMalformed) {
  FrameConverter conv;
  auto message = [&](const sensor_msgs::Image& msg) -> std::string {
    try {
      conv.convert(msg);
    } catch (const MalformedImage& e) {
      return e.what();
    }
    return "accepted";
  };
  // Trailing bytes: cv_bridge wants exactly step x height.
  sensor_msgs::Image longer = imageMessage(randomPixels(CV_8UC1, 1), "mono8");
  longer.data.resize(longer.data.size() + 100);
  EXPECT_NE(message(longer).find("more than step x height"), std::string::npos) << message(longer);
  // A 16-bit row that ends in the middle of a sample.
  sensor_msgs::Image odd = imageMessage(randomPixels(CV_16UC1, 1), "mono16");
  odd.step = 129;
  odd.data.assign(static_cast<std::size_t>(odd.step) * odd.height, 0);
  EXPECT_NE(message(odd).find("16-bit samples"), std::string::npos) << message(odd);
  // step x height is 2^32, 0 in cv_bridge's 32-bit check, which then lets the message through.
  sensor_msgs::Image wrapped_size;
  wrapped_size.width = wrapped_size.height = wrapped_size.step = 65536;
  wrapped_size.encoding = "mono8";
  EXPECT_NE(message(wrapped_size).find("step x height needs 4294967296"), std::string::npos)
      << message(wrapped_size);
  // The converter still works afterwards.
  EXPECT_EQ(conv.convert(imageMessage(randomPixels(CV_8UC3, 1), "bgr8")).type(), CV_8UC3);
}

TEST(ImageEncodings, TinyBayerAndColourImagesConvert) {
  FrameConverter conv;
  for (int side : {1, 2, 3}) {
    const cv::Mat bayer8(side, side, CV_8UC1, cv::Scalar(90));
    const cv::Mat bayer16(side, side, CV_16UC1, cv::Scalar(900));
    const cv::Mat rgba16(side, side, CV_16UC4, cv::Scalar::all(900));
    EXPECT_EQ(conv.convert(imageMessage(bayer8, "bayer_rggb8")).type(), CV_8UC3) << side;
    EXPECT_EQ(conv.convert(imageMessage(bayer16, "bayer_gbrg16")).type(), CV_8UC3) << side;
    EXPECT_EQ(conv.convert(imageMessage(rgba16, "rgba16")).type(), CV_8UC3) << side;
  }
}
