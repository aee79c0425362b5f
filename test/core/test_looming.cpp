// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/looming.h"

using obstacle_tracker::core::LoomingEstimator;

namespace {

// s(t) = s0 * T / (T - t): constant closing speed, contact at t = T.
double approachSize(double s0, double T, double t) { return s0 * T / (T - t); }

}  // namespace

TEST(Looming, KnownTimeToContactWithin10PercentAfter10Frames) {
  const double fps = 30.0, T = 4.0, s0 = 20.0;
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.004);  // 0.4 % size noise per frame
    LoomingEstimator est(15);
    for (int k = 0; k < 90; ++k) {
      const double t = k / fps;
      const double s = approachSize(s0, T, t) * (1.0 + noise(rng));
      // Boxes of changing aspect: only sqrt(w*h) matters.
      const double aspect = 1.5 + 0.2 * std::sin(k * 0.1);
      est.add(t, cv::Rect2f(100.f, 50.f, static_cast<float>(s * std::sqrt(aspect)),
                            static_cast<float>(s / std::sqrt(aspect))));
      if (k >= 10) {
        const double truth = T - t;
        EXPECT_NEAR(est.timeToContact(), truth, 0.1 * truth) << "seed " << seed << " frame " << k;
        EXPECT_NEAR(est.expansionRate(), 1.0 / truth, 0.1 / truth);
      }
    }
  }
}

TEST(Looming, RecedingAndSteadyGiveInfiniteTimeToContact) {
  LoomingEstimator est(10);
  for (int k = 0; k < 20; ++k) est.addSize(k / 30.0, 50.0 * std::exp(-0.3 * k / 30.0));
  EXPECT_NEAR(est.expansionRate(), -0.3, 1e-9);
  EXPECT_TRUE(std::isinf(est.timeToContact()));
  est.reset();
  for (int k = 0; k < 20; ++k) est.addSize(k / 30.0, 50.0);
  EXPECT_NEAR(est.expansionRate(), 0.0, 1e-12);
  EXPECT_TRUE(std::isinf(est.timeToContact()));
}

TEST(Looming, NeedsThreeSamples) {
  LoomingEstimator est(10);
  est.addSize(0.0, 10.0);
  est.addSize(0.1, 11.0);
  EXPECT_EQ(est.expansionRate(), 0.0);
  EXPECT_TRUE(std::isinf(est.timeToContact()));
  est.addSize(0.2, 12.1);
  // Slope log(1.1)/0.1 at the mean time 0.1 s, carried to 0.2 s.
  EXPECT_NEAR(est.timeToContact(), 0.1 / std::log(1.1) - 0.1, 1e-9);
}

TEST(Looming, ResizeAtReDetectionIsNotExpansion) {
  // Constant-speed approach (contact at T = 2 s); at frame 20 a re-detection re-sizes the box
  // by +40 %.
  const double T = 2.0;
  LoomingEstimator with_mark(15), without_mark(15);
  for (int k = 0; k < 30; ++k) {
    const double t = k / 30.0;
    double s = approachSize(30.0, T, t);
    if (k >= 20) s *= 1.4;
    if (k == 20) with_mark.markDiscontinuity();
    with_mark.addSize(t, s);
    without_mark.addSize(t, s);
  }
  const double truth = T - 29 / 30.0;
  EXPECT_NEAR(with_mark.timeToContact(), truth, 0.01 * truth);
  // Without the mark the step would read as a much faster approach.
  EXPECT_LT(without_mark.timeToContact(), 0.5 * truth);
}

TEST(Looming, StampsBackwardsResetEqualStampsReplace) {
  LoomingEstimator est(10);
  for (int k = 0; k < 5; ++k) est.addSize(k * 0.1, 10.0 * std::exp(k * 0.1));
  EXPECT_EQ(est.samples(), 5);
  est.addSize(0.4, 10.0 * std::exp(0.4));  // same stamp: replaced
  EXPECT_EQ(est.samples(), 5);
  est.addSize(0.0, 10.0);  // backwards: history restarts
  EXPECT_EQ(est.samples(), 1);
  EXPECT_EQ(est.expansionRate(), 0.0);
}

TEST(Looming, IgnoresBadInputAndKeepsWindow) {
  LoomingEstimator est(3);
  est.add(0.0, cv::Rect2f(0, 0, 0, 5));
  est.addSize(std::numeric_limits<double>::quiet_NaN(), 5.0);
  est.addSize(0.0, -1.0);
  EXPECT_EQ(est.samples(), 0);
  for (int k = 0; k < 10; ++k) est.addSize(k, k < 7 ? 1.0 : std::exp(-0.2 * (k - 7)));
  EXPECT_EQ(est.samples(), 3);
  EXPECT_NEAR(est.expansionRate(), -0.2, 1e-9);  // only the last 3 samples (receding)
  est.setWindow(1);
  EXPECT_EQ(est.window(), 3);
}
