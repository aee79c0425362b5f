// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Sequence regressions of the closed loop on generated flight scenes (include/obstacle_tracker/
// scene), with numeric bars on OTB precision (20 px) and success AUC. The bars sit a little under
// the values measured when they were set (printed by each test), so that a regression fails.
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/eval/sequence.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace core = obstacle_tracker::core;
namespace eval = obstacle_tracker::eval;
namespace scene = obstacle_tracker::scene;

namespace {

struct SceneRun {
  eval::OtbScores scores;
  std::vector<std::vector<core::Obstacle>> frames;  // every frame's output
  std::vector<scene::FrameTruth> truth;
};

// Runs the pipeline over a generated scene; gt_start: start from the first visible main box.
SceneRun runScene(const std::string& name, int frames, bool gt_start, const core::Params& params = core::Params(),
             cv::Size size = cv::Size(480, 360), bool mono16 = false, unsigned seed = 3) {
  scene::SceneGenerator gen = scene::makeScenario(name, seed, frames, size, mono16);
  core::Pipeline pipeline(params);
  eval::FrameConverter converter;  // the nodelet's stretch for 16-bit frames
  SceneRun run;
  std::vector<cv::Rect2f> predicted, gt;
  cv::Mat raw;
  bool started = !gt_start;
  for (int i = 0; i < gen.frameCount(); ++i) {
    scene::FrameTruth truth;
    gen.renderFrame(i, raw, &truth);
    const cv::Mat& frame = converter.convert(raw);
    const scene::ObstacleTruth* main = truth.find(1);
    const cv::Rect2f main_box = (main != nullptr && main->visible) ? main->box : cv::Rect2f();
    const double stamp = i / gen.fps();
    std::vector<core::Obstacle> out;
    if (!started) {
      if (eval::isPresent(main_box)) {
        out = pipeline.startTrack(frame, stamp, main_box);
        started = true;
      }
    } else {
      out = pipeline.process(frame, stamp);
    }
    cv::Rect2f best;
    for (const auto& o : out) {
      if (o.state == core::TrackState::kTracking || o.state == core::TrackState::kRedetecting) {
        best = o.box;
        break;
      }
    }
    predicted.push_back(best);
    gt.push_back(main_box);
    run.frames.push_back(out);
    run.truth.push_back(truth);
  }
  run.scores = eval::otbScores(predicted, gt);
  std::printf("[ scene    ] %-28s %s: precision %.3f  AUC %.3f  (%d frames)\n", name.c_str(),
              gt_start ? "gt  " : "auto", run.scores.precision20, run.scores.auc, run.scores.frames);
  return run;
}

}  // namespace

TEST(PipelineScenes, DemoFromGroundTruth) {
  // An approach: the box lags the growth (ApproachTimeToContact); measured 1.000 / 0.408.
  const SceneRun r = runScene("demo", 150, true);
  EXPECT_GE(r.scores.precision20, 0.90);
  EXPECT_GE(r.scores.auc, 0.40);
}

TEST(PipelineScenes, CrossingAutoInit) {
  // No ground truth used: the pipeline finds the aircraft itself. Measured 0.940 / 0.598.
  const SceneRun r = runScene("crossing", 150, false);
  EXPECT_GE(r.scores.precision20, 0.85);
  EXPECT_GE(r.scores.auc, 0.28);
}

// A constant-size obstacle keeps its box size: the crossing aircraft, started from its box, at
// 640x480 for 300 frames, seeds 1-6; the box side sqrt(w h) against the truth's. The issue's
// target is within 5 % on every frame; measured with the scale confirmation on 13 / 300 / 300 /
// 230 / 300 / 300 frames (seeds 1 and 4 still shrink: their thin aircraft fills little of the
// box, and the clouds moving behind it bias both the scale search and the pixel expansions
// towards smaller, docs/measurements.md), without it (scale_confirm_frames 1) on 9 / 123 / 190 /
// 90 / 298 / 297. Held here: all seeds tracked, and within 5 % on 75 % of the frames together.
TEST(PipelineScenes, ConstantSizeKeepsItsBox) {
  int tracked = 0, within = 0;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    const SceneRun r = runScene("crossing", 300, true, core::Params(), cv::Size(640, 480), false, seed);
    int seed_tracked = 0, seed_within = 0;
    for (std::size_t i = 0; i < r.frames.size(); ++i) {
      const scene::ObstacleTruth* m = r.truth[i].find(1);
      if (m == nullptr || !m->visible || r.frames[i].empty()) continue;
      const cv::Rect2f& b = r.frames[i][0].box;
      ++seed_tracked;
      const double ratio = std::sqrt(static_cast<double>(b.area()) / m->box.area());
      seed_within += std::abs(ratio - 1.0) <= 0.05 ? 1 : 0;
    }
    std::printf("[ scene    ] crossing seed %u: box side within 5 %% on %d of %d tracked frames\n", seed,
                seed_within, seed_tracked);
    EXPECT_GE(seed_tracked, 295) << "seed " << seed;
    tracked += seed_tracked;
    within += seed_within;
  }
  EXPECT_GE(within, 0.75 * tracked);
}

// A collision course: the obstacle keeps its bearing and only grows, so there is no motion to
// confirm it by; auto_init_min_growth's growth cue does (without it `approach` never starts).
// `demo`, the same approach over a lattice tower with camera jitter, checks that a candidate
// sliding along the lattice is not taken for a mover (the motion cue's vacated-position test):
// before the aircraft is found the loop may hold a provisional box on the tower (the persistence
// start, pipeline_search.cpp), but never confirmed nor with confidence >= 0.5; from the first box
// on the aircraft (centre within 20 px) it follows the aircraft.
TEST(PipelineScenes, CollisionCourseAutoInit) {
  for (const auto& [name, frames] : {std::pair<const char*, int>{"approach", 120}, {"demo", 150}}) {
    const SceneRun r = runScene(name, frames, false);
    int first = -1;
    for (std::size_t i = 0; i < r.frames.size() && first < 0; ++i) {
      if (r.frames[i].empty()) continue;
      const scene::ObstacleTruth* m = r.truth[i].find(1);
      const bool on_aircraft = m != nullptr && m->visible && eval::centreError(r.frames[i][0].box, m->box) <= 20.0;
      if (on_aircraft) {
        first = static_cast<int>(i);
      } else {
        EXPECT_FALSE(r.frames[i][0].confirmed) << name << " frame " << i << ": confirmed off the aircraft";
        EXPECT_LT(r.frames[i][0].confidence, 0.5f) << name << " frame " << i << ": confident off the aircraft";
      }
    }
    ASSERT_GE(first, 0) << name << ": never started";
    EXPECT_LT(first, static_cast<int>(0.6 * frames)) << name;
    int followed = 0, visible = 0;
    for (std::size_t i = static_cast<std::size_t>(first); i < r.frames.size(); ++i) {
      const scene::ObstacleTruth* m = r.truth[i].find(1);
      if (m == nullptr || !m->visible) continue;
      ++visible;
      if (r.frames[i].empty()) continue;
      followed += eval::centreError(r.frames[i][0].box, m->box) <= 20.0 ? 1 : 0;
    }
    std::printf("[ scene    ] %-8s auto: first box on the aircraft at frame %d, centre within 20 px on %d of %d\n",
                name, first, followed, visible);
    EXPECT_GE(followed, static_cast<int>(0.9 * visible)) << name;
  }
}

// Auto-initialisation sometimes confirms a scene object; an auto-started track is then verified
// over a longer time (pipeline_search.cpp, verify()), and a confirmed mover that passes the same test
// takes its place. `tiny` with the camera's on-screen display and shake at 640x480 (seed 1)
// starts on a part of the lattice mast and keeps it for good with the verification off; with it,
// the tiny multirotor takes over.
TEST(PipelineScenes, UnverifiedStartGivesWayToAMover) {
  const cv::Size size(640, 480);
  core::Params off;
  off.auto_init_verify_frames = 0;
  const SceneRun without = runScene("tiny+overlay+jitter", 180, false, off, size, false, 1);
  const SceneRun with = runScene("tiny+overlay+jitter", 180, false, core::Params(), size, false, 1);
  EXPECT_LE(without.scores.precision20, 0.10);
  EXPECT_GE(with.scores.precision20, 0.20);
  // The mover is reported under a new id: the first track was replaced, not moved.
  int first_id = -1, last_id = -1;
  for (const auto& f : with.frames) {
    if (f.empty()) continue;
    if (first_id < 0) first_id = f.front().id;
    last_id = f.front().id;
  }
  EXPECT_GE(first_id, 0);
  EXPECT_NE(first_id, last_id);
  // The overlay-started track is never reported as confirmed, nor with confidence >= 0.5; the
  // mover that replaced it is confirmed (it replaced it by verifying first).
  int first_reports = 0, last_confirmed = 0, last_reports = 0;
  for (const auto& f : with.frames) {
    for (const auto& o : f) {
      if (o.id == first_id) {
        ++first_reports;
        EXPECT_FALSE(o.confirmed);
        EXPECT_LT(o.confidence, 0.5f);
      } else if (o.id == last_id) {
        ++last_reports;
        last_confirmed += o.confirmed ? 1 : 0;
      }
    }
  }
  EXPECT_GT(first_reports, 0);
  EXPECT_EQ(last_confirmed, last_reports);
  // ... and the track that replaced it is on the multirotor (not the mast found again).
  int reported = 0, on_target = 0;
  for (std::size_t i = 0; i < with.frames.size(); ++i) {
    if (with.frames[i].empty() || with.frames[i].front().id != last_id) continue;
    const scene::ObstacleTruth* m = with.truth[i].find(1);
    if (m == nullptr || !m->visible) continue;
    ++reported;
    const cv::Rect2f& b = with.frames[i].front().box;
    on_target += eval::centreError(b, m->box) <= 20.0;
  }
  std::printf("[ scene    ] the replacing track: on the multirotor on %d of %d frames\n", on_target, reported);
  EXPECT_GT(reported, 0);
  EXPECT_GE(on_target, static_cast<int>(0.8 * reported));
}

// setParams with the same values changes nothing, also while a challenger is tracked unreported
// beside an unverified track (the challenger is not one of the max_obstacles tracks and must not
// push the reported track out).
TEST(PipelineScenes, SameParamsWhileVerifyingChangeNothing) {
  scene::SceneGenerator gen = scene::makeScenario("tiny+overlay+jitter", 1, 180, cv::Size(640, 480));
  core::Pipeline plain, touched;
  cv::Mat frame;
  int differing = 0, reported = 0;
  for (int i = 0; i < gen.frameCount(); ++i) {
    gen.renderFrame(i, frame, nullptr);
    const double stamp = i / gen.fps();
    touched.setParams(touched.params());
    const std::vector<core::Obstacle> a = plain.process(frame, stamp);
    const std::vector<core::Obstacle>& b = touched.process(frame, stamp);
    reported += a.empty() ? 0 : 1;
    bool same = a.size() == b.size();
    for (std::size_t k = 0; same && k < a.size(); ++k) same = a[k].id == b[k].id && a[k].box == b[k].box;
    differing += same ? 0 : 1;
  }
  EXPECT_GT(reported, 0);
  EXPECT_EQ(differing, 0);
}

// A track that passes the verification is never replaced: the generated crossing aircraft, once
// started, keeps its id to the end while other candidates come and go.
TEST(PipelineScenes, VerifiedTrackKeepsItsId) {
  const SceneRun r = runScene("crossing", 150, false);
  int first_id = -1, changes = 0, previous = -1;
  for (const auto& f : r.frames) {
    if (f.empty()) continue;
    if (first_id < 0) first_id = f.front().id;
    changes += previous >= 0 && f.front().id != previous ? 1 : 0;
    previous = f.front().id;
  }
  EXPECT_GE(first_id, 0);
  EXPECT_EQ(changes, 0);
}

TEST(PipelineScenes, CrossingWithJerks) {
  // The ground-truth box is the drawn pixel extent, motion blur included, so during a jerk it
  // stretches along the blur while the tracker's box keeps the aircraft's size: the AUC bar
  // follows that definition. The same on every CPU (OpenCV dispatch limited or not): the
  // filter's float steps do not depend on it (portable_math.h).
  const SceneRun r = runScene("crossing+jerk", 150, true);
  EXPECT_GE(r.scores.precision20, 0.85);
  EXPECT_GE(r.scores.auc, 0.35);
}

TEST(PipelineScenes, CloudOcclusion) {
  // Measured 0.60 / 0.43: the box stays on the cloud edge for a while before the re-detection
  // brings it back; a regression bar, not a goal.
  const SceneRun r = runScene("crossing+occlusion", 150, true);
  EXPECT_GE(r.scores.precision20, 0.50);
  EXPECT_GE(r.scores.auc, 0.35);
}

TEST(PipelineScenes, OutOfViewNoStaleBox) {
  core::Params params;
  params.max_redetect_failures = 10;
  const SceneRun r = runScene("out_of_view", 240, true, params);
  // While the obstacle is out of the frame, nothing is reported as tracking for longer than the
  // re-detection allows (frames out of view, minus max_redetect_failures + 1).
  int out_of_view = 0, tracking_while_out = 0;
  for (std::size_t i = 0; i < r.truth.size(); ++i) {
    const scene::ObstacleTruth* m = r.truth[i].find(1);
    if (m == nullptr || !m->visible) {
      ++out_of_view;
      for (const auto& o : r.frames[i]) tracking_while_out += o.state == core::TrackState::kTracking ? 1 : 0;
    }
  }
  std::printf("[ scene    ] out_of_view: %d frames out of view, %d tracking reports then\n", out_of_view,
              tracking_while_out);
  EXPECT_GT(out_of_view, 0);
  EXPECT_LE(tracking_while_out, out_of_view / 4);
  EXPECT_GE(r.scores.precision20, 0.60);
}

TEST(PipelineScenes, ThreeObstaclesKeepTheirIds) {
  core::Params params;
  params.max_obstacles = 3;
  scene::SceneGenerator gen = scene::makeScenario("multi", 3, 150, cv::Size(480, 360));
  core::Pipeline pipeline(params);
  cv::Mat frame;
  scene::FrameTruth truth;
  gen.renderFrame(0, frame, &truth);
  // Start one track per visible target; remember which id follows which obstacle.
  std::vector<std::pair<int, int>> id_of;  // (track id, truth id)
  for (const auto& t : truth.obstacles) {
    if (t.distractor || !t.visible) continue;
    const auto& out = pipeline.startTrack(frame, 0.0, t.box);
    int newest = -1;
    for (const auto& o : out) newest = std::max(newest, o.id);
    id_of.emplace_back(newest, t.id);
  }
  ASSERT_GE(id_of.size(), 2u);
  int checks = 0, good = 0;
  for (int i = 1; i < gen.frameCount(); ++i) {
    gen.renderFrame(i, frame, &truth);
    const auto& out = pipeline.process(frame, i / gen.fps());
    for (const auto& [track_id, truth_id] : id_of) {
      const scene::ObstacleTruth* t = truth.find(truth_id);
      if (t == nullptr || t->visible_fraction < 0.8f) continue;  // hidden: ids may not be checked
      for (const auto& o : out) {
        if (o.id != track_id || o.state != core::TrackState::kTracking) continue;
        ++checks;
        good += eval::centreError(o.box, t->box) <= 20.0 ? 1 : 0;
      }
    }
  }
  std::printf("[ scene    ] multi: %d of %d tracking reports on the obstacle their id started on\n", good, checks);
  ASSERT_GT(checks, 50);
  EXPECT_GE(good, static_cast<int>(0.85 * checks));
}
