// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known-answer tests of core::IntensityStretch, the 16-bit / float to 8-bit rule of the nodelet
// and the tools: percentiles, hot pixels, flat frames, smoothing, reset, NaN and infinities,
// several channels, and no allocation per frame.
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/intensity_stretch.h"

#include "alloc_counter.h"

using obstacle_tracker::core::IntensityStretch;

namespace {

// 10 x 1000 ramp 1000..1999 along each row.
cv::Mat ramp16() {
  cv::Mat img(10, 1000, CV_16UC1);
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) img.at<std::uint16_t>(r, c) = static_cast<std::uint16_t>(1000 + c);
  }
  return img;
}

}  // namespace

TEST(IntensityStretch, HotAndDeadPixelsAreIgnored) {
  cv::Mat m16(100, 100, CV_16UC1, cv::Scalar(3000));
  m16(cv::Rect(0, 0, 100, 50)).setTo(3100);
  m16.at<std::uint16_t>(7, 7) = 65535;  // hot pixel
  m16.at<std::uint16_t>(8, 8) = 0;      // dead pixel
  IntensityStretch stretch(1.0, 99.0, 1.0);
  cv::Mat out;
  stretch.apply(m16, out);
  ASSERT_EQ(out.type(), CV_8UC1);
  EXPECT_EQ(stretch.lastLow(), 3000);
  EXPECT_EQ(stretch.lastHigh(), 3100);
  EXPECT_EQ(out.at<uchar>(10, 10), 255);
  EXPECT_EQ(out.at<uchar>(90, 90), 0);
  EXPECT_EQ(out.at<uchar>(7, 7), 255);  // saturates
  EXPECT_EQ(out.at<uchar>(8, 8), 0);
}

TEST(IntensityStretch, RampBetweenPercentiles) {
  // 10000 values 1000..1999, ten of each but one 1000 that became a hot pixel. Low: the first
  // level with more than 0.5 % = 50 values at or below it (9 + 5 * 10 = 59 at 1005); high: the
  // first with at least 99.5 % = 9950 (9959 at 1995). The hot pixel moves neither.
  cv::Mat img = ramp16();
  img.at<std::uint16_t>(0, 0) = 65535;
  IntensityStretch stretch(0.5, 99.5, 1.0);
  cv::Mat out;
  stretch.apply(img, out);
  EXPECT_EQ(stretch.lastLow(), 1005);
  EXPECT_EQ(stretch.lastHigh(), 1995);
  EXPECT_EQ(out.at<std::uint8_t>(5, 0), 0);
  EXPECT_EQ(out.at<std::uint8_t>(5, 999), 255);
  EXPECT_EQ(out.at<std::uint8_t>(5, 600), 153);  // (1600 - 1005) * 255 / 990 = 153.3
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), 255);  // the hot pixel clips
  for (int c = 1; c < 1000; ++c) EXPECT_GE(out.at<std::uint8_t>(5, c), out.at<std::uint8_t>(5, c - 1));
  // Percentiles 0 and 100 are the extremes.
  IntensityStretch full(0.0, 100.0, 1.0);
  full.apply(ramp16(), out);
  EXPECT_EQ(full.lastLow(), 1000);
  EXPECT_EQ(full.lastHigh(), 1999);
}

TEST(IntensityStretch, FlatFramesDoNotDivideByZero) {
  IntensityStretch stretch(1.0, 99.0, 1.0);
  cv::Mat out;
  for (int level : {0, 500, 65535}) {
    stretch.apply(cv::Mat(10, 10, CV_16UC1, cv::Scalar(level)), out);
    EXPECT_EQ(cv::countNonZero(out), 0) << level;
    EXPECT_EQ(stretch.lastLow(), level);
    EXPECT_EQ(stretch.lastHigh(), level + 1.0);
  }
  for (float level : {0.0f, 0.5f, 1e6f, -3e4f}) {
    stretch.apply(cv::Mat(10, 10, CV_32FC1, cv::Scalar(level)), out);
    EXPECT_EQ(cv::countNonZero(out), 0) << level;
  }
}

TEST(IntensityStretch, SmoothingFollowsAStepGeometrically) {
  // A step from a 1000..1999 frame to frames 1000 counts brighter: the range moves by
  // `smoothing` of the remaining distance per frame and converges on the new one.
  IntensityStretch stretch(0.0, 100.0, 0.2);
  cv::Mat out;
  stretch.apply(ramp16(), out);
  EXPECT_EQ(stretch.lastLow(), 1000);
  EXPECT_EQ(stretch.lastHigh(), 1999);
  const cv::Mat brighter = ramp16() + cv::Scalar(1000);
  double expected_low = 1000.0;
  for (int i = 1; i <= 40; ++i) {
    stretch.apply(brighter, out);
    expected_low = 0.8 * expected_low + 0.2 * 2000.0;
    EXPECT_NEAR(stretch.lastLow(), expected_low, 1e-9) << i;
    EXPECT_NEAR(stretch.lastHigh() - stretch.lastLow(), 999.0, 1e-9) << i;
  }
  EXPECT_NEAR(stretch.lastLow(), 2000.0, 0.2);  // 1000 * 0.8^40 = 0.13
  EXPECT_EQ(out.at<std::uint8_t>(5, 0), 0);
  EXPECT_EQ(out.at<std::uint8_t>(5, 999), 255);
  // While converging, the step shows as a brighter picture rather than being normalised away.
  IntensityStretch fresh(0.0, 100.0, 0.2);
  fresh.apply(ramp16(), out);
  fresh.apply(brighter, out);
  EXPECT_EQ(fresh.lastLow(), 1200);
  EXPECT_GT(out.at<std::uint8_t>(5, 0), 0);
}

TEST(IntensityStretch, ResetForgetsTheSmoothedRange) {
  IntensityStretch stretch(0.0, 100.0, 0.2);
  cv::Mat out;
  stretch.apply(ramp16(), out);
  stretch.reset();
  EXPECT_EQ(stretch.lastLow(), 0);
  EXPECT_EQ(stretch.lastHigh(), 255);
  stretch.apply(ramp16() + cv::Scalar(1000), out);
  EXPECT_EQ(stretch.lastLow(), 2000);  // this frame's range alone
  EXPECT_EQ(stretch.lastHigh(), 2999);
  // A frame of another depth is in other units: it starts afresh too.
  cv::Mat f(4, 4, CV_32FC1, cv::Scalar(0.25f));
  f.at<float>(0, 0) = 0.75f;
  stretch.apply(f, out);
  EXPECT_FLOAT_EQ(stretch.lastLow(), 0.25f);
  EXPECT_FLOAT_EQ(stretch.lastHigh(), 0.75f);
}

TEST(IntensityStretch, FloatWithNaNAndInfinities) {
  cv::Mat f(3, 3, CV_32FC1, cv::Scalar(0.5f));
  f.at<float>(0, 0) = 0.0f;
  f.at<float>(2, 2) = 1.0f;
  f.at<float>(1, 0) = std::nanf("");
  f.at<float>(0, 2) = std::numeric_limits<float>::infinity();
  f.at<float>(2, 0) = -std::numeric_limits<float>::infinity();
  IntensityStretch stretch(0.0, 100.0, 1.0);
  cv::Mat out;
  stretch.apply(f, out);
  ASSERT_EQ(out.type(), CV_8UC1);
  EXPECT_EQ(stretch.lastLow(), 0.0);
  EXPECT_EQ(stretch.lastHigh(), 1.0);
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), 0);
  EXPECT_EQ(out.at<std::uint8_t>(2, 2), 255);
  EXPECT_NEAR(out.at<std::uint8_t>(1, 1), 128, 1);
  EXPECT_EQ(out.at<std::uint8_t>(1, 0), 0);    // NaN -> the low end
  EXPECT_EQ(out.at<std::uint8_t>(0, 2), 255);  // +inf -> the high end
  EXPECT_EQ(out.at<std::uint8_t>(2, 0), 0);    // -inf -> the low end
  EXPECT_TRUE(std::isnan(f.at<float>(1, 0)));  // input untouched
  // Doubles go the same way; a frame without a finite value does not throw.
  cv::Mat d;
  f.convertTo(d, CV_64F);
  cv::Mat out64;
  stretch.apply(d, out64);
  EXPECT_EQ(cv::norm(out, out64, cv::NORM_INF), 0.0);
  stretch.apply(cv::Mat(2, 2, CV_32FC1, cv::Scalar(std::nanf(""))), out);
  EXPECT_EQ(cv::countNonZero(out), 0);
}

TEST(IntensityStretch, ChannelsArePooledAndKept) {
  // One range over all channels (colour balance is kept), any channel count.
  for (int cn : {2, 3, 4}) {
    cv::Mat img(4, 4, CV_16UC(cn), cv::Scalar(100, 200, 300, 400));
    IntensityStretch stretch(0.0, 100.0, 1.0);
    cv::Mat out;
    stretch.apply(img, out);
    ASSERT_EQ(out.type(), CV_8UC(cn));
    EXPECT_EQ(stretch.lastLow(), 100);
    EXPECT_EQ(stretch.lastHigh(), 100.0 * cn);
    EXPECT_EQ(out.at<std::uint8_t>(3, 3 * cn), 0);
    EXPECT_EQ(out.at<std::uint8_t>(3, 3 * cn + cn - 1), 255);
  }
  cv::Mat img(4, 4, CV_16UC3, cv::Scalar(1000, 2000, 5000));
  IntensityStretch stretch(0.0, 100.0, 1.0);
  cv::Mat out;
  stretch.apply(img, out);
  EXPECT_EQ(out.at<cv::Vec3b>(1, 1), cv::Vec3b(0, 64, 255));  // 1000 * 255 / 4000 = 63.75
}

TEST(IntensityStretch, BadSettingsAndFramesThrow) {
  EXPECT_THROW(IntensityStretch(50.0, 10.0), std::invalid_argument);
  EXPECT_THROW(IntensityStretch(-1.0, 99.0), std::invalid_argument);
  EXPECT_THROW(IntensityStretch(1.0, 101.0), std::invalid_argument);
  EXPECT_THROW(IntensityStretch(1.0, 99.0, 0.0), std::invalid_argument);
  EXPECT_THROW(IntensityStretch(1.0, 99.0, 1.5), std::invalid_argument);
  IntensityStretch stretch;
  EXPECT_THROW(stretch.setPercentiles(std::nan(""), 99.0), std::invalid_argument);
  EXPECT_THROW(stretch.setSmoothing(std::nan("")), std::invalid_argument);
  cv::Mat out;
  EXPECT_THROW(stretch.apply(cv::Mat(), out), std::invalid_argument);
  EXPECT_THROW(stretch.apply(cv::Mat(4, 4, CV_8UC1, cv::Scalar(1)), out), std::invalid_argument);
}

TEST(IntensityStretch, NoAllocationPerFrameAfterTheFirst) {
  OT_SKIP_UNLESS_COUNTING_ALLOCATIONS();
  ASSERT_GT(probeOpenCvAllocations(), 0);  // so that a zero below means something

  cv::Mat m16(480, 640, CV_16UC3), f32(480, 640, CV_32FC1);
  cv::randu(m16, 4000, 9000);
  cv::randu(f32, -1.0, 1.0);
  f32.at<float>(3, 3) = std::nanf("");  // the float path's copy into its own buffer
  IntensityStretch stretch;
  cv::Mat out16, out32;
  stretch.apply(m16, out16);
  IntensityStretch float_stretch;
  float_stretch.apply(f32, out32);
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < 5; ++i) {
    stretch.apply(m16, out16);
    float_stretch.apply(f32, out32);
  }
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 0);
}
