// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// KcfTracker's known answers: sub-pixel shifts, scale, occlusion, evaluate / shifted search, and
// detect + learn against update.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "kcf_test_frames.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/kcf.h"

namespace oc = obstacle_tracker::core;
using obstacle_tracker::core::boxCentre;
using obstacle_tracker::test::makeTexture;
using obstacle_tracker::test::renderFrame;
using obstacle_tracker::test::shiftedPattern;

class KcfSubPixel : public ::testing::TestWithParam<int> {};

TEST_P(KcfSubPixel, KnownShiftsAreFoundWithinAQuarterPixel) {
  const int type = GetParam();
  const cv::Mat tex = makeTexture(320, 1);
  const cv::Size fs(320, 240);
  const double cx = 160.0, cy = 120.0;
  const std::vector<cv::Point2d> shifts = {{0.25, 0.0},  {0.0, -0.5}, {1.3, 0.7},  {-2.6, 1.85},
                                           {3.4, -3.1},  {-0.8, -4.3}, {5.5, 2.25}, {-6.2, -1.4}};
  const cv::Mat first = shiftedPattern(tex, fs, 0.0, 0.0, type);
  oc::Params p;
  p.scale_count = 1;  // pure translation
  for (double side : {24.0, 40.0, 64.0}) {
    double worst = 0.0;
    for (const auto& d : shifts) {
      oc::KcfTracker kcf(p);
      kcf.init(first, cv::Rect2f(static_cast<float>(cx - side / 2), static_cast<float>(cy - side / 2),
                                 static_cast<float>(side), static_cast<float>(side)));
      const oc::KcfResult r = kcf.update(shiftedPattern(tex, fs, d.x, d.y, type));
      const cv::Point2f c = boxCentre(r.box);
      const double err = std::hypot(c.x - (cx + d.x), c.y - (cy + d.y));
      worst = std::max(worst, err);
      EXPECT_LT(err, 0.25) << "box side " << side << " shift " << d << " found "
                           << c - cv::Point2f(static_cast<float>(cx), static_cast<float>(cy));
      EXPECT_GT(r.peak, 0.5);
      EXPECT_GT(r.confidence, 0.5);
    }
    RecordProperty("worst_error_px_side_" + std::to_string(static_cast<int>(side)),
                   std::to_string(worst));
  }
}

INSTANTIATE_TEST_SUITE_P(GreyAndColour, KcfSubPixel, ::testing::Values(CV_8UC1, CV_8UC3));

// Scale search (3 scales) and the DSST scale filter (17 scales) must both follow a growing and then
// shrinking pattern.
class KcfScale : public ::testing::TestWithParam<bool> {};

TEST_P(KcfScale, FollowsAGrowingPatternWithin5PercentScale) {
  const cv::Mat bg = makeTexture(160, 3);
  const cv::Mat obj = makeTexture(64, 4);
  const cv::Size fs(320, 240);
  const double side0 = 40.0;
  oc::Params p;
  p.kcf_scale_filter = GetParam();
  if (p.kcf_scale_filter) {
    p.scale_count = 17;
    p.scale_step = 1.03;
  } else {
    p.scale_count = 3;
    p.scale_step = 1.05;
  }
  oc::KcfTracker kcf(p);
  kcf.init(renderFrame(bg, obj, fs, 150, 120, side0, CV_8UC1),
           cv::Rect2f(150 - 20, 120 - 20, 40, 40));
  // 1.0 -> 1.15 over 10 frames while drifting right.
  double side = side0;
  double x = 150.0;
  oc::KcfResult r;
  for (int i = 1; i <= 10; ++i) {
    side = side0 * (1.0 + 0.015 * i);
    x += 1.5;
    r = kcf.update(renderFrame(bg, obj, fs, x, 120, side, CV_8UC1));
  }
  const double est = std::sqrt(r.box.area()) / side0;
  EXPECT_NEAR(est, side / side0, 0.05 * side / side0) << "estimated scale " << est;
  EXPECT_LT(cv::norm(boxCentre(r.box) - cv::Point2f(static_cast<float>(x), 120.0f)), 2.0);
  // And shrinking back to 1.0 over 10 frames, then 3 frames at that size (the scale filter's
  // model trails a fast shrink by a few frames).
  for (int i = 1; i <= 13; ++i) {
    side = side0 * 1.15 * (1.0 - 0.013 * std::min(i, 10));
    r = kcf.update(renderFrame(bg, obj, fs, x, 120, side, CV_8UC1));
  }
  const double est2 = std::sqrt(r.box.area()) / side0;
  EXPECT_NEAR(est2, side / side0, 0.05 * side / side0) << "estimated scale " << est2;
}

INSTANTIATE_TEST_SUITE_P(SearchAndFilter, KcfScale, ::testing::Values(false, true));

// The three-scale search's step against the size trend given from outside (setSizeTrend): a
// pattern growing 2 % a frame. Without a trend given, and with a growing trend, the first step
// comes on the same frame; with no trend (0) or a shrinking one, scale_confirm_frames - 1 frames
// later (the larger scale must win that many frames in a row).
TEST(KcfScaleConfirmation, AStepWaitsUnlessTheTrendAgrees) {
  const cv::Mat bg = makeTexture(160, 3);
  const cv::Mat obj = makeTexture(64, 4);
  const cv::Size fs(320, 240);
  oc::Params p;
  p.scale_confirm_frames = 4;
  int first_step[4] = {0, 0, 0, 0};  // per trend + 1: the frame the box first grew
  for (int trend : {2, 1, 0, -1}) {  // 2: setSizeTrend never called
    oc::KcfTracker kcf(p);
    kcf.init(renderFrame(bg, obj, fs, 160, 120, 40.0, CV_8UC1), cv::Rect2f(140, 100, 40, 40));
    for (int k = 1; k <= 20 && first_step[trend + 1] == 0; ++k) {
      if (trend <= 1) kcf.setSizeTrend(trend);
      const cv::Mat frame = renderFrame(bg, obj, fs, 160, 120, 40.0 * (1.0 + 0.02 * k), CV_8UC1);
      const double side = std::sqrt(kcf.update(frame).box.area());
      if (side > 40.5) first_step[trend + 1] = k;
    }
  }
  const int at_once = first_step[3];  // no trend given
  ASSERT_GT(at_once, 0) << "the box never grew";
  EXPECT_EQ(first_step[2], at_once) << "growing trend";
  EXPECT_EQ(first_step[1], at_once + p.scale_confirm_frames - 1) << "no trend";
  EXPECT_EQ(first_step[0], at_once + p.scale_confirm_frames - 1) << "shrinking trend";
  oc::KcfTracker kcf(p);
  EXPECT_THROW(kcf.setSizeTrend(2), std::invalid_argument);
  EXPECT_THROW(kcf.setSizeTrend(-2), std::invalid_argument);
}

TEST(Kcf, FullOcclusionDropsConfidenceAndFreezesTheModel) {
  const cv::Mat bg = makeTexture(160, 5);
  const cv::Mat obj = makeTexture(64, 6);
  const cv::Size fs(320, 240);
  oc::Params p;
  oc::KcfTracker kcf(p);
  const cv::Rect2f box(140, 100, 40, 40);
  const cv::Mat visible = renderFrame(bg, obj, fs, 160, 120, 40, CV_8UC1);
  kcf.init(visible, box);
  oc::KcfResult before;
  for (int i = 0; i < 5; ++i) before = kcf.update(visible);
  EXPECT_TRUE(before.model_updated);
  EXPECT_GT(before.confidence, 0.7);
  // A uniform occluder (a flat grey board much bigger than the window) covers the target.
  cv::Mat occluded = visible.clone();
  occluded(cv::Rect(60, 20, 200, 200)).setTo(128);
  const oc::KcfResult evaluated_before = kcf.evaluate(visible, box);
  for (int i = 0; i < 5; ++i) {
    const oc::KcfResult r = kcf.update(occluded);
    EXPECT_LT(r.confidence, p.learn_threshold);
    EXPECT_LT(r.peak, 0.5f * before.peak);
    EXPECT_LT(r.psr, 8.0f);  // a flat response
    EXPECT_FALSE(r.model_updated);
  }
  // The model did not learn the occluder: on the visible target it answers as before.
  const oc::KcfResult evaluated_after = kcf.evaluate(visible, box);
  EXPECT_FLOAT_EQ(evaluated_after.peak, evaluated_before.peak);
  // A textured occluder (another random pattern) also drops the confidence.
  cv::Mat other = renderFrame(bg, makeTexture(64, 99), fs, 160, 120, 80, CV_8UC1);
  kcf.init(visible, box);
  for (int i = 0; i < 3; ++i) kcf.update(visible);
  const oc::KcfResult r = kcf.update(other);
  EXPECT_LT(r.confidence, p.learn_threshold);
  EXPECT_FALSE(r.model_updated);
}

TEST(Kcf, EvaluateDoesNotChangeStateAndRanksCandidates) {
  const cv::Mat bg = makeTexture(160, 7);
  const cv::Mat obj = makeTexture(64, 8);
  const cv::Size fs(320, 240);
  const cv::Mat frame = renderFrame(bg, obj, fs, 100, 100, 30, CV_8UC3);
  oc::KcfTracker a, b;
  const cv::Rect2f box(85, 85, 30, 30);
  a.init(frame, box);
  b.init(frame, box);
  const oc::KcfResult on_target = a.evaluate(frame, cv::Rect2f(87, 84, 30, 30));
  const oc::KcfResult off_target = a.evaluate(frame, cv::Rect2f(220, 150, 30, 30));
  EXPECT_GT(on_target.peak, 0.6);
  EXPECT_GT(on_target.confidence, 0.6);
  EXPECT_LT(off_target.confidence, 0.3);
  EXPECT_NEAR(boxCentre(on_target.box).x, 100.0, 0.5);
  EXPECT_NEAR(boxCentre(on_target.box).y, 100.0, 0.5);
  EXPECT_FALSE(on_target.model_updated);
  // a evaluated twice, b never: their next updates are identical.
  const cv::Mat next = renderFrame(bg, obj, fs, 103, 98, 30, CV_8UC3);
  const oc::KcfResult ra = a.update(next);
  const oc::KcfResult rb = b.update(next);
  EXPECT_EQ(ra.box, rb.box);
  EXPECT_EQ(ra.peak, rb.peak);
}

TEST(Kcf, ShiftedSearchFindsATargetBeyondTheWindow) {
  // The target jumps two box sides between two frames (frames dropped in between): around its
  // old box the filter cannot see it; searching around the caller's prediction finds it.
  const cv::Mat bg = makeTexture(160, 21);
  const cv::Mat obj = makeTexture(64, 22);
  const cv::Size fs(320, 240);
  const cv::Mat f0 = renderFrame(bg, obj, fs, 100, 120, 30, CV_8UC3);
  const cv::Mat f1 = renderFrame(bg, obj, fs, 160, 120, 30, CV_8UC3);
  const cv::Rect2f box(85, 105, 30, 30);
  oc::KcfTracker plain, shifted;
  EXPECT_THROW(shifted.shiftSearch(cv::Point2f(1.0f, 0.0f)), std::logic_error);
  plain.init(f0, box);
  shifted.init(f0, box);
  shifted.shiftSearch(cv::Point2f(std::nanf(""), 0.0f));  // ignored
  EXPECT_EQ(shifted.box(), plain.box());
  shifted.shiftSearch(cv::Point2f(56.0f, 3.0f));  // a prediction a few pixels off
  EXPECT_NEAR(boxCentre(shifted.box()).x, 156.0, 1e-3);
  const oc::KcfResult rp = plain.update(f1);
  const oc::KcfResult rs = shifted.update(f1);
  EXPECT_GT(std::abs(boxCentre(rp.box).x - 160.0), 10.0) << "the jump should be beyond the unshifted search";
  EXPECT_NEAR(boxCentre(rs.box).x, 160.0, 1.0);
  EXPECT_NEAR(boxCentre(rs.box).y, 120.0, 1.0);
  EXPECT_GT(rs.confidence, 0.6);
  EXPECT_GT(rs.peak, rp.peak);
}

TEST(Kcf, DetectThenLearnEqualsUpdate) {
  const cv::Mat bg = makeTexture(160, 14);
  const cv::Mat obj = makeTexture(64, 15);
  const cv::Size fs(320, 240);
  for (bool filter : {false, true}) {
    oc::Params p;
    p.kcf_scale_filter = filter;
    oc::KcfTracker a(p), b(p), c(p);
    const cv::Rect2f box(80, 80, 40, 40);
    const cv::Mat f0 = renderFrame(bg, obj, fs, 100, 100, 40, CV_8UC3);
    a.init(f0, box);
    b.init(f0, box);
    c.init(f0, box);
    for (int i = 1; i <= 4; ++i) {
      const cv::Mat f = renderFrame(bg, obj, fs, 100 + 2 * i, 100 - i, 40 + i, CV_8UC3);
      const oc::KcfResult ra = a.update(f);
      const oc::KcfResult rb = b.detect(f);
      const oc::KcfResult rc = c.detect(f);  // never learns
      ASSERT_TRUE(ra.model_updated);
      EXPECT_FALSE(rb.model_updated);
      EXPECT_FALSE(rc.model_updated);
      b.learn(f);
      EXPECT_EQ(ra.box, rb.box);
      EXPECT_EQ(ra.peak, rb.peak);
    }
    const cv::Mat last = renderFrame(bg, obj, fs, 112, 94, 46, CV_8UC3);
    const oc::KcfResult ra = a.update(last);
    const oc::KcfResult rb = b.update(last);
    const oc::KcfResult rc = c.update(last);
    EXPECT_EQ(ra.box, rb.box) << "scale filter " << filter;
    EXPECT_EQ(ra.peak, rb.peak);
    EXPECT_NE(ra.peak, rc.peak);  // c's model is still the first frame's
  }
}
