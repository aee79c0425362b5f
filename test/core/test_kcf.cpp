// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/kcf.h"

namespace oc = obstacle_tracker::core;

namespace {

// A smooth random texture (band-limited noise), tileable by construction is not needed: frames are
// rendered from it with an exact sub-pixel affine map, so the "true" motion is known.
cv::Mat makeTexture(int size, int seed) {
  cv::Mat noise(size, size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat out;
  noise.convertTo(out, CV_8U);
  return out;
}

// Renders a frame: a background texture, and a target texture of side `side` * scale centred at
// (cx, cy). Sub-pixel positions and scales come from warpAffine with bilinear sampling.
cv::Mat renderFrame(const cv::Mat& bg, const cv::Mat& obj, cv::Size frame_size, double cx,
                    double cy, double side, int type) {
  cv::Mat frame;
  cv::resize(bg, frame, frame_size, 0, 0, cv::INTER_LINEAR);
  const double s = side / obj.cols;
  const cv::Matx23d m(s, 0.0, cx - 0.5 * side + 0.5 * s - 0.5, 0.0, s,
                      cy - 0.5 * side + 0.5 * s - 0.5);
  cv::Mat warped, mask;
  cv::warpAffine(obj, warped, m, frame_size, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  cv::Mat ones(obj.size(), CV_8U, cv::Scalar(255));
  cv::warpAffine(ones, mask, m, frame_size, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  // Alpha blend with the (anti-aliased) mask so the object's sub-pixel position is exact.
  cv::Mat f32, w32, b32;
  warped.convertTo(w32, CV_32F);
  frame.convertTo(b32, CV_32F);
  mask.convertTo(f32, CV_32F, 1.0 / 255.0);
  cv::Mat blended = w32.mul(f32) + b32.mul(1.0 - f32);
  blended.convertTo(frame, CV_8U);
  if (type == CV_8UC3) {
    cv::Mat colour;
    cv::cvtColor(frame, colour, cv::COLOR_GRAY2BGR);
    // Give the colour channels something different so the max-channel gradient matters.
    cv::Mat ch[3];
    cv::split(colour, ch);
    ch[0] = 255 - ch[0];
    cv::merge(ch, 3, colour);
    return colour;
  }
  return frame;
}

cv::Point2f centre(const cv::Rect2f& b) { return {b.x + b.width * 0.5f, b.y + b.height * 0.5f}; }

}  // namespace

// The whole frame is one textured pattern translated by a known sub-pixel amount (bilinear
// warp of a smooth texture, so the shifted frame is the exact translate up to rounding to 8 bit).
cv::Mat shiftedPattern(const cv::Mat& tex, cv::Size fs, double dx, double dy, int type) {
  const cv::Matx23d m(1.0, 0.0, dx, 0.0, 1.0, dy);
  cv::Mat out;
  cv::warpAffine(tex, out, m, fs, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  if (type == CV_8UC3) {
    cv::Mat ch[3] = {255 - out, out, out / 2 + 60};
    cv::merge(ch, 3, out);
  }
  return out;
}

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
      const cv::Point2f c = centre(r.box);
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
  EXPECT_LT(cv::norm(centre(r.box) - cv::Point2f(static_cast<float>(x), 120.0f)), 2.0);
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
  EXPECT_NEAR(centre(on_target.box).x, 100.0, 0.5);
  EXPECT_NEAR(centre(on_target.box).y, 100.0, 0.5);
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
  EXPECT_NEAR(centre(shifted.box()).x, 156.0, 1e-3);
  const oc::KcfResult rp = plain.update(f1);
  const oc::KcfResult rs = shifted.update(f1);
  EXPECT_GT(std::abs(centre(rp.box).x - 160.0), 10.0) << "the jump should be beyond the unshifted search";
  EXPECT_NEAR(centre(rs.box).x, 160.0, 1.0);
  EXPECT_NEAR(centre(rs.box).y, 120.0, 1.0);
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

TEST(Kcf, TinyTargetsAndBoxesPartlyOutsideTheFrame) {
  // A small bright drone-like blob over a low-contrast textured sky (as in the infrared clips).
  const cv::Mat bg = makeTexture(160, 9) / 4 + 60;
  cv::Mat obj(16, 16, CV_8UC1, cv::Scalar(235));
  obj(cv::Rect(0, 0, 5, 5)).setTo(120);
  const cv::Size fs(320, 240);
  oc::Params p;
  oc::KcfTracker kcf(p);
  // A 6x6 target.
  kcf.init(renderFrame(bg, obj, fs, 100, 100, 6, CV_8UC1), cv::Rect2f(97, 97, 6, 6));
  EXPECT_GE(kcf.templateCells().width, 8);
  oc::KcfResult r;
  for (int i = 1; i <= 10; ++i) {
    r = kcf.update(renderFrame(bg, obj, fs, 100 + i, 100, 6, CV_8UC1));
  }
  EXPECT_NEAR(centre(r.box).x, 110.0, 1.0);
  EXPECT_NEAR(centre(r.box).y, 100.0, 1.0);
  // A box hanging over the top-left corner: no crash, box stays finite and near the target.
  const cv::Mat corner = renderFrame(bg, makeTexture(64, 11), fs, 10, 8, 40, CV_8UC3);
  kcf.init(corner, cv::Rect2f(-10, -12, 40, 40));
  r = kcf.update(renderFrame(bg, makeTexture(64, 11), fs, 12, 9, 40, CV_8UC3));
  EXPECT_TRUE(std::isfinite(r.box.x) && std::isfinite(r.box.y));
  EXPECT_NEAR(centre(r.box).x, 12.0, 2.0);
  EXPECT_NEAR(centre(r.box).y, 9.0, 2.0);
  // A very thin, large box (aspect 8:1) and a box larger than the frame.
  kcf.init(corner, cv::Rect2f(0, 100, 300, 30));
  EXPECT_NO_THROW(kcf.update(corner));
  kcf.init(corner, cv::Rect2f(-50, -50, 500, 400));
  EXPECT_NO_THROW(kcf.update(corner));
}

TEST(Kcf, BadInputThrowsInvalidArgument) {
  oc::KcfTracker kcf;
  const cv::Mat frame(100, 100, CV_8UC1, cv::Scalar(50));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(kcf.initialized());
  EXPECT_THROW(kcf.update(frame), std::logic_error);
  EXPECT_THROW(kcf.init(cv::Mat(), cv::Rect2f(10, 10, 20, 20)), std::invalid_argument);
  EXPECT_THROW(kcf.init(cv::Mat(100, 100, CV_32F, cv::Scalar(0)), cv::Rect2f(10, 10, 20, 20)),
               std::invalid_argument);
  EXPECT_THROW(kcf.init(cv::Mat(100, 100, CV_8UC4, cv::Scalar(0)), cv::Rect2f(10, 10, 20, 20)),
               std::invalid_argument);
  EXPECT_THROW(kcf.init(frame, cv::Rect2f(10, 10, 0, 20)), std::invalid_argument);
  EXPECT_THROW(kcf.init(frame, cv::Rect2f(10, 10, 20, -5)), std::invalid_argument);
  EXPECT_THROW(kcf.init(frame, cv::Rect2f(nan, 10, 20, 20)), std::invalid_argument);
  EXPECT_THROW(kcf.init(frame, cv::Rect2f(10, 10, nan, 20)), std::invalid_argument);
  EXPECT_THROW(kcf.init(frame, cv::Rect2f(10, 10, std::numeric_limits<float>::infinity(), 20)),
               std::invalid_argument);
  EXPECT_THROW(kcf.init(frame, cv::Rect2f(200, 200, 20, 20)), std::invalid_argument);
  EXPECT_THROW(kcf.init(frame, cv::Rect2f(0, 0, 3.0e9f, 20)), std::invalid_argument);
  EXPECT_FALSE(kcf.initialized());
  kcf.init(frame, cv::Rect2f(10, 10, 20, 20));  // a flat frame is legal
  EXPECT_TRUE(kcf.initialized());
  EXPECT_THROW(kcf.update(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(kcf.update(cv::Mat(100, 100, CV_16UC1, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(kcf.evaluate(frame, cv::Rect2f(0, 0, nan, 3)), std::invalid_argument);
  const oc::KcfResult r = kcf.update(frame);  // flat frame: finite, low confidence
  EXPECT_TRUE(std::isfinite(r.peak) && std::isfinite(r.psr) && std::isfinite(r.confidence));
  EXPECT_GE(r.confidence, 0.0f);
  EXPECT_LE(r.confidence, 1.0f);
}

TEST(Kcf, ParametersOutOfRangeAreClamped) {
  oc::Params p;
  p.kcf_template_size = 100000;
  p.kcf_cell_size = 0;
  p.learning_rate = 7.0;
  p.scale_count = -3;
  p.kcf_padding = std::numeric_limits<double>::quiet_NaN();
  oc::KcfTracker kcf(p);
  EXPECT_EQ(kcf.params().kcf_template_size, 256);
  EXPECT_EQ(kcf.params().kcf_cell_size, 1);
  EXPECT_EQ(kcf.params().learning_rate, 1.0);
  EXPECT_EQ(kcf.params().scale_count, 1);
  EXPECT_EQ(kcf.params().kcf_padding, oc::Params().kcf_padding);
  p = oc::Params();
  p.kcf_template_size = 1;
  kcf.setParams(p);
  EXPECT_EQ(kcf.params().kcf_template_size, 32);
  const cv::Mat frame = makeTexture(128, 12);
  kcf.init(frame, cv::Rect2f(40, 40, 30, 30));
  EXPECT_EQ(kcf.templateCells(), cv::Size(8, 8));
  const oc::KcfResult r = kcf.update(frame);  // the smallest grid still has a sidelobe: it learns
  EXPECT_GT(r.psr, 5.0f);
  EXPECT_TRUE(r.model_updated);
}

TEST(Kcf, IsMovable) {
  const cv::Mat frame = makeTexture(128, 13);
  std::vector<oc::KcfTracker> tracks;
  for (int i = 0; i < 4; ++i) {
    tracks.emplace_back();
    tracks.back().init(frame, cv::Rect2f(10.0f + 10 * i, 20, 30, 30));
  }
  oc::KcfTracker moved = std::move(tracks[1]);
  EXPECT_TRUE(moved.initialized());
  EXPECT_FALSE(tracks[1].initialized());  // NOLINT(bugprone-use-after-move): documented state
  EXPECT_EQ(moved.box(), cv::Rect2f(20, 20, 30, 30));
  EXPECT_NO_THROW(moved.update(frame));
  EXPECT_THROW(tracks[1].update(frame), std::logic_error);
  tracks.erase(tracks.begin());
  EXPECT_EQ(tracks[0].box(), cv::Rect2f());  // the moved-from one
  EXPECT_EQ(tracks[1].box(), cv::Rect2f(30, 20, 30, 30));
}

TEST(Kcf, ConfidenceMappingIsMonotoneAndBounded) {
  EXPECT_EQ(oc::KcfTracker::confidenceFrom(0.0f, 50.0f), 0.0f);
  EXPECT_EQ(oc::KcfTracker::confidenceFrom(1.0f, 0.0f), 0.0f);
  EXPECT_EQ(oc::KcfTracker::confidenceFrom(1.0f, 100.0f), 1.0f);
  float last = -1.0f;
  for (float v = 0.0f; v <= 1.0f; v += 0.05f) {
    const float c = oc::KcfTracker::confidenceFrom(v, 4.0f + 12.0f * v);
    EXPECT_GE(c, last);
    EXPECT_GE(c, 0.0f);
    EXPECT_LE(c, 1.0f);
    last = c;
  }
}

TEST(Kcf, RandomFramesAndBoxesNeverBreakIt) {
  // Deterministic random sweep over frame sizes (down to 1x1), types, boxes (tiny, huge, partly
  // outside) and parameters: every call either works with finite outputs or throws
  // std::invalid_argument for a box that misses the frame or is over 16 times its size.
  cv::RNG rng(2026);
  for (int it = 0; it < 150; ++it) {
    const int fw = rng.uniform(1, 200), fh = rng.uniform(1, 160);
    const int type = rng.uniform(0, 2) ? CV_8UC3 : CV_8UC1;
    cv::Mat frame(fh, fw, type);
    rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
    oc::Params p;
    p.kcf_template_size = rng.uniform(32, 129);
    p.kcf_cell_size = rng.uniform(1, 9);
    p.kcf_padding = rng.uniform(0.0, 3.0);
    p.scale_count = rng.uniform(1, 8);
    p.kcf_scale_filter = rng.uniform(0, 2) != 0;
    oc::KcfTracker kcf(p);
    const cv::Rect2f box(static_cast<float>(rng.uniform(-50.0, fw + 10.0)),
                         static_cast<float>(rng.uniform(-50.0, fh + 10.0)),
                         static_cast<float>(rng.uniform(1.0, 400.0)),
                         static_cast<float>(rng.uniform(1.0, 300.0)));
    try {
      kcf.init(frame, box);
    } catch (const std::invalid_argument& e) {
      const cv::Rect2f fr(0, 0, static_cast<float>(fw), static_cast<float>(fh));
      const bool misses = (box & fr).area() <= 0.0f;
      const bool huge = box.width > 16.0f * fw || box.height > 16.0f * fh;
      EXPECT_TRUE(misses || huge) << "init refused a legal box: " << e.what();
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      cv::Mat next(fh, fw, type);
      rng.fill(next, cv::RNG::UNIFORM, 0, 256);
      const oc::KcfResult r = kcf.update(next);
      ASSERT_TRUE(std::isfinite(r.box.x) && std::isfinite(r.box.y) && std::isfinite(r.box.width) &&
                  std::isfinite(r.box.height) && std::isfinite(r.peak) && std::isfinite(r.psr))
          << "iteration " << it;
      EXPECT_GE(r.confidence, 0.0f);
      EXPECT_LE(r.confidence, 1.0f);
      EXPECT_GT(r.box.width, 0.0f);
      EXPECT_GT(r.box.height, 0.0f);
      const oc::KcfResult e = kcf.evaluate(next, cv::Rect2f(0, 0, static_cast<float>(fw),
                                                            static_cast<float>(fh)));
      EXPECT_TRUE(std::isfinite(e.peak) && std::isfinite(e.box.x));
    }
  }
}
