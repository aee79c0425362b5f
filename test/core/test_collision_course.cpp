// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Collision course (collision_course.h): known bearings, and the generated approach and crossing
// scenes seen through a pinhole camera of the scene's focal length.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/collision_course.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/scene/scene_generator.h"

using obstacle_tracker::core::CollisionCourse;
namespace core = obstacle_tracker::core;
namespace scene = obstacle_tracker::scene;

namespace {

constexpr double kFps = 30.0;

CollisionCourse::Track track(int id, double azimuth, double expansion_rate, double sigma = 0.05) {
  CollisionCourse::Track t;
  t.id = id;
  t.has_bearing = true;
  t.bearing = cv::Vec3d(std::sin(azimuth), 0.0, std::cos(azimuth));
  t.expansion_rate = expansion_rate;
  t.expansion_rate_sigma = sigma;
  return t;
}

}  // namespace

TEST(CollisionCourse, ConstantBearingAndClosingIsFlaggedAfterItsHistory) {
  CollisionCourse cc;
  cc.setMaxBearingRate(0.05);
  for (int k = 0; k <= 30; ++k) {
    std::vector<CollisionCourse::Track> tracks{track(3, 0.2, 0.5)};
    cc.update(k / kFps, tracks);
    EXPECT_NEAR(tracks[0].bearing_rate, 0.0, 1e-9);
    EXPECT_EQ(tracks[0].collision_course, k / kFps >= CollisionCourse::kMinHistory - 1e-9) << k;
  }
}

TEST(CollisionCourse, TurningBearingIsNotFlaggedAndItsRateIsMeasured) {
  CollisionCourse cc;
  cc.setMaxBearingRate(0.05);
  std::vector<CollisionCourse::Track> tracks;
  for (int k = 0; k <= 90; ++k) {
    tracks = {track(1, 0.2 * k / kFps, 0.5)};  // 0.2 rad/s
    cc.update(k / kFps, tracks);
    EXPECT_FALSE(tracks[0].collision_course) << k;
  }
  EXPECT_NEAR(tracks[0].bearing_rate, 0.2, 1e-6);
}

TEST(CollisionCourse, NotClosingOrUncertainIsNotFlagged) {
  CollisionCourse cc;
  for (int k = 0; k <= 30; ++k) {
    std::vector<CollisionCourse::Track> tracks{track(1, 0.0, 0.0), track(2, 0.1, -0.3), track(3, 0.3, 0.5, 0.3)};
    cc.update(k / kFps, tracks);
    for (const auto& t : tracks) EXPECT_FALSE(t.collision_course) << t.id;
  }
}

TEST(CollisionCourse, HistoryRestartsWithoutBearingOrWhenTimeGoesBack) {
  CollisionCourse cc;
  std::vector<CollisionCourse::Track> tracks;
  for (int k = 0; k <= 15; ++k) {
    tracks = {track(1, 0.0, 0.5)};
    cc.update(k / kFps, tracks);
  }
  EXPECT_TRUE(tracks[0].collision_course);
  tracks = {track(1, 0.0, 0.5)};
  tracks[0].has_bearing = false;  // no camera_info for a frame
  cc.update(16 / kFps, tracks);
  EXPECT_FALSE(tracks[0].collision_course);
  EXPECT_EQ(tracks[0].bearing_rate, 0.0);
  tracks = {track(1, 0.0, 0.5)};
  cc.update(17 / kFps, tracks);
  EXPECT_FALSE(tracks[0].collision_course);  // history starts again
  tracks = {track(1, 0.0, 0.5)};
  cc.update(17 / kFps, tracks);  // the same stamp again: no rate from dt = 0, nothing breaks
  EXPECT_TRUE(std::isfinite(tracks[0].bearing_rate));
  for (int k = 18; k <= 30; ++k) {
    tracks = {track(1, 0.0, 0.5)};
    cc.update(k / kFps, tracks);
  }
  EXPECT_TRUE(tracks[0].collision_course);
  tracks = {track(1, 0.0, 0.5)};
  cc.update(1.0 / kFps, tracks);  // a looping bag
  EXPECT_FALSE(tracks[0].collision_course);
  tracks = {track(1, 0.0, 0.5)};
  tracks[0].bearing = cv::Vec3d(std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0);
  cc.update(2.0 / kFps, tracks);
  EXPECT_FALSE(tracks[0].collision_course);
  EXPECT_EQ(tracks[0].bearing_rate, 0.0);
}

namespace {

// Frames of the scene (from frame 10 on) flagged as a collision course, tracked from the first
// ground-truth box, bearings through a pinhole camera of the scene's focal length.
int flaggedFrames(const char* name, int seed, int* checked) {
  scene::SceneGenerator gen = scene::makeScenario(name, static_cast<std::uint64_t>(seed), 150, cv::Size(640, 480));
  const double f = gen.info().focal_length_px;
  core::Pipeline pipeline;
  CollisionCourse cc;
  core::Params params;
  cc.setMaxBearingRate(params.collision_bearing_rate);
  cv::Mat frame;
  scene::FrameTruth truth;
  int flagged = 0;
  *checked = 0;
  std::vector<CollisionCourse::Track> tracks;
  for (int i = 0; i < gen.frameCount(); ++i) {
    gen.renderFrame(i, frame, &truth);
    const double stamp = i / gen.fps();
    const auto& out = i == 0 ? pipeline.startTrack(frame, stamp, truth.find(1)->box) : pipeline.process(frame, stamp);
    tracks.clear();
    for (const auto& o : out) {
      CollisionCourse::Track t;
      t.id = o.id;
      t.has_bearing = true;
      const cv::Point2d uv = core::boxCentre(cv::Rect2d(o.box));
      t.bearing = cv::Vec3d((uv.x - 0.5 * frame.cols) / f, (uv.y - 0.5 * frame.rows) / f, 1.0);
      t.expansion_rate = o.expansion_rate;
      t.expansion_rate_sigma = o.expansion_rate_sigma;
      tracks.push_back(t);
    }
    cc.update(stamp, tracks);
    if (i < 10) continue;
    ++*checked;
    flagged += !tracks.empty() && tracks.front().collision_course ? 1 : 0;
  }
  std::printf("[ course   ] %-10s seed %d: collision course on %d of %d frames\n", name, seed, flagged, *checked);
  return flagged;
}

}  // namespace

TEST(CollisionCourse, ApproachSceneIsFlaggedCrossingIsNot) {
  for (int seed = 1; seed <= 2; ++seed) {
    int checked = 0;
    // Flagged once closing is beyond doubt (the expansion rate > 2 sigma): the last part of the
    // approach, where the time to contact is short.
    EXPECT_GE(flaggedFrames("approach", seed, &checked), 30) << seed;
    EXPECT_EQ(flaggedFrames("crossing", seed, &checked), 0) << seed;
  }
}
