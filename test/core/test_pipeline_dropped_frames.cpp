// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The closed loop when frames are dropped before they reach it: a nodelet drops the camera's
// frames while the tracker is busy, so which frames it sees depends on the machine's load. The
// accuracy over the frames it answers must not depend on which ones those are. Deterministic
// drop patterns stand in for the load here, at the sizes of the accuracy rostests
// (test/ros/accuracy: the same scene through the nodelet, scored there in lock-step, since which
// frames a loaded machine drops cannot be repeated).
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace core = obstacle_tracker::core;
namespace eval = obstacle_tracker::eval;
namespace scene = obstacle_tracker::scene;

namespace {

// Auto-initialised run over a generated scene (8-bit BGR frames, as the pipeline takes them),
// each frame after the first dropped with
// probability drop_tenths / 10 (std::mt19937's output is the same on every platform; a
// distribution's is not). Scores over the answered frames, as the accuracy rostest does.
eval::OtbScores runWithDrops(const char* scenario, cv::Size size, unsigned drop_seed, unsigned drop_tenths) {
  scene::SceneGenerator gen = scene::makeScenario(scenario, 3, 150, size, false);
  core::Pipeline pipeline;
  std::mt19937 rng(drop_seed);
  std::vector<cv::Rect2f> predicted, truth;
  cv::Mat raw;
  for (int i = 0; i < gen.frameCount(); ++i) {
    scene::FrameTruth frame_truth;
    gen.renderFrame(i, raw, &frame_truth);
    if (i > 0 && rng() % 10 < drop_tenths) continue;
    const scene::ObstacleTruth* main = frame_truth.find(1);
    const std::vector<core::Obstacle>& out = pipeline.process(raw, i / gen.fps());
    cv::Rect2f best;
    for (const core::Obstacle& o : out) {
      if (o.state == core::TrackState::kTracking || o.state == core::TrackState::kRedetecting) {
        best = o.box;
        break;
      }
    }
    predicted.push_back(best);
    truth.push_back(main != nullptr && main->visible ? main->box : cv::Rect2f());
  }
  return eval::otbScores(predicted, truth);
}

// The bars of both tests: 8 seeded patterns with 30 % of the frames dropped; at least 6 of them
// keep P@20 >= 0.80, and the mean P@20 over all 8 is at least 0.75. Each pattern is printed.
void expectBirdKeptAcrossDrops(cv::Size size) {
  constexpr int kPatterns = 8;
  int kept = 0;
  double mean = 0.0;
  for (unsigned seed = 1; seed <= kPatterns; ++seed) {
    const eval::OtbScores s = runWithDrops("bird", size, seed, 3);
    std::printf("[ dropped  ] bird %dx%d, 30 %% of frames dropped (pattern %u): P@20 %.3f AUC %.3f over %d frames\n",
                size.width, size.height, seed, s.precision20, s.auc, s.frames);
    kept += s.precision20 >= 0.80 ? 1 : 0;
    mean += s.precision20 / kPatterns;
  }
  EXPECT_GE(kept, 6) << "drop patterns with P@20 >= 0.80";
  EXPECT_GE(mean, 0.75);
}

}  // namespace

TEST(PipelineDroppedFrames, FastBirdIsKeptAcrossDroppedFrames) {
  // The bird moves up to 3 box widths a second with a wavy path: after a few dropped frames it
  // has left the filter's window unless the search follows its velocity over the missing time
  // (Pipeline: bridgeDroppedFrames). Measured: 7 of 8 drop patterns keep P@20 >= 0.80 (mean
  // 0.84); without the bridge 3 of 8 (mean 0.55). The one that fails loses the bird in a gap and
  // then holds the sky, at the confidence capped for a box without its target's contrast.
  expectBirdKeptAcrossDrops(cv::Size(480, 360));
}

// The size the real-time accuracy rostest sends at the camera's rate (cmake/ros_accuracy.cmake).
// Measured: 7 of 8 patterns, mean 0.84; the one that fails fails as above.
TEST(PipelineDroppedFrames, FastBirdIsKeptAcrossDroppedFramesAt720p) {
  expectBirdKeptAcrossDrops(cv::Size(1280, 720));
}
