// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The same frames give the same scores on every CPU: OpenCV chooses SSE, AVX2 or AVX-512 kernels
// at run time, and cv::setUseOptimized(false) makes it use the baseline ones. On each scene the
// OTB precision at 20 px and success AUC of the main obstacle must agree within 0.02 either way
// (the tolerance of docs/portability.md: cv::exp's last bit still follows the dispatch path),
// auto-started and from a box, colour and grey; the scenes include re-detection and the scale
// search. How many frames are bit-identical is printed.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/eval/metrics.h"
#include "rendered_clip.h"

namespace oc = obstacle_tracker::core;
namespace ev = obstacle_tracker::eval;

namespace {

constexpr double kTolerance = 0.02;

using Clip = obstacle_tracker::test::RenderedClip;

// Rendered once, before either run: the scene generator's own OpenCV calls are not under test.
Clip render(const std::string& scenario, int frames, bool grey) {
  return obstacle_tracker::test::renderClip(scenario, 3, frames, cv::Size(480, 360), grey);
}

std::vector<cv::Rect2f> track(const Clip& c, bool from_box) {
  oc::Pipeline pipeline;
  std::vector<cv::Rect2f> boxes;
  for (std::size_t i = 0; i < c.frames.size(); ++i) {
    const double stamp = static_cast<double>(i) / c.fps;
    const bool start = from_box && i == 0 && c.truth[0].area() > 0;
    const auto& out = start ? pipeline.startTrack(c.frames[i], stamp, c.truth[0]) : pipeline.process(c.frames[i], stamp);
    boxes.push_back(out.empty() ? cv::Rect2f() : out.front().box);
  }
  return boxes;
}

void expectDispatchInvariant(const std::string& scenario, int frames, bool from_box, bool grey) {
  cv::setUseOptimized(true);
  const Clip clip = render(scenario, frames, grey);
  const std::vector<cv::Rect2f> optimised = track(clip, from_box);
  cv::setUseOptimized(false);
  const std::vector<cv::Rect2f> baseline = track(clip, from_box);
  cv::setUseOptimized(true);
  const ev::OtbScores a = ev::otbScores(optimised, clip.truth), b = ev::otbScores(baseline, clip.truth);
  int identical = 0, with_box = 0;
  for (std::size_t i = 0; i < optimised.size(); ++i) {
    identical += optimised[i] == baseline[i] ? 1 : 0;
    with_box += optimised[i].area() > 0 ? 1 : 0;
  }
  std::printf("[ dispatch ] %-20s %s: P@20 %.3f / %.3f, AUC %.3f / %.3f (dispatch on / off), %d of %d frames identical\n",
              scenario.c_str(), from_box ? "gt  " : "auto", a.precision20, b.precision20, a.auc, b.auc, identical,
              frames);
  EXPECT_NEAR(a.precision20, b.precision20, kTolerance) << scenario;
  EXPECT_NEAR(a.auc, b.auc, kTolerance) << scenario;
  EXPECT_GT(with_box, frames / 3) << scenario << ": too few frames with a track to prove much";
}

}  // namespace

TEST(DispatchInvariance, CrossingWithJerksFromTheBox) { expectDispatchInvariant("crossing+jerk", 150, true, false); }
TEST(DispatchInvariance, CloudOcclusionFromTheBoxGrey) { expectDispatchInvariant("crossing+occlusion", 120, true, true); }
TEST(DispatchInvariance, BirdAutoStarted) { expectDispatchInvariant("bird", 150, false, false); }
TEST(DispatchInvariance, ApproachAutoStartedGrey) { expectDispatchInvariant("approach", 120, false, true); }
TEST(DispatchInvariance, ApproachFromTheBox) { expectDispatchInvariant("approach", 120, true, false); }
