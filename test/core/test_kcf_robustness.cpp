// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// KcfTracker at its edges: tiny targets and boxes partly outside the frame, bad input, parameters
// out of range, moves, the confidence mapping, random frames and boxes.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
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
  EXPECT_NEAR(boxCentre(r.box).x, 110.0, 1.0);
  EXPECT_NEAR(boxCentre(r.box).y, 100.0, 1.0);
  // A box hanging over the top-left corner: no crash, box stays finite and near the target.
  const cv::Mat corner = renderFrame(bg, makeTexture(64, 11), fs, 10, 8, 40, CV_8UC3);
  kcf.init(corner, cv::Rect2f(-10, -12, 40, 40));
  r = kcf.update(renderFrame(bg, makeTexture(64, 11), fs, 12, 9, 40, CV_8UC3));
  EXPECT_TRUE(std::isfinite(r.box.x) && std::isfinite(r.box.y));
  EXPECT_NEAR(boxCentre(r.box).x, 12.0, 2.0);
  EXPECT_NEAR(boxCentre(r.box).y, 9.0, 2.0);
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
