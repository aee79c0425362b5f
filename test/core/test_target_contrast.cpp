// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// TargetContrast (target_contrast.h): known answers for a small target against sky noise, a box
// on plain sky, a colour-only target, a near obstacle at 1080p (sampled window), the lost() rule
// and bad input.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "alloc_counter.h"
#include "obstacle_tracker/core/target_contrast.h"

namespace core = obstacle_tracker::core;

namespace {

// Sky: a level with Gaussian noise (sigma grey levels).
cv::Mat skyFrame(cv::Size size, double level, double sigma, unsigned seed = 3) {
  cv::Mat f(size, CV_32F, cv::Scalar(level));
  cv::Mat n(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(n, cv::RNG::NORMAL, 0.0, sigma);
  f += n;
  cv::Mat out;
  f.convertTo(out, CV_8U);
  return out;
}

}  // namespace

TEST(TargetContrast, ASmallTargetStandsOutOfTheSkyAndAnEmptyBoxDoesNot) {
  cv::Mat frame = skyFrame(cv::Size(320, 240), 90.0, 3.0);
  // A 5x3 px aircraft 60 levels above the sky in a 17x13 box (annotated boxes keep a margin).
  cv::rectangle(frame, cv::Rect(156, 118, 5, 3), cv::Scalar(150), cv::FILLED);
  const core::TargetContrast contrast;
  const float on_target = contrast.measure(frame, cv::Rect2f(150.0f, 113.0f, 17.0f, 13.0f));
  const float on_sky = contrast.measure(frame, cv::Rect2f(60.0f, 60.0f, 17.0f, 13.0f));
  // Noise sigma 3: the target is about 20 sigma out, the empty box's 4th largest pixel ~2-3.
  EXPECT_GT(on_target, 12.0f);
  EXPECT_LT(on_sky, core::TargetContrast::kFloor);
  EXPECT_TRUE(core::TargetContrast::lost(on_target, on_sky));
  EXPECT_FALSE(core::TargetContrast::lost(on_target, on_target));
}

TEST(TargetContrast, OneHotPixelIsNotAnObject) {
  cv::Mat frame = skyFrame(cv::Size(200, 150), 90.0, 2.0);
  frame.at<uchar>(75, 100) = 255;
  const core::TargetContrast contrast;
  EXPECT_LT(contrast.measure(frame, cv::Rect2f(92.0f, 68.0f, 17.0f, 13.0f)), core::TargetContrast::kFloor);
}

TEST(TargetContrast, AColourOnlyTargetCounts) {
  // Same grey level as the sky in two channels: only its red differs (BGR order).
  cv::Mat frame(cv::Size(200, 150), CV_8UC3, cv::Scalar(120, 120, 120));
  cv::Mat noise(frame.size(), CV_8UC3);
  cv::RNG rng(5);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 3);
  frame += noise;
  cv::rectangle(frame, cv::Rect(98, 72, 6, 4), cv::Scalar(120, 120, 200), cv::FILLED);
  const core::TargetContrast contrast;
  EXPECT_GT(contrast.measure(frame, cv::Rect2f(92.0f, 66.0f, 18.0f, 16.0f)), 20.0f);
}

TEST(TargetContrast, ANearObstacleAt1080pIsMeasuredOnASampledWindowWithoutAllocating) {
  cv::Mat frame = skyFrame(cv::Size(1920, 1080), 140.0, 3.0);
  cv::circle(frame, cv::Point(960, 540), 250, cv::Scalar(60), cv::FILLED);
  const core::TargetContrast contrast;
  const cv::Rect2f box(700.0f, 280.0f, 520.0f, 520.0f);
  float on_target = 0.0f;
#ifdef OT_COUNT_ALLOCATIONS
  g_allocations = 0;
  g_counting = true;
#endif
  on_target = contrast.measure(frame, box);
#ifdef OT_COUNT_ALLOCATIONS
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 0);
#endif
  EXPECT_GT(on_target, 20.0f);
  const cv::Mat sky = skyFrame(cv::Size(1920, 1080), 140.0, 3.0, 9);
  EXPECT_LT(contrast.measure(sky, box), core::TargetContrast::kFloor);
}

TEST(TargetContrast, LostOnlyWhenNothingStandsOutOfAnObjectThatDidAtItsStart) {
  using C = core::TargetContrast;
  EXPECT_FALSE(C::lost(40.0f, 8.0f));   // faded to a fifth, still well out of the noise
  EXPECT_TRUE(C::lost(40.0f, 2.0f));    // nothing there
  EXPECT_FALSE(C::lost(4.0f, 1.0f));    // started on a faint or textured object: no check
  EXPECT_FALSE(C::lost(0.0f, 0.0f));    // unknown at the start (box at the frame's edge)
  EXPECT_TRUE(C::lost(C::kMinReference, 0.5f * C::kMinReference - 0.01f));
}

TEST(TargetContrast, BadInputMeasuresZero) {
  const core::TargetContrast contrast;
  const cv::Mat grey(120, 160, CV_8UC1, cv::Scalar(50));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(contrast.measure(cv::Mat(), cv::Rect2f(10, 10, 20, 20)), 0.0f);
  EXPECT_EQ(contrast.measure(cv::Mat(120, 160, CV_16UC1, cv::Scalar(0)), cv::Rect2f(10, 10, 20, 20)), 0.0f);
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(nan, 10, 20, 20)), 0.0f);
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(10, 10, 0.5f, 20)), 0.0f);
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(500, 500, 20, 20)), 0.0f);  // outside the frame
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(-1e30f, 10, 1e30f, 20)), 0.0f);
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(0, 0, 160, 120)), 0.0f);  // no ring left
}
