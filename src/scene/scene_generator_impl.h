// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The scene generator's private state, shared by its source files:
//   scene_setup.cpp      builds a scene from its name (scenery, obstacles, camera, noise tables);
//   scene_scenarios.cpp  the obstacles of each base scenario;
//   scene_modifiers.cpp  the modifiers that change the scene at set-up;
//   scene_rasterize.cpp  draws one obstacle over one exposure, with its ground-truth box;
//   scene_frame.cpp      composes, finishes and measures the frames.
// Every random draw and every float operation is in a fixed order: the same scene gives the same
// bytes on any machine (scene_generator.h), so moving code between these files must keep it.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/scene/background.h"
#include "obstacle_tracker/scene/random.h"
#include "obstacle_tracker/scene/scene_generator.h"
#include "obstacle_tracker/scene/shapes.h"

namespace obstacle_tracker {
namespace scene {

// 0 before e0, 1 after e1, a smooth ramp between.
inline double smooth01(double e0, double e1, double x) {
  if (e1 <= e0) return x >= e1 ? 1.0 : 0.0;
  double t = (x - e0) / (e1 - e0);
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  return t * t * (3.0 - 2.0 * t);
}

inline double sinTurn(double turns) { return detSin(2.0 * kPi * turns); }

struct SceneGenerator::Impl {
  struct TrackPose {
    Pose pose;  // centre in scene coordinates (frame coordinates of an unmoved camera)
    double ttc = std::numeric_limits<double>::infinity();
  };

  struct Track {
    int id = 0;
    bool distractor = false;
    ShapeModel model;
    std::function<TrackPose(double)> at;
    double ttc0 = std::numeric_limits<double>::infinity();
    double closing_speed = 0.0;
  };

  struct Occluder {
    cv::Mat premul, alpha;
    cv::Point2d centre_mid;  // scene coordinates at t_mid
    cv::Point2d velocity;    // px/s
    double t_mid = 0.0;
    cv::Point topLeft(double t, cv::Point2d cam) const {
      const cv::Point2d c = centre_mid + velocity * (t - t_mid) - cam;
      return {static_cast<int>(std::floor(c.x - 0.5 * alpha.cols + 0.5)), static_cast<int>(std::floor(c.y - 0.5 * alpha.rows + 0.5))};
    }
  };

  struct Rendered {
    int track = 0;
    cv::Rect patch;  // frame coordinates, unclipped
    cv::Mat col_store, a_store;
    cv::Mat col, a;  // views of the stores, patch-sized
    ObstacleTruth truth;
    double total = 0.0;
  };

  // The modifiers of the scenario name.
  struct Flags {
    bool jitter = false, jerk = false, blur = false, noise = false, illumination = false, occlusion = false;
    bool flock = false, overlay = false, glare = false, clutter = false, small = false, large = false;
    int cls = -1;
  };

  // Where the scenery put the horizon and the sun (frame coordinates of an unmoved camera).
  struct SceneryLayout {
    double horizon = 0.0;
    cv::Point2d sun;
  };

  // What a base scenario places its obstacles with.
  struct ObstaclePlacement {
    double width = 0.0, height = 0.0;  // frame size, px
    double duration = 0.0;             // s
    double horizon = 0.0;              // frame row of the horizon
    double sky_y = 0.0;                // a typical obstacle row
    double size_mult = 1.0;            // the small / large modifiers
    int cls = -1;                      // the as_* modifiers; -1: the scenario's own class
    ObstacleClass mainClass(ObstacleClass own) const { return cls >= 0 ? static_cast<ObstacleClass>(cls) : own; }
  };

  using PlaceObstacles = void (Impl::*)(const ObstaclePlacement& at, Rng& rng);
  struct BaseScenario {
    const char* name;
    int default_frames;
    PlaceObstacles place;
  };

  ScenarioConfig cfg;
  ScenarioInfo info;
  int frames = 0, W = 0, H = 0;
  double fps = 30.0, f_px = 0.0, duration = 0.0;
  bool mono16 = false;
  std::string base_name;
  Flags flags;

  BackgroundSpec bg;
  cv::Mat pano;
  cv::Point2d base;
  std::vector<Track> tracks;
  std::vector<Occluder> occluders;
  std::vector<std::function<cv::Point2d(double)>> camera_parts;
  double exposure = 0.35;  // fraction of the frame period
  float noise_sigma = 1.0f, fpn_sigma = 0.0f;
  std::vector<std::int16_t> noise, fpn;

  // Per-frame buffers.
  std::vector<Rendered> objs;
  std::vector<int> order;  // indices into objs, far to near
  std::vector<std::vector<ProjectedPlate>> samples;
  cv::Mat cov_store, scol_store, sa_store;
  std::vector<std::uint32_t> blur_scratch;
  cv::Mat mask_tmp;
  std::vector<float> colmax_;

  cv::Point2d cameraAt(double t) const {
    cv::Point2d d(0, 0);
    for (const auto& f : camera_parts) d += f(t);
    return d;
  }
  cv::Point2f blurAt(int i) const {
    const double t = i / fps;
    const cv::Point2d d = cameraAt(t) - cameraAt(t - exposure / fps);
    if (std::fabs(d.x) < 1.5 && std::fabs(d.y) < 1.5) return {0.0f, 0.0f};
    // The frame shows the scene at the end of the exposure; earlier in the exposure the camera
    // window was d behind, so the content appeared shifted by up to +d.
    return {static_cast<float>(d.x), static_cast<float>(d.y)};
  }

  // Set-up (scene_setup.cpp).
  void setup();
  const BaseScenario& parseName();
  void setModifierFlag(const std::string& modifier);
  SceneryLayout chooseScenery();
  void placeObstacles(const BaseScenario& scenario, double horizon);
  void addTrack(int id, ObstacleClass c, std::function<TrackPose(double)> fn, bool distractor = false);
  void setClosingSpeeds();
  void renderPanorama(const SceneryLayout& layout);
  void makeNoiseTables();
  void fillObstacleInfo();

  // Base scenarios (scene_scenarios.cpp).
  static const BaseScenario& findBaseScenario(const std::string& name);
  void placeCollisionCourse(const ObstaclePlacement& at, Rng& rt, double span_frac, double ratio);
  void placeApproach(const ObstaclePlacement& at, Rng& rt);
  void placeRecede(const ObstaclePlacement& at, Rng& rt);
  void placeDemo(const ObstaclePlacement& at, Rng& rt);
  void placeCrossing(const ObstaclePlacement& at, Rng& rt);
  void placeRotation(const ObstaclePlacement& at, Rng& rt);
  void placeOutOfView(const ObstaclePlacement& at, Rng& rt);
  void placeMulti(const ObstaclePlacement& at, Rng& rt);
  void placeBird(const ObstaclePlacement& at, Rng& rt);
  void placeTiny(const ObstaclePlacement& at, Rng& rt);

  // Modifiers applied at set-up (scene_modifiers.cpp).
  double raiseHorizon(Rng& rb);
  void chooseNoiseLevels();
  void addErraticMotion();
  void addGlare(SceneryLayout& layout);
  void addFlock();
  void addOcclusion();
  void addJitter();
  void addJerks();
  cv::Rect2f mainBoundsAt(double t) const;

  // One obstacle over one exposure (scene_rasterize.cpp).
  struct Extent {
    float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  };
  void rasterize(int track_index, double t, const cv::Point2d& cam, const std::vector<cv::Point>& blur_off, Rendered& ro);
  int sampleExposure(const Track& tr, double t, const TrackPose& mid, const cv::Point2d& cam, Extent& ext);
  bool placePatch(const Extent& ext, Rendered& ro) const;
  void drawSamples(int n, Rendered& ro);
  void drawPlate(const ProjectedPlate& pl, const cv::Rect& patch, cv::Mat& C, cv::Mat& A);
  void measureDrawnBox(const std::vector<cv::Point>& blur_off, Rendered& ro);

  // Frames (scene_frame.cpp).
  void computeObjects(int i);
  template <typename T, int CN>
  void composite(cv::Mat& out);
  void changeIllumination(cv::Mat& out, double t) const;
  void addSensorNoise(cv::Mat& out, int i) const;
  void drawOverlay(cv::Mat& out, int i, double t) const;
};

}  // namespace scene
}  // namespace obstacle_tracker
