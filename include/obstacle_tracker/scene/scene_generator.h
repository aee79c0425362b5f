// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Generated flight scenes with exact per-frame ground truth.
//
//   auto gen = obstacle_tracker::scene::makeScenario("approach+jitter+noise", 7, 240, {640, 480});
//   cv::Mat frame; obstacle_tracker::scene::FrameTruth truth;
//   for (int i = 0; i < gen.frameCount(); ++i) gen.renderFrame(i, frame, &truth);
//
// A scenario name is a base motion followed by '+'-separated modifiers (listScenarios()). The
// same (name, seed, frames, size, mono16, fps) gives the same bytes on any machine: all random
// numbers come from the generator's own integer PRNG, and the rendering uses basic arithmetic
// (see random.h, raster.h).
//
// Ground truth conventions: boxes are in pixels, top-left corner + size, with pixel (c, r)
// covering [c, c+1) x [r, r+1). `box` is the extent of the drawn obstacle (every pixel whose
// coverage is at least half a grey level), refined to sub-pixel from the coverage of the outermost
// pixel rows and columns, so it matches the drawn mask within a pixel. It covers the whole obstacle
// (including its motion-blur streak), clipped to the frame, even where a cloud or a nearer
// obstacle hides it; `visible_fraction` is the share of the obstacle's
// area that is inside the frame and not hidden; `visible` is visible_fraction >= kVisibleThreshold.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/scene/shapes.h"

namespace obstacle_tracker {
namespace scene {

constexpr float kVisibleThreshold = 0.2f;

struct ScenarioConfig {
  std::string name = "demo";     // base[+modifier...], see listScenarios()
  std::uint64_t seed = 1;
  int frames = 0;                // 0: the scenario's default length
  cv::Size size{640, 480};       // at least 16 x 16
  bool mono16 = false;           // CV_16UC1 thermal-like frames instead of CV_8UC3 BGR
  double fps = 30.0;             // (0, 1000]
  bool render_obstacles = true;  // false: the same scene without the obstacles (for tests)
};

struct ObstacleTruth {
  int id = 0;                     // 1 = the main obstacle (groundtruth_rect.txt)
  ObstacleClass cls = ObstacleClass::kFixedWing;
  bool distractor = false;        // part of a bird flock, not a tracking target
  cv::Rect2f box;                 // see the conventions above; empty when fully outside the frame
  bool visible = false;
  float visible_fraction = 0.0f;  // [0, 1]
  double distance_m = 0.0;        // from the camera (from size_m, focal length and scale)
  double time_to_contact = std::numeric_limits<double>::infinity();  // s; +inf when not closing
  double scale_px = 0.0;          // pixels per model unit (the drawn size before projection)
  cv::Rect2f shape_box;           // analytic extent of the model's projected outline (all plates,
                                  // exposure included), unclipped; proportional to scale_px
};

struct FrameTruth {
  int frame = 0;
  double time = 0.0;  // s, frame / fps
  std::vector<ObstacleTruth> obstacles;  // targets (ids 1, 2, 3) first, then distractors
  // The obstacle with this id, or nullptr.
  const ObstacleTruth* find(int id) const;
};

// Static facts about a scene, written to scene.yaml.
struct ObstacleInfo {
  int id = 0;
  ObstacleClass cls = ObstacleClass::kFixedWing;
  bool distractor = false;
  double size_m = 0.0;                 // wingspan / diagonal
  double time_to_contact_at_start = std::numeric_limits<double>::infinity();  // s (approach)
  double closing_speed_mps = 0.0;      // approach only
};

struct ScenarioInfo {
  std::string name;
  std::string description;
  double focal_length_px = 0.0;
  double horizontal_fov_deg = 0.0;
  std::vector<ObstacleInfo> obstacles;
};

struct ScenarioDescription {
  std::string name;
  bool modifier = false;  // false: a base motion; true: combine with '+'
  std::string description;
};

// The base scenarios and the modifiers, in a fixed order; "demo" is the README's demo.
std::vector<ScenarioDescription> listScenarios();

class SceneGenerator {
 public:
  // Throws std::invalid_argument for an unknown scenario or modifier, frames < 1 (after the
  // default), a size below 16 x 16 or a bad fps.
  explicit SceneGenerator(const ScenarioConfig& config);
  ~SceneGenerator();
  SceneGenerator(SceneGenerator&&) noexcept;
  SceneGenerator& operator=(SceneGenerator&&) noexcept;
  SceneGenerator(const SceneGenerator&) = delete;
  SceneGenerator& operator=(const SceneGenerator&) = delete;

  const ScenarioConfig& config() const;
  const ScenarioInfo& info() const;
  int frameCount() const;
  double fps() const;
  cv::Size size() const;
  int type() const;  // CV_8UC3 or CV_16UC1

  // Renders frame i (0 <= i < frameCount(), else std::out_of_range) into out (reallocated only
  // when its size/type differ); fills *truth when given. Frames can be rendered in any order.
  void renderFrame(int i, cv::Mat& out, FrameTruth* truth = nullptr);
  // Ground truth of frame i without rendering the frame.
  FrameTruth truth(int i);
  // The drawn coverage of obstacle `id` in frame i, CV_8UC1 (0..255; any non-zero coverage is at
  // least 1), unoccluded, after the same camera motion blur as the frame. All zero when absent.
  void renderObstacleMask(int i, int id, cv::Mat& mask);
  // Thermal counts mapped to 0..255 by the 8-bit previews (video output of a mono16 scene).
  void thermalDisplayRange(double& lo, double& hi) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

SceneGenerator makeScenario(const std::string& name, std::uint64_t seed, int frames = 0,
                            cv::Size size = cv::Size(640, 480), bool mono16 = false, double fps = 30.0);

}  // namespace scene
}  // namespace obstacle_tracker
