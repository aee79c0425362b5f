// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The scene generator's private state, shared by its source files.
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

  struct Flags {
    bool jitter = false, jerk = false, blur = false, noise = false, illumination = false, occlusion = false;
    bool flock = false, overlay = false, glare = false, clutter = false, small = false, large = false;
    int cls = -1;
  };

  ScenarioConfig cfg;
  ScenarioInfo info;
  int frames = 0, W = 0, H = 0;
  double fps = 30.0, f_px = 0.0, duration = 0.0;
  bool mono16 = false;
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

  void setup();
  void rasterize(int track_index, double t, const cv::Point2d& cam, const std::vector<cv::Point>& blur_off, Rendered& ro);
  void computeObjects(int i);
  template <typename T, int CN>
  void composite(cv::Mat& out);
};

}  // namespace scene
}  // namespace obstacle_tracker
