// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// FrameInterval (frame_interval.h): the usual interval between frames and the time lost to
// frames dropped upstream, from the stamps alone.
#include <limits>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/frame_interval.h"

namespace core = obstacle_tracker::core;

TEST(FrameInterval, SteadyStreamHasItsPeriodAndNoDrops) {
  core::FrameInterval f;
  EXPECT_EQ(f.usual(), 0.0);
  f.add(10.0);
  EXPECT_EQ(f.usual(), 0.0);
  EXPECT_EQ(f.last(), 0.0);
  EXPECT_EQ(f.dropped(), 0.0);
  for (int i = 1; i < 40; ++i) {
    f.add(10.0 + i / 30.0);
    EXPECT_NEAR(f.usual(), 1.0 / 30.0, 1e-9);
    EXPECT_EQ(f.dropped(), 0.0) << "frame " << i;
  }
}

TEST(FrameInterval, GapCountsTheTimeBeyondOneUsualInterval) {
  core::FrameInterval f;
  for (int i = 0; i < 10; ++i) f.add(i * 0.1);
  f.add(1.3);  // frames 10, 11 and 12 dropped
  EXPECT_NEAR(f.last(), 0.4, 1e-9);
  EXPECT_NEAR(f.usual(), 0.1, 1e-9);  // one long interval does not move the median
  EXPECT_NEAR(f.dropped(), 0.3, 1e-9);
  f.add(1.4);
  EXPECT_EQ(f.dropped(), 0.0);
  // Jitter under half an interval is not a drop.
  f.add(1.54);
  EXPECT_EQ(f.dropped(), 0.0);
}

TEST(FrameInterval, UsualIntervalIsTheMedianWhileFewerThanHalfAreGaps) {
  core::FrameInterval f;
  double t = 0.0;
  f.add(t);
  // Every third interval is a gap of two frames: the median stays one frame.
  for (int i = 0; i < 30; ++i) {
    t += (i % 3 == 2) ? 0.2 : 0.1;
    f.add(t);
  }
  EXPECT_NEAR(f.usual(), 0.1, 1e-9);
  // A stream whose frames all come at half the rate has that rate as its usual interval.
  for (int i = 0; i < core::FrameInterval::kWindow; ++i) {
    t += 0.2;
    f.add(t);
  }
  EXPECT_NEAR(f.usual(), 0.2, 1e-9);
  EXPECT_EQ(f.dropped(), 0.0);
}

TEST(FrameInterval, EpochStampsWithJitterAreNoDrops) {
  // Camera stamps are seconds since 1970: the intervals' rounding, and jitter of a fifth of a
  // period, stay far from a dropped frame.
  core::FrameInterval f;
  const double jitter[] = {0.2, -0.2, 0.1, 0.0, -0.1};
  for (int i = 0; i < 200; ++i) {
    f.add(1.7e9 + (i + jitter[i % 5]) / 30.0);
    EXPECT_EQ(f.dropped(), 0.0) << "frame " << i;
  }
  EXPECT_NEAR(f.usual(), 1.0 / 30.0, 0.01);
}

TEST(FrameInterval, BackwardsStampStartsOverAndBadStampsAreIgnored) {
  core::FrameInterval f;
  for (int i = 0; i < 5; ++i) f.add(100.0 + i);
  EXPECT_NEAR(f.usual(), 1.0, 1e-9);
  f.add(std::numeric_limits<double>::quiet_NaN());
  f.add(std::numeric_limits<double>::infinity());
  EXPECT_NEAR(f.usual(), 1.0, 1e-9);
  f.add(104.0);  // a repeated stamp: no interval
  EXPECT_NEAR(f.usual(), 1.0, 1e-9);
  EXPECT_EQ(f.dropped(), 0.0);
  f.add(3.0);  // backwards (a replayed bag): a new stream
  EXPECT_EQ(f.usual(), 0.0);
  f.add(3.5);
  EXPECT_NEAR(f.usual(), 0.5, 1e-9);
  f.reset();
  EXPECT_EQ(f.usual(), 0.0);
  EXPECT_EQ(f.last(), 0.0);
}
