// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known answers of the generated `recede` scene (scene_scenarios.cpp): an aircraft flying away
// from the camera, its distance growing linearly in time.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "obstacle_tracker/scene/scene_generator.h"

namespace os = obstacle_tracker::scene;

namespace {

cv::Point2d centreOf(const cv::Rect2f& b) { return {b.x + 0.5 * b.width, b.y + 0.5 * b.height}; }

}  // namespace

// The apparent size falls as 1 / distance, to a sixth of the start's over the clip; never
// closing, so the time to contact is +inf.
TEST(SceneRecede, ShrinksAsTheDistanceGrows) {
  auto g = os::makeScenario("recede", 21, 90, cv::Size(320, 240));
  ASSERT_EQ(g.info().obstacles.size(), 1u);
  EXPECT_TRUE(std::isinf(g.info().obstacles[0].time_to_contact_at_start));
  const os::ObstacleTruth o0 = *g.truth(0).find(1);
  const os::ObstacleTruth o1 = *g.truth(1).find(1);
  const double speed = (o1.distance_m - o0.distance_m) * g.fps();  // m/s away from the camera
  ASSERT_GT(speed, 0.0);
  for (int i = 10; i < g.frameCount(); i += 10) {
    const os::FrameTruth ti = g.truth(i);
    const os::ObstacleTruth& o = *ti.find(1);
    EXPECT_TRUE(std::isinf(o.time_to_contact)) << "frame " << i;
    EXPECT_NEAR(o.distance_m, o0.distance_m + speed * i / g.fps(), 1e-6 * o.distance_m) << "frame " << i;
    // The outline is the union over the exposure, in which a near, fast-shrinking start moves
    // most: the drawn box within a few pixels of the size law.
    const double k = o0.scale_px / o.scale_px;
    EXPECT_NEAR(o.box.width, o0.box.width / k, 3.0) << "frame " << i;
    EXPECT_NEAR(o.box.height, o0.box.height / k, 3.0) << "frame " << i;
  }
  const os::FrameTruth tl = g.truth(g.frameCount() - 1);
  EXPECT_NEAR(o0.scale_px / tl.find(1)->scale_px, 6.0, 0.2);
}

// The centre moves on a straight line towards one point, its distance from it proportional to
// the size: (c(t) - c(0)) = (k(t) - 1) (c(0) - focus) with k the size relative to the start.
TEST(SceneRecede, CentreConvergesOnOnePoint) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    auto g = os::makeScenario("recede", seed, 90, cv::Size(640, 480));
    const os::ObstacleTruth o0 = *g.truth(0).find(1);
    const os::ObstacleTruth om = *g.truth(45).find(1);
    const os::ObstacleTruth ol = *g.truth(89).find(1);
    const double km = om.scale_px / o0.scale_px, kl = ol.scale_px / o0.scale_px;
    const cv::Point2d c0 = centreOf(o0.shape_box), cm = centreOf(om.shape_box), cl = centreOf(ol.shape_box);
    const cv::Point2d predicted = c0 + (cm - c0) * ((kl - 1.0) / (km - 1.0));
    EXPECT_NEAR(cl.x, predicted.x, 1.5) << "seed " << seed;
    EXPECT_NEAR(cl.y, predicted.y, 1.5) << "seed " << seed;
  }
}

// Even the `large` aircraft is wholly in view at the start.
TEST(SceneRecede, LargeStartsInView) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    auto g = os::makeScenario("recede+large", seed, 60, cv::Size(640, 480));
    const os::FrameTruth t0 = g.truth(0);
    EXPECT_GE(t0.find(1)->visible_fraction, 0.999) << "seed " << seed;
  }
}
