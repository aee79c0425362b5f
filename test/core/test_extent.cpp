// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// ExtentGrower (extent_grower.h): from a salient region's bright core to the object's visible
// extent, with known answers on blurred blobs, and the cases where the core must come back as it
// is (object joined to the surroundings, no contrast, bad input).
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "alloc_counter.h"
#include "noisy_frame.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/extent_grower.h"

namespace core = obstacle_tracker::core;

namespace {

constexpr double kShare = 0.1;  // extent_contrast's default

// A Gaussian blob (amplitude a, sigma s) centred at c on a flat background with noise.
cv::Mat blobFrame(cv::Size size, cv::Point2f c, double s, double a, double background, double noise,
                  unsigned seed = 7) {
  cv::Mat f(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const double r2 = (x + 0.5 - c.x) * (x + 0.5 - c.x) + (y + 0.5 - c.y) * (y + 0.5 - c.y);
      f.at<float>(y, x) = static_cast<float>(background + a * std::exp(-r2 / (2.0 * s * s)));
    }
  }
  return obstacle_tracker::testing::withNoiseAs8Bit(f, noise, seed);
}

// The blob's pixels above half its amplitude: the box Otsu gives of a blob on a flat background.
cv::Rect2f halfMaxBox(cv::Point2f c, double s) {
  const float r = static_cast<float>(s * std::sqrt(2.0 * std::log(2.0)));
  return {c.x - r, c.y - r, 2.0f * r, 2.0f * r};
}

}  // namespace

TEST(ExtentGrower, BlurredBlobGrowsToItsVisibleExtent) {
  // Where the profile a exp(-r^2 / 2 s^2) falls to kShare x its peak: r = s sqrt(2 ln(1/kShare)).
  core::ExtentGrower grower;
  for (const double s : {1.5, 2.0, 3.0, 5.0}) {
    const cv::Point2f c(60.3f, 41.7f);
    const cv::Mat frame = blobFrame(cv::Size(120, 90), c, s, 120.0, 60.0, 1.0);
    const cv::Rect2f core_box = halfMaxBox(c, s);
    const cv::Rect2f grown = grower.grow(frame, core_box, kShare);
    const double expected = 2.0 * s * std::sqrt(2.0 * std::log(1.0 / kShare));
    SCOPED_TRACE(s);
    EXPECT_NEAR(grown.width, expected, 1.5);
    EXPECT_NEAR(grown.height, expected, 1.5);
    EXPECT_NEAR(core::boxCentre(grown).x, c.x, 0.75);
    EXPECT_NEAR(core::boxCentre(grown).y, c.y, 0.75);
    EXPECT_GT(grown.area(), 2.0f * core_box.area());
    // The grown box always contains the core.
    EXPECT_EQ((grown & core_box).area(), core_box.area());
  }
}

TEST(ExtentGrower, HigherShareGrowsLess) {
  core::ExtentGrower grower;
  const cv::Point2f c(50.0f, 50.0f);
  const cv::Mat frame = blobFrame(cv::Size(100, 100), c, 3.0, 120.0, 60.0, 1.0);
  const cv::Rect2f core_box = halfMaxBox(c, 3.0);
  const float w10 = grower.grow(frame, core_box, 0.1).width;
  const float w30 = grower.grow(frame, core_box, 0.3).width;
  EXPECT_GT(w10, w30 + 1.0f);
  EXPECT_GE(w30, core_box.width);
  // 0 switches the step off.
  EXPECT_EQ(grower.grow(frame, core_box, 0.0), core_box);
}

TEST(ExtentGrower, DarkObjectOnBrightSkyAndColour) {
  core::ExtentGrower grower;
  const cv::Point2f c(40.0f, 30.0f);
  // A dark blob (a silhouette against a bright sky): contrast is |pixel - background|.
  cv::Mat grey = blobFrame(cv::Size(80, 60), c, 2.0, -100.0, 200.0, 1.0);
  const cv::Rect2f core_box = halfMaxBox(c, 2.0);
  const cv::Rect2f g1 = grower.grow(grey, core_box, kShare);
  EXPECT_GT(g1.width, core_box.width + 2.0f);
  // The same blob in one channel of a BGR frame: the channel with the contrast counts.
  cv::Mat bgr;
  cv::Mat flat(grey.size(), CV_8U, cv::Scalar(200));
  cv::merge(std::vector<cv::Mat>{flat, grey, flat}, bgr);
  const cv::Rect2f g3 = grower.grow(bgr, core_box, kShare);
  EXPECT_NEAR(g3.width, g1.width, 1.0);
  EXPECT_NEAR(g3.height, g1.height, 1.0);
}

TEST(ExtentGrower, ObjectJoinedToItsSurroundingsKeepsTheCore) {
  // A small blob on a thin bar that runs out of the window to one side (a wire, an edge of the
  // scene): the bar is not the object's own extent, although the box would grow only about 2x.
  core::ExtentGrower grower;
  const cv::Point2f c(60.0f, 40.0f);
  cv::Mat frame = blobFrame(cv::Size(120, 80), c, 2.0, 150.0, 60.0, 0.5);
  cv::line(frame, cv::Point(60, 40), cv::Point(119, 40), cv::Scalar(150));
  const cv::Rect2f core_box(57.0f, 37.0f, 6.0f, 6.0f);
  EXPECT_EQ(grower.grow(frame, core_box, kShare), core_box);
  // Without the bar the same blob grows.
  const cv::Mat alone = blobFrame(cv::Size(120, 80), c, 2.0, 150.0, 60.0, 0.5);
  EXPECT_GT(grower.grow(alone, core_box, kShare).area(), core_box.area());
  // A core on flat noise (nothing stands out) comes back unchanged too.
  const cv::Mat noise = blobFrame(cv::Size(120, 80), c, 2.0, 0.0, 60.0, 2.0);
  EXPECT_EQ(grower.grow(noise, core_box, kShare), core_box);
}

TEST(ExtentGrower, GrowthIsBounded) {
  // A bright 3x3 core inside a dimmer disc of radius 5 (a third of the core's contrast): the disc
  // is object by the contrast rule and lies inside the window, but would take the box to 11x11,
  // more than 4x the 4x4 core, which is refused.
  core::ExtentGrower grower;
  cv::Mat frame = blobFrame(cv::Size(120, 120), cv::Point2f(60.5f, 60.5f), 1.0, 0.0, 60.0, 0.5);
  cv::circle(frame, cv::Point(60, 60), 5, cv::Scalar(125), cv::FILLED);
  cv::rectangle(frame, cv::Point(59, 59), cv::Point(61, 61), cv::Scalar(255), cv::FILLED);
  const cv::Rect2f core_box(58.5f, 58.5f, 4.0f, 4.0f);
  EXPECT_EQ(grower.grow(frame, core_box, kShare), core_box);
  // A disc of radius 3 (7x7, 3x the core) is taken.
  frame = blobFrame(cv::Size(120, 120), cv::Point2f(60.5f, 60.5f), 1.0, 0.0, 60.0, 0.5);
  cv::circle(frame, cv::Point(60, 60), 3, cv::Scalar(125), cv::FILLED);
  cv::rectangle(frame, cv::Point(59, 59), cv::Point(61, 61), cv::Scalar(255), cv::FILLED);
  const cv::Rect2f grown = grower.grow(frame, core_box, kShare);
  EXPECT_NEAR(grown.width, 7.0f, 0.6f);
  EXPECT_NEAR(grown.height, 7.0f, 0.6f);
}

TEST(ExtentGrower, BadInputReturnsTheBoxUnchanged) {
  core::ExtentGrower grower;
  const cv::Mat frame = blobFrame(cv::Size(64, 48), cv::Point2f(32.0f, 24.0f), 2.0, 120.0, 60.0, 1.0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const cv::Rect2f boxes[] = {{nan, 20.0f, 4.0f, 4.0f},   {30.0f, 20.0f, inf, 4.0f},  {30.0f, 20.0f, 0.5f, 4.0f},
                              {-500.0f, -500.0f, 4.0f, 4.0f}, {1e30f, 1e30f, 1e30f, 1e30f}, {62.0f, 46.0f, 2.0f, 2.0f},
                              {-1e9f, -1e9f, 3e9f, 3e9f}};
  for (const cv::Rect2f& b : boxes) {
    const cv::Rect2f out = grower.grow(frame, b, kShare);
    const bool same = (out.x == b.x || (std::isnan(out.x) && std::isnan(b.x))) && out.y == b.y &&
                      out.width == b.width && out.height == b.height;
    EXPECT_TRUE(same) << b << " -> " << out;
  }
  EXPECT_EQ(grower.grow(cv::Mat(), cv::Rect2f(1, 1, 4, 4), kShare), cv::Rect2f(1, 1, 4, 4));
  const cv::Mat f32(48, 64, CV_32F, cv::Scalar(0));
  EXPECT_EQ(grower.grow(f32, cv::Rect2f(1, 1, 4, 4), kShare), cv::Rect2f(1, 1, 4, 4));
}

TEST(ExtentGrower, NoAllocationAfterTheLargestWindow) {
  OT_SKIP_UNLESS_COUNTING_ALLOCATIONS();
  core::ExtentGrower grower;
  const cv::Mat frame = blobFrame(cv::Size(200, 160), cv::Point2f(100.0f, 80.0f), 4.0, 120.0, 60.0, 1.0);
  grower.grow(frame, halfMaxBox(cv::Point2f(100.0f, 80.0f), 4.0), kShare);  // largest window first
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < 50; ++i) {
    const double s = 1.0 + 0.06 * i;
    grower.grow(frame, halfMaxBox(cv::Point2f(100.0f, 80.0f), s), kShare);
  }
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 0);
}
