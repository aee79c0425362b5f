// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// PatchSampler (patch_sampler.h): known answers on ramps, bit-equality with the direct two-row
// bilinear formula, and the border.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "obstacle_tracker/core/patch_sampler.h"

namespace oc = obstacle_tracker::core;

namespace {

// The bilinear value at patch pixel (u, v) computed directly from the two source rows and
// columns around it, for windows under twice the patch (no box shrink): the sampler keeps each
// source row's horizontal pass and reuses it, which must not change a bit.
cv::Mat directBilinear(const cv::Mat& frame, cv::Point2f c, cv::Size2f ws, int tw, int th) {
  const int nc = frame.channels();
  cv::Mat out(th, tw, frame.type());
  const double fx = ws.width / tw, fy = ws.height / th;  // float quotients, as the sampler's
  const double x0 = static_cast<double>(c.x) - 0.5 * ws.width, y0 = static_cast<double>(c.y) - 0.5 * ws.height;
  const auto clampTo = [](int v, int n) { return v < 0 ? 0 : (v > n - 1 ? n - 1 : v); };
  for (int v = 0; v < th; ++v) {
    const double i = y0 + (v + 0.5) * fy - 0.5;
    const double iff = std::floor(i);
    const float b = static_cast<float>(i - iff);
    const uchar* r0 = frame.ptr<uchar>(clampTo(static_cast<int>(iff), frame.rows));
    const uchar* r1 = frame.ptr<uchar>(clampTo(static_cast<int>(iff) + 1, frame.rows));
    for (int u = 0; u < tw; ++u) {
      const double j = x0 + (u + 0.5) * fx - 0.5;
      const double jf = std::floor(j);
      const float a = static_cast<float>(j - jf);
      const int k0 = clampTo(static_cast<int>(jf), frame.cols) * nc, k1 = clampTo(static_cast<int>(jf) + 1, frame.cols) * nc;
      for (int ch = 0; ch < nc; ++ch) {
        const float top = r0[k0 + ch] + a * (static_cast<float>(r0[k1 + ch]) - r0[k0 + ch]);
        const float bot = r1[k0 + ch] + a * (static_cast<float>(r1[k1 + ch]) - r1[k0 + ch]);
        out.ptr<uchar>(v)[u * nc + ch] = static_cast<uchar>(top + b * (bot - top) + 0.5f);
      }
    }
  }
  return out;
}

}  // namespace

TEST(PatchSampler, SameBitsAsTheDirectTwoRowFormula) {
  cv::RNG rng(5);
  oc::PatchSampler sampler;
  cv::Mat patch;
  for (const int type : {CV_8UC1, CV_8UC3}) {
    cv::Mat frame(120, 160, type);
    rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
    for (int trial = 0; trial < 200; ++trial) {
      const int tw = rng.uniform(4, 48), th = rng.uniform(4, 48);
      // From 0.3x (upsampling: one source row serves several patch rows) to 1.9x the patch,
      // centred anywhere, partly outside the frame too.
      const cv::Size2f ws(static_cast<float>(tw * rng.uniform(0.3, 1.9)), static_cast<float>(th * rng.uniform(0.3, 1.9)));
      const cv::Point2f c(rng.uniform(-20.0f, 180.0f), rng.uniform(-20.0f, 140.0f));
      sampler.sample(frame, c, ws, tw, th, patch);
      const cv::Mat expected = directBilinear(frame, c, ws, tw, th);
      ASSERT_EQ(cv::norm(patch, expected, cv::NORM_INF), 0.0)
          << "type " << type << " trial " << trial << ": " << tw << "x" << th << " from " << ws << " at " << c;
    }
  }
}

TEST(PatchSampler, RampsAreInterpolatedAlongBothAxes) {
  // Grey = 2 x (row or column index): every patch pixel has a known value, so a patch row built
  // from the wrong source row (or column) shows at once, up- and down-sampled (with the box
  // shrink from twice the patch on).
  cv::Mat rows_ramp(100, 100, CV_8UC1), cols_ramp(100, 100, CV_8UC1);
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      rows_ramp.at<uchar>(y, x) = static_cast<uchar>(2 * y);
      cols_ramp.at<uchar>(y, x) = static_cast<uchar>(2 * x);
    }
  oc::PatchSampler sampler;
  cv::Mat patch;
  for (const float scale : {0.25f, 0.5f, 1.0f, 1.5f, 2.0f, 3.0f}) {
    const int side = 24;
    const float window = side * scale;
    const cv::Point2f c(50.0f, 50.0f);
    for (int axis = 0; axis < 2; ++axis) {
      sampler.sample(axis == 0 ? rows_ramp : cols_ramp, c, cv::Size2f(window, window), side, side, patch);
      for (int k = 0; k < side; ++k) {
        // Patch pixel k's centre is at frame coordinate c - window / 2 + (k + 0.5) scale - 0.5.
        const float centre = axis == 0 ? c.y : c.x;
        const double expected = 2.0 * (centre - 0.5 * window + (k + 0.5) * scale - 0.5);
        const int value = axis == 0 ? patch.at<uchar>(k, side / 2) : patch.at<uchar>(side / 2, k);
        EXPECT_NEAR(value, expected, 1.0) << "scale " << scale << " axis " << axis << " pixel " << k;
      }
    }
  }
}

TEST(PatchSampler, OutsideTheFrameTheBorderIsReplicated) {
  cv::Mat frame(40, 40, CV_8UC1);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) frame.at<uchar>(y, x) = static_cast<uchar>(5 * x + y);
  oc::PatchSampler sampler;
  cv::Mat patch;
  // A window whose left half lies left of the frame: its left patch columns repeat column 0.
  sampler.sample(frame, cv::Point2f(0.0f, 20.0f), cv::Size2f(20.0f, 20.0f), 20, 20, patch);
  for (int v = 0; v < 20; ++v) {
    for (int u = 0; u < 9; ++u) EXPECT_EQ(patch.at<uchar>(v, u), frame.at<uchar>(10 + v, 0)) << u << "," << v;
  }
  // One whose lower half lies below it: its lower patch rows repeat the last row.
  sampler.sample(frame, cv::Point2f(20.0f, 40.0f), cv::Size2f(20.0f, 20.0f), 20, 20, patch);
  for (int v = 11; v < 20; ++v) {
    for (int u = 0; u < 20; ++u) EXPECT_EQ(patch.at<uchar>(v, u), frame.at<uchar>(39, 10 + u)) << u << "," << v;
  }
}
