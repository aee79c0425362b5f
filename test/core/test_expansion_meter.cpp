// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known answers for the expansion measured from the object's pixels (expansion_meter.h,
// scale_alignment.h) and the size trend summed from it (looming.h): objects drawn at known sizes
// and positions on a background.
#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/expansion_meter.h"
#include "obstacle_tracker/core/looming.h"
#include "obstacle_tracker/core/scale_alignment.h"

using obstacle_tracker::core::ExpansionMeasurement;
using obstacle_tracker::core::ExpansionMeter;
using obstacle_tracker::core::ScaleAlignment;

namespace {

// Smooth random texture (blurred noise), the object's appearance, 128 x 128.
cv::Mat objectTexture(unsigned seed, int channels) {
  cv::Mat noise(32, 32, channels == 1 ? CV_8UC1 : CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 20, 120);
  cv::Mat big;
  cv::resize(noise, big, cv::Size(128, 128), 0, 0, cv::INTER_CUBIC);
  return big;
}

// The texture drawn centred at c with side `side` on a plain background (grey 180), rendered at
// four times the resolution and area-averaged down, as a camera integrates over its pixels (a
// point-sampled rendering aliases differently at every size, which is not an expansion).
cv::Mat frameWith(const cv::Mat& tex, cv::Point2f c, float side, cv::Size size = cv::Size(320, 240)) {
  constexpr int kSuper = 4;
  cv::Mat fine(size.height * kSuper, size.width * kSuper, tex.type(), cv::Scalar::all(180));
  const float k = kSuper * side / static_cast<float>(tex.cols);
  const float tcx = 0.5f * (tex.cols - 1), tcy = 0.5f * (tex.rows - 1);
  const cv::Point2f cf(kSuper * c.x + 0.5f * (kSuper - 1), kSuper * c.y + 0.5f * (kSuper - 1));
  const cv::Matx23f a(k, 0.0f, cf.x - k * tcx, 0.0f, k, cf.y - k * tcy);
  cv::warpAffine(tex, fine, a, fine.size(), cv::INTER_LINEAR, cv::BORDER_TRANSPARENT);
  cv::Mat frame;
  cv::resize(fine, frame, size, 0, 0, cv::INTER_AREA);
  return frame;
}

cv::Rect2f boxAt(cv::Point2f c, float side) { return {c.x - 0.5f * side, c.y - 0.5f * side, side, side}; }

ExpansionMeasurement measure(const cv::Mat& tex, cv::Point2f c0, float s0, cv::Point2f c1, float s1,
                             cv::Point2f centre_error = {0.0f, 0.0f}) {
  ExpansionMeter meter;
  meter.setReference(frameWith(tex, c0, s0), boxAt(c0, s0));
  return meter.measure(frameWith(tex, c1, s1), c1 + centre_error);
}

}  // namespace

TEST(ScaleAlignment, RecoversScaleAndShiftOfAPatch) {
  const cv::Mat tex = objectTexture(5, 1);
  cv::Mat a, b;
  cv::resize(tex, a, cv::Size(64, 64), 0, 0, cv::INTER_AREA);
  // b(c + s (x - c) + t) = a(x): b is a scaled by s about c = (31.5, 31.5), then shifted by t.
  const float s = 1.04f;
  const cv::Point2f t(1.3f, -0.7f);
  const cv::Matx23f warp(s, 0.0f, 31.5f * (1.0f - s) + t.x, 0.0f, s, 31.5f * (1.0f - s) + t.y);
  cv::warpAffine(a, b, warp, a.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  ScaleAlignment align;
  const auto e = align.estimate(a, b, cv::Rect(16, 16, 32, 32));
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.log_scale, std::log(s), 0.005);
  EXPECT_NEAR(e.shift.x, t.x, 0.1f);
  EXPECT_NEAR(e.shift.y, t.y, 0.1f);
  EXPECT_GT(e.sigma, 0.0);
}

TEST(ScaleAlignment, FlatPatchesAreNoMeasurement) {
  const cv::Mat flat(64, 64, CV_8UC1, cv::Scalar(128));
  ScaleAlignment align;
  EXPECT_FALSE(align.estimate(flat, flat, cv::Rect(16, 16, 32, 32)).valid);
  EXPECT_FALSE(align.estimate(flat, flat, cv::Rect(60, 60, 32, 32)).valid);  // region outside the patch
  EXPECT_THROW(align.estimate(flat, cv::Mat(32, 32, CV_8UC1), cv::Rect(8, 8, 8, 8)), std::invalid_argument);
}

TEST(ExpansionMeter, SmoothDiscWithThinWings) {
  // A head-on aircraft as the generated approach scene draws it: a blurred disc and two faint
  // wings, in a box four times wider than high. No corners, but the outline gives the scale.
  auto draw = [](float scale) {
    // At 4x resolution with sub-pixel outlines (8 fractional bits), then area-averaged down.
    constexpr int kShift = 8;
    const auto fixed = [](double v) { return cvRound(v * (1 << kShift)); };
    cv::Mat fine(960, 1280, CV_8UC1, cv::Scalar(190));
    const double cx = 640.0, cy = 480.0, half_span = 160.0 * scale, half_chord = 4.0 * scale;
    const cv::Point wing[4] = {{fixed(cx - half_span), fixed(cy - half_chord)}, {fixed(cx + half_span), fixed(cy - half_chord)},
                               {fixed(cx + half_span), fixed(cy + half_chord)}, {fixed(cx - half_span), fixed(cy + half_chord)}};
    cv::fillConvexPoly(fine, wing, 4, cv::Scalar(175), cv::LINE_AA, kShift);
    cv::circle(fine, {fixed(cx), fixed(cy)}, fixed(40.0 * scale), cv::Scalar(120), cv::FILLED, cv::LINE_AA, kShift);
    cv::GaussianBlur(fine, fine, cv::Size(0, 0), 6.0 * scale);
    cv::Mat f;
    cv::resize(fine, f, cv::Size(320, 240), 0, 0, cv::INTER_AREA);
    return f;
  };
  const cv::Rect2f box(160.0f - 40.0f, 120.0f - 10.0f, 80.0f, 20.0f);
  for (double ratio : {0.97, 1.02, 1.03, 1.06}) {
    ExpansionMeter meter;
    meter.setReference(draw(1.0f), box);
    const ExpansionMeasurement m = meter.measure(draw(static_cast<float>(ratio)), {160.0f, 120.0f});
    ASSERT_TRUE(m.valid) << ratio;
    EXPECT_NEAR(m.log_ratio, std::log(ratio), 0.25 * std::abs(std::log(ratio))) << ratio;
  }
}

TEST(ExpansionMeter, MeasuresKnownScaleChanges) {
  for (int channels : {1, 3}) {
    const cv::Mat tex = objectTexture(7, channels);
    for (double ratio : {0.95, 1.0, 1.02, 1.05, 1.10}) {
      const ExpansionMeasurement m =
          measure(tex, {160.0f, 120.0f}, 60.0f, {163.0f, 118.5f}, static_cast<float>(60.0 * ratio));
      ASSERT_TRUE(m.valid) << ratio;
      EXPECT_NEAR(m.log_ratio, std::log(ratio), 0.012) << "ratio " << ratio << ", channels " << channels;
      EXPECT_GT(m.sigma, 0.0);
      EXPECT_LE(m.sigma, 0.01);
    }
  }
}

TEST(ExpansionMeter, IndependentOfTheBoxSizeAndOfACentringError) {
  // A small box (16 px, upsampled) and a large one (300 px, box-filtered), with the new centre
  // off by a tenth of the box: the ratio is a property of the object, not of the sampling.
  const cv::Mat tex = objectTexture(9, 3);
  for (float side : {16.0f, 300.0f}) {
    const cv::Size size(side > 100.0f ? 1280 : 320, side > 100.0f ? 720 : 240);
    const cv::Point2f c(0.5f * size.width, 0.5f * size.height);
    ExpansionMeter meter;
    meter.setReference(frameWith(tex, c, side, size), boxAt(c, side));
    const ExpansionMeasurement m = meter.measure(frameWith(tex, c, side * 1.04f, size), c + cv::Point2f(0.1f * side, 0.0f));
    ASSERT_TRUE(m.valid) << side;
    EXPECT_NEAR(m.log_ratio, std::log(1.04), 0.012) << side;
  }
}

TEST(ExpansionMeter, NoMeasurementWithoutTextureOrReference) {
  ExpansionMeter meter;
  const cv::Mat plain(240, 320, CV_8UC1, cv::Scalar(90));
  EXPECT_FALSE(meter.measure(plain, {160.0f, 120.0f}).valid);  // no reference yet
  meter.setReference(plain, boxAt({160.0f, 120.0f}, 40.0f));
  EXPECT_FALSE(meter.measure(plain, {160.0f, 120.0f}).valid);  // flat: nothing to align
  meter.setReference(plain, boxAt({160.0f, 120.0f}, 3.0f));    // below kMinBoxSide
  EXPECT_FALSE(meter.hasReference());
  meter.setReference(plain, cv::Rect2f(std::nanf(""), 0.0f, 10.0f, 10.0f));
  EXPECT_FALSE(meter.hasReference());
}

TEST(ExpansionMeter, PartlyOccludedObject) {
  // A flat occluder covers an eighth of the new object: its pixels misfit and are down-weighted
  // (Huber); the measured expansion is still the object's. (A quarter throws the fit off; the
  // size filter's gate drops such a measurement: SizeFilter.OutlierExpansionIsDropped.)
  const cv::Mat tex = objectTexture(13, 1);
  const cv::Point2f c(160.0f, 120.0f);
  ExpansionMeter meter;
  meter.setReference(frameWith(tex, c, 60.0f), boxAt(c, 60.0f));
  cv::Mat next = frameWith(tex, c, 63.0f);
  cv::rectangle(next, cv::Rect(160, 88, 16, 32), cv::Scalar(200), cv::FILLED);
  const ExpansionMeasurement m = meter.measure(next, c);
  ASSERT_TRUE(m.valid);
  EXPECT_NEAR(m.log_ratio, std::log(63.0 / 60.0), 0.012);
}

// The size trend a looming estimate hands the correlation filter (looming.h): the pixel
// expansions of the last frames, summed. 1.2 % a frame adds up to 0.12 over 10 frames (+1); a
// constant size to about 0 (0); the reverse to -1. Fewer than half the frames measured, or a
// restart, is no trend.
TEST(LoomingTrend, GrowingConstantAndShrinking) {
  const cv::Mat tex = objectTexture(21, 1);
  const cv::Point2f c(160.0f, 120.0f);
  for (double per_frame : {1.012, 1.0, 1.0 / 1.012}) {
    obstacle_tracker::core::LoomingEstimator looming;
    float side = 50.0f;
    looming.start(frameWith(tex, c, side), 0.0, boxAt(c, side));
    const int expected = per_frame > 1.001 ? 1 : (per_frame < 0.999 ? -1 : 0);
    for (int k = 1; k <= 12; ++k) {
      side = static_cast<float>(side * per_frame);
      looming.track(frameWith(tex, c, side), k / 30.0, boxAt(c, side));
      if (k < obstacle_tracker::core::LoomingEstimator::kTrendFrames / 2) {
        EXPECT_EQ(looming.sizeTrend(), 0) << "frame " << k;
      }
    }
    EXPECT_EQ(looming.sizeTrend(), expected) << "per frame " << per_frame;
    looming.restart(frameWith(tex, c, side), 0.5, boxAt(c, side));
    EXPECT_EQ(looming.sizeTrend(), 0) << "after a restart, per frame " << per_frame;
  }
}

// Expansions that swing by +6 % and -4 % on alternate frames add up to 0.1 over 10 frames, past
// the sum's threshold, but their mean is far inside their scatter: no trend. A steady 1 % a frame
// with a small wobble is one.
TEST(LoomingTrend, ScatteredExpansionsAreNoTrend) {
  const cv::Mat tex = objectTexture(21, 1);
  const cv::Point2f c(160.0f, 120.0f);
  const struct {
    double even, odd;  // ln expansion on even and odd frames
    int expected;
  } cases[] = {{0.06, -0.04, 0}, {-0.04, 0.06, 0}, {0.012, 0.008, 1}, {-0.012, -0.008, -1}};
  for (const auto& tc : cases) {
    obstacle_tracker::core::LoomingEstimator looming;
    double side = 50.0;
    looming.start(frameWith(tex, c, static_cast<float>(side)), 0.0, boxAt(c, static_cast<float>(side)));
    for (int k = 1; k <= 11; ++k) {
      side *= std::exp(k % 2 == 0 ? tc.even : tc.odd);
      const float s = static_cast<float>(side);
      looming.track(frameWith(tex, c, s), k / 30.0, boxAt(c, s));
    }
    EXPECT_EQ(looming.sizeTrend(), tc.expected) << "expansions " << tc.even << ", " << tc.odd;
  }
}

TEST(LoomingTrend, NoTrendWithoutMeasurements) {
  const cv::Mat plain(240, 320, CV_8UC1, cv::Scalar(90));
  obstacle_tracker::core::LoomingEstimator looming;
  const cv::Point2f c(160.0f, 120.0f);
  looming.start(plain, 0.0, boxAt(c, 40.0f));
  for (int k = 1; k <= 12; ++k) looming.track(plain, k / 30.0, boxAt(c, 40.0f * (1.0f + 0.02f * k)));
  EXPECT_EQ(looming.sizeTrend(), 0);  // flat: the box sizes are no evidence of a trend
}
