// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known answers for the box-size filter (size_filter.h): sizes of an object closing or receding at
// a constant speed, of a constant-size object, and noisy measurements of them.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/size_filter.h"

using obstacle_tracker::core::SizeFilter;

namespace {

constexpr double kFps = 30.0;

// s(t) = s0 T / (T - t): contact at T (T < 0: receding, s shrinks as T / (T - t) with T - t < 0).
double approachSize(double s0, double T, double t) { return s0 * T / (T - t); }

// ln of the size ratio from the frame before t to t.
double approachExpansion(double s0, double T, double t) {
  return std::log(approachSize(s0, T, t) / approachSize(s0, T, t - 1.0 / kFps));
}

}  // namespace

TEST(SizeFilter, ConstantSizeHasNoRateAndNoContact) {
  SizeFilter f;
  f.reset(0.0, 40.0, 0.05);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int k = 1; k <= 300; ++k) {
    f.predict(k / kFps);
    f.updateExpansion(noise(rng), 0.01);
    f.updateSize(40.0 * std::exp(noise(rng)), 0.05);
  }
  EXPECT_NEAR(f.size(), 40.0, 0.05 * 40.0);
  EXPECT_NEAR(f.expansionRate(), 0.0, 3.0 * f.expansionRateSigma());
  // Not closing, or closing so uncertainly that the time to contact says nothing yet.
  EXPECT_TRUE(!std::isfinite(f.timeToContact()) || f.timeToContactSigma() > f.timeToContact());
  EXPECT_LT(f.expansionRateSigma(), 0.2);
  EXPECT_GT(f.expansionRateSigma(), 0.0);
}

TEST(SizeFilter, ApproachAtConstantSpeedFromExpansionAlone) {
  // Exact expansions alone (no size measurement at all): the rate and the size follow.
  const double T = 4.0, s0 = 20.0;
  SizeFilter f;
  f.reset(0.0, s0, 0.05);
  int checked = 0, within = 0;
  for (int k = 1; k <= 100; ++k) {
    const double t = k / kFps;
    f.predict(t);
    f.updateExpansion(approachExpansion(s0, T, t), 0.003);
    if (k < 10) continue;
    ++checked;
    const double truth = T - t;
    within += std::abs(f.timeToContact() - truth) <= 0.1 * truth ? 1 : 0;
    EXPECT_NEAR(f.size(), approachSize(s0, T, t), 0.05 * approachSize(s0, T, t)) << "frame " << k;
  }
  EXPECT_GE(within, static_cast<int>(0.95 * checked));
  // The uncertainty propagated to the time to contact covers the error.
  EXPECT_LT(std::abs(f.timeToContact() - (T - 100 / kFps)), 3.0 * f.timeToContactSigma() + 0.05);
}

TEST(SizeFilter, ApproachFromNoisySizesAlone) {
  // No expansion measurement at all (a textureless target): sizes with 5 % noise. The rate comes
  // from the sizes' trend; within 30 % after two seconds.
  const double T = 5.0, s0 = 20.0;
  SizeFilter f;
  f.reset(0.0, s0, 0.05);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  int checked = 0, within = 0;
  for (int k = 1; k <= 120; ++k) {
    const double t = k / kFps;
    f.predict(t);
    f.updateSize(approachSize(s0, T, t) * std::exp(noise(rng)), 0.05);
    if (k < 60) continue;
    ++checked;
    within += std::abs(f.expansionRate() - 1.0 / (T - t)) <= 0.3 / (T - t) ? 1 : 0;
  }
  EXPECT_GE(within, static_cast<int>(0.8 * checked));
}

TEST(SizeFilter, RecedingObjectShrinksAndNeverCloses) {
  const double T = -3.0, s0 = 60.0;  // moving away: s = s0 * 3 / (3 + t)
  SizeFilter f;
  f.reset(0.0, s0, 0.05);
  for (int k = 1; k <= 90; ++k) {
    const double t = k / kFps;
    f.predict(t);
    f.updateExpansion(approachExpansion(s0, T, t), 0.003);
    f.updateSize(approachSize(s0, T, t), 0.05);
  }
  const double t = 90 / kFps;
  EXPECT_NEAR(f.expansionRate(), 1.0 / (T - t), 0.1 * std::abs(1.0 / (T - t)));
  EXPECT_TRUE(std::isinf(f.timeToContact()));
  EXPECT_TRUE(std::isinf(f.timeToContactSigma()));
  EXPECT_NEAR(f.size(), approachSize(s0, T, t), 0.03 * approachSize(s0, T, t));
}

TEST(SizeFilter, ExpansionIsRelativeToThePreviousPredict) {
  // Without motion noise a measured expansion moves the size by that much, whatever the size was.
  SizeFilter f(0.0);
  f.reset(0.0, 10.0, 0.5);
  f.predict(1.0 / kFps);
  f.updateExpansion(std::log(1.01), 1e-6);
  EXPECT_NEAR(f.size(), 10.1, 0.001);
  f.predict(2.0 / kFps);
  f.updateExpansion(0.0, 1e-6);
  EXPECT_NEAR(f.size(), 10.1, 0.001);
}

TEST(SizeFilter, BadValuesChangeNothing) {
  SizeFilter f;
  f.reset(0.0, 30.0, 0.05);
  f.predict(0.1);
  const double size = f.size(), rate = f.expansionRate();
  f.updateExpansion(std::numeric_limits<double>::quiet_NaN(), 0.01);
  f.updateExpansion(0.1, 0.0);
  f.updateSize(-3.0, 0.05);
  f.updateSize(std::numeric_limits<double>::infinity(), 0.05);
  f.predict(0.05);  // back in time
  f.predict(std::numeric_limits<double>::quiet_NaN());
  EXPECT_DOUBLE_EQ(f.size(), size);
  EXPECT_DOUBLE_EQ(f.expansionRate(), rate);
  EXPECT_TRUE(std::isfinite(f.expansionRateSigma()));
  SizeFilter bad;
  bad.reset(0.0, std::numeric_limits<double>::quiet_NaN(), 0.05);
  EXPECT_FALSE(bad.initialized());
  bad.reset(0.0, -1.0, 0.05);
  EXPECT_FALSE(bad.initialized());
}

TEST(SizeFilter, ImminentContactStaysFinite) {
  // Contact at T = 1 s, measured exactly up to 5 ms before it and then a frame after it: the
  // state stays finite (v dt is held at kMaxRateTimesDt) and closing.
  const double T = 1.0;
  SizeFilter f;
  f.reset(0.0, 30.0, 0.05);
  double last = 0.0;
  for (double t : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98, 0.995, 1.03}) {
    f.predict(t);
    const double now = std::min(t, 0.995);
    f.updateExpansion(std::log(approachSize(30.0, T, now) / approachSize(30.0, T, std::min(last, 0.995))), 0.005);
    last = t;
    EXPECT_TRUE(std::isfinite(f.size())) << t;
    EXPECT_TRUE(std::isfinite(f.expansionRate())) << t;
    EXPECT_TRUE(std::isfinite(f.expansionRateSigma())) << t;
  }
  EXPECT_GT(f.expansionRate(), 0.0);
  EXPECT_LT(f.timeToContact(), 0.5);
}

TEST(SizeFilter, GapsDoNotRunAway) {
  // Closing at 1 %/frame, then gaps of 1.5 s (re-detections far apart), 10 s and 1e200 s: the
  // rate never runs away and the state stays finite.
  SizeFilter f;
  f.reset(0.0, 30.0, 0.05);
  double t = 0.0;
  for (int k = 1; k <= 30; ++k) {
    t = k / kFps;
    f.predict(t);
    f.updateExpansion(0.01, 0.005);
  }
  for (int gap = 0; gap < 12; ++gap) {
    t += 1.5;
    f.predict(t);
    f.restartSize(30.0, 0.05);
  }
  EXPECT_LT(f.expansionRate(), 2.0);
  f.predict(t + 10.0);
  f.predict(1e200);
  EXPECT_TRUE(f.initialized());
  EXPECT_TRUE(std::isfinite(f.size()));
  EXPECT_TRUE(std::isfinite(f.expansionRate()));
  EXPECT_TRUE(std::isfinite(f.expansionRateSigma()));
}

TEST(SizeFilter, TrackStartingCloseToContact) {
  // The track starts 0.5 s before contact: per-frame expansions of 7 % and more from the first
  // frame. The first measurements are not gated away; the time to contact is within 20 % after
  // a few frames.
  const double T = 0.5, s0 = 40.0;
  SizeFilter f;
  f.reset(0.0, s0, 0.05);
  for (int k = 1; k <= 9; ++k) {
    const double t = k / kFps;
    f.predict(t);
    f.updateExpansion(approachExpansion(s0, T, t), 0.005);
    if (k >= 5) {
      EXPECT_NEAR(f.timeToContact(), T - t, 0.2 * (T - t)) << "frame " << k;
    }
  }
}

TEST(SizeFilter, OutlierExpansionIsDropped) {
  // Closing steadily at 1 %/frame; one frame measures -10 % (an occluder aligned instead of the
  // object): the gate drops it, the rate is not thrown.
  SizeFilter f;
  f.reset(0.0, 30.0, 0.05);
  for (int k = 1; k <= 60; ++k) {
    f.predict(k / kFps);
    f.updateExpansion(k == 40 ? -0.10 : 0.01, 0.005);
    if (k == 39 || k == 40) {
      EXPECT_GT(f.expansionRate(), 0.2) << k;
    }
  }
  EXPECT_NEAR(f.expansionRate(), 0.3, 0.05);
}

TEST(SizeFilter, RestartKeepsTheRate) {
  SizeFilter f;
  f.reset(0.0, 30.0, 0.05);
  for (int k = 1; k <= 60; ++k) {
    f.predict(k / kFps);
    f.updateExpansion(0.01, 0.005);
  }
  const double rate = f.expansionRate();
  f.predict(61 / kFps);
  f.restartSize(20.0, 0.05);  // a re-detected box of another size: not an expansion
  EXPECT_NEAR(f.size(), 20.0, 1e-9);
  EXPECT_NEAR(f.expansionRate(), rate * (1.0 / (1.0 - rate / kFps)), 1e-9);
}
