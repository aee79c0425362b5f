// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Scene set-up: the scenario name, the scenery, the obstacles and the camera motion, then the
// panorama and the noise tables. The steps draw from separate seeded generators, in the order
// setup() calls them.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "scene_generator_impl.h"

namespace obstacle_tracker {
namespace scene {

void SceneGenerator::Impl::setup() {
  W = cfg.size.width;
  H = cfg.size.height;
  mono16 = cfg.mono16;
  fps = cfg.fps;
  f_px = 0.5 * W * 1.7320508075688772;  // 60 degree horizontal field of view
  info.horizontal_fov_deg = 60.0;

  const BaseScenario& scenario = parseName();
  frames = cfg.frames > 0 ? cfg.frames : scenario.default_frames;
  if (frames < 1) throw std::invalid_argument("scene: frames must be >= 1");
  duration = frames / fps;

  SceneryLayout layout = chooseScenery();
  chooseNoiseLevels();
  placeObstacles(scenario, layout.horizon);
  if (flags.blur) addErraticMotion();
  setClosingSpeeds();
  // Glare, flock and occlusion are placed around the main obstacle's path, zig-zag included.
  if (flags.glare) addGlare(layout);
  if (flags.flock) addFlock();
  if (flags.occlusion) addOcclusion();
  if (flags.jitter) addJitter();
  if (flags.jerk) addJerks();

  renderPanorama(layout);
  makeNoiseTables();
  fillObstacleInfo();
  objs.resize(tracks.size());
}

// "base+mod+mod": sets the flags, the name and description; returns the base scenario.
const SceneGenerator::Impl::BaseScenario& SceneGenerator::Impl::parseName() {
  std::vector<std::string> tok;
  {
    std::stringstream ss(cfg.name);
    std::string t;
    while (std::getline(ss, t, '+'))
      if (!t.empty()) tok.push_back(t);
  }
  if (tok.empty()) throw std::invalid_argument("scene: empty scenario name");
  const auto all = listScenarios();
  auto known = [&](const std::string& n, bool modifier) {
    for (const auto& d : all)
      if (d.name == n && d.modifier == modifier) return true;
    return false;
  };
  base_name = tok[0];
  if (!known(base_name, false))
    throw std::invalid_argument("scene: unknown base scenario '" + base_name + "' (generate_scene --list names them)");
  for (std::size_t k = 1; k < tok.size(); ++k) {
    const std::string& m = tok[k];
    if (!known(m, true)) throw std::invalid_argument("scene: unknown modifier '" + m + "' in '" + cfg.name + "'");
    setModifierFlag(m);
  }
  if (base_name == "demo") {
    flags.jitter = true;
  }
  for (const auto& d : all)
    if (d.name == base_name) info.description = d.description;
  info.name = cfg.name;
  return findBaseScenario(base_name);
}

// The flag a known modifier sets (listScenarios() lists the names).
void SceneGenerator::Impl::setModifierFlag(const std::string& modifier) {
  struct FlagModifier {
    const char* name;
    bool Flags::*flag;
  };
  static constexpr FlagModifier kFlagModifiers[] = {
      {"jitter", &Flags::jitter},       {"jerk", &Flags::jerk},   {"blur", &Flags::blur},
      {"noise", &Flags::noise},         {"illumination", &Flags::illumination},
      {"occlusion", &Flags::occlusion}, {"flock", &Flags::flock}, {"overlay", &Flags::overlay},
      {"glare", &Flags::glare},         {"clutter", &Flags::clutter},
      {"small", &Flags::small},         {"large", &Flags::large},
  };
  struct ClassModifier {
    const char* name;
    ObstacleClass cls;
  };
  static constexpr ClassModifier kClassModifiers[] = {
      {"as_fixed_wing", ObstacleClass::kFixedWing},
      {"as_multirotor", ObstacleClass::kMultirotor},
      {"as_bird", ObstacleClass::kBird},
  };
  for (const auto& m : kFlagModifiers)
    if (modifier == m.name) flags.*m.flag = true;
  for (const auto& m : kClassModifiers)
    if (modifier == m.name) flags.cls = static_cast<int>(m.cls);
}

// Sky, clouds and horizon from the scene seed.
SceneGenerator::Impl::SceneryLayout SceneGenerator::Impl::chooseScenery() {
  const double Wd = W, Hd = H;
  Rng rb(hashCombine(cfg.seed, 1));
  bg.frame_height = static_cast<float>(H);
  bg.cloud_cover = static_cast<float>(rb.uniform(0.18, 0.5));
  bg.cloud_scale = static_cast<float>(rb.uniform(0.7, 1.3));
  bg.palette = rb.uniformInt(0, 2);
  bg.trees = static_cast<float>(rb.uniform(0.35, 0.85));
  bg.buildings = static_cast<float>(rb.uniform(0.0, 0.4));
  bg.mast = rb.chance(0.3);
  bg.glare = static_cast<float>(rb.uniform(0.15, 0.35));
  double horizon = Hd * rb.uniform(0.78, 0.9);
  if (flags.clutter || base_name == "tiny") horizon = raiseHorizon(rb);
  if (base_name == "tiny") bg.mast = true;
  if (base_name == "demo") {
    bg.cloud_cover = static_cast<float>(rb.uniform(0.2, 0.35));
    bg.palette = 0;
    horizon = Hd * 0.84;
  }
  const cv::Point2d sun(rb.chance(0.5) ? Wd * rb.uniform(-0.3, 0.05) : Wd * rb.uniform(0.95, 1.3), Hd * rb.uniform(-0.35, 0.05));
  SceneryLayout layout;
  layout.horizon = horizon;
  layout.sun = sun;
  return layout;
}

void SceneGenerator::Impl::placeObstacles(const BaseScenario& scenario, double horizon) {
  const double Hd = H;
  ObstaclePlacement at;
  at.width = W;
  at.height = H;
  at.duration = duration;
  at.horizon = horizon;
  at.size_mult = flags.small ? 0.35 : (flags.large ? 2.5 : 1.0);
  at.cls = flags.cls;
  Rng rt(hashCombine(cfg.seed, 2));
  at.sky_y = flags.clutter ? horizon - 0.07 * Hd : Hd * 0.4;
  (this->*scenario.place)(at, rt);
}

// Each obstacle's model has its own generator, so adding obstacles leaves the others unchanged.
void SceneGenerator::Impl::addTrack(int id, ObstacleClass c, std::function<TrackPose(double)> fn, bool distractor) {
  Track tr;
  tr.id = id;
  tr.distractor = distractor;
  Rng rm(hashCombine(cfg.seed, 3, static_cast<std::uint64_t>(id)));
  tr.model = makeModel(c, rm);
  tr.at = std::move(fn);
  tracks.push_back(std::move(tr));
}

// Physical quantities from the drawn scale: distance = f * size / scale.
void SceneGenerator::Impl::setClosingSpeeds() {
  for (auto& tr : tracks) {
    if (std::isfinite(tr.ttc0)) {
      const double d0 = f_px * tr.model.size_m / tr.at(0.0).pose.scale;
      tr.closing_speed = d0 / tr.ttc0;
    }
  }
}

// Panorama covering every camera window (frame times and exposure starts).
void SceneGenerator::Impl::renderPanorama(const SceneryLayout& layout) {
  double mnx = 0, mny = 0, mxx = 0, mxy = 0;
  for (int i = 0; i < frames; ++i) {
    for (double t : {i / fps, (i - exposure) / fps}) {
      const cv::Point2d d = cameraAt(t);
      mnx = std::min(mnx, d.x);
      mny = std::min(mny, d.y);
      mxx = std::max(mxx, d.x);
      mxy = std::max(mxy, d.y);
    }
  }
  const int margin = 2;
  base = cv::Point2d(margin - std::floor(mnx), margin - std::floor(mny));
  bg.size = cv::Size(W + static_cast<int>(std::ceil(mxx) - std::floor(mnx)) + 2 * margin + 1,
                     H + static_cast<int>(std::ceil(mxy) - std::floor(mny)) + 2 * margin + 1);
  bg.horizon_y = static_cast<float>(base.y + layout.horizon);
  bg.sun = cv::Point2f(static_cast<float>(base.x + layout.sun.x), static_cast<float>(base.y + layout.sun.y));
  bg.seed = hashCombine(cfg.seed, 9);
  renderBackground(bg, mono16, pano);
}

// Noise tables: temporal noise (two frames long, read at a per-frame offset) and column
// fixed-pattern noise; integer Irwin-Hall samples (sum of four 16-bit uniforms).
void SceneGenerator::Impl::makeNoiseTables() {
  Rng rn(hashCombine(cfg.seed, 10));
  const std::size_t cn = mono16 ? 1 : 3;
  const std::size_t npx = static_cast<std::size_t>(W) * static_cast<std::size_t>(H) * cn;
  if (noise_sigma > 0.0f) {
    noise.resize(2 * npx);
    // Sum of four U(0, 65535): mean 131070, sd 65536 * sqrt(4/12) = 37837.
    const float k = noise_sigma / 37837.0f;
    for (auto& v : noise) {
      const std::uint64_t r = rn.next();
      const std::int64_t s = static_cast<std::int64_t>(r & 0xFFFF) + static_cast<std::int64_t>((r >> 16) & 0xFFFF) +
                             static_cast<std::int64_t>((r >> 32) & 0xFFFF) + static_cast<std::int64_t>(r >> 48) - 131070;
      v = static_cast<std::int16_t>(std::floor(static_cast<float>(s) * k + 0.5f));
    }
  }
  if (fpn_sigma > 0.0f) {
    fpn.resize(static_cast<std::size_t>(W) * cn);
    for (auto& v : fpn) v = static_cast<std::int16_t>(std::floor(static_cast<float>(rn.normal()) * fpn_sigma + 0.5f));
  }
}

void SceneGenerator::Impl::fillObstacleInfo() {
  info.focal_length_px = f_px;
  for (const auto& tr : tracks) {
    ObstacleInfo oi;
    oi.id = tr.id;
    oi.cls = tr.model.cls;
    oi.distractor = tr.distractor;
    oi.size_m = tr.model.size_m;
    oi.time_to_contact_at_start = tr.ttc0;
    oi.closing_speed_mps = tr.closing_speed;
    info.obstacles.push_back(oi);
  }
}

}  // namespace scene
}  // namespace obstacle_tracker
