// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Scene generator: the scenario list and the public interface (scene_generator.h). The work is
// in the files that scene_generator_impl.h names.
#include "obstacle_tracker/scene/scene_generator.h"

#include <stdexcept>

#include "scene_generator_impl.h"

namespace obstacle_tracker {
namespace scene {

const ObstacleTruth* FrameTruth::find(int id) const {
  for (const auto& o : obstacles)
    if (o.id == id) return &o;
  return nullptr;
}

std::vector<ScenarioDescription> listScenarios() {
  return {
      {"demo", false, "the README demo: a light aircraft approaching (time to contact known) in a sky with clouds above a tree line, mild camera jitter and sensor noise"},
      {"approach", false, "a fixed-wing aircraft on a collision course: size grows as s0*T/(T-t), time to contact T-t known per frame"},
      {"recede", false, "a fixed-wing aircraft flying away: size falls as s0*T/(T+t) to a sixth over the scene; not closing (time to contact +inf)"},
      {"crossing", false, "a fixed-wing aircraft crossing the view at constant distance; the camera pans slowly after it"},
      {"rotation", false, "a multirotor hovering and drifting with planar rotation (image roll) and out-of-plane rotation (yaw, view elevation, tilt)"},
      {"out_of_view", false, "a multirotor that flies out of the frame on one side, comes back, leaves on the other side and comes back"},
      {"multi", false, "three obstacles (multirotor id 1, aircraft id 2, bird id 3) whose paths cross near the centre, hiding each other"},
      {"bird", false, "a flapping bird crossing the view with a wavy flight path"},
      {"tiny", false, "a multirotor a few pixels wide drifting just above a cluttered horizon (trees, buildings, a lattice mast)"},
      {"jitter", true, "camera shake: a sum of low- and high-frequency oscillations of a few pixels"},
      {"jerk", true, "sudden camera jerks (a tenth of the frame in two frames, held, then re-centred) with camera motion blur"},
      {"blur", true, "long exposure (a whole frame period) and an erratic zig-zag of the main obstacle: strong motion blur"},
      {"noise", true, "strong sensor noise (and column fixed-pattern noise in the thermal mode)"},
      {"illumination", true, "illumination change: the scene dims to about half and recovers (auto-exposure / sun behind cloud), with a colour shift"},
      {"occlusion", true, "a dense cloud drifts across the main obstacle: partial, then full, then partial occlusion"},
      {"flock", true, "a flock of birds (distractors, ids from 101) crosses close to the main obstacle"},
      {"overlay", true, "camera on-screen display: date/time, azimuth/elevation, field of view, frame counter and a reticle"},
      {"glare", true, "the sun next to the main obstacle's path, with strong glare and a lens streak"},
      {"clutter", true, "a high horizon (trees, buildings, a mast) with the obstacle in front of it"},
      {"small", true, "the main obstacle about a third of its usual size"},
      {"large", true, "the main obstacle about two and a half times its usual size"},
      {"as_fixed_wing", true, "the main obstacle is a fixed-wing aircraft"},
      {"as_multirotor", true, "the main obstacle is a multirotor"},
      {"as_bird", true, "the main obstacle is a bird"},
  };
}

SceneGenerator::SceneGenerator(const ScenarioConfig& config) : impl_(new Impl) {
  if (config.size.width < 16 || config.size.height < 16 || config.size.width > 8192 || config.size.height > 8192)
    throw std::invalid_argument("scene: frame size must be between 16x16 and 8192x8192");
  if (!(config.fps > 0.0 && config.fps <= 1000.0)) throw std::invalid_argument("scene: fps must be in (0, 1000]");
  if (config.frames < 0) throw std::invalid_argument("scene: frames must be >= 0 (0 = default)");
  impl_->cfg = config;
  impl_->setup();
}

SceneGenerator::~SceneGenerator() = default;
SceneGenerator::SceneGenerator(SceneGenerator&&) noexcept = default;
SceneGenerator& SceneGenerator::operator=(SceneGenerator&&) noexcept = default;

const ScenarioConfig& SceneGenerator::config() const { return impl_->cfg; }
const ScenarioInfo& SceneGenerator::info() const { return impl_->info; }
int SceneGenerator::frameCount() const { return impl_->frames; }
double SceneGenerator::fps() const { return impl_->fps; }
cv::Size SceneGenerator::size() const { return cv::Size(impl_->W, impl_->H); }
int SceneGenerator::type() const { return impl_->mono16 ? CV_16UC1 : CV_8UC3; }

void SceneGenerator::thermalDisplayRange(double& lo, double& hi) const {
  lo = 5500.0;
  hi = 13500.0;
}

SceneGenerator makeScenario(const std::string& name, std::uint64_t seed, int frames, cv::Size size, bool mono16, double fps) {
  ScenarioConfig c;
  c.name = name;
  c.seed = seed;
  c.frames = frames;
  c.size = size;
  c.mono16 = mono16;
  c.fps = fps;
  return SceneGenerator(c);
}

}  // namespace scene
}  // namespace obstacle_tracker
