// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The modifiers that change a scene at set-up (listScenarios() describes them). Illumination and
// overlay act on the finished frames instead (scene_frame.cpp); small, large and as_* on the
// base scenario's placement. Each modifier that draws random numbers has its own generator.
#include <algorithm>
#include <cmath>

#include "obstacle_tracker/core/box_geometry.h"
#include "scene_generator_impl.h"

namespace obstacle_tracker {
namespace scene {

// clutter (and the tiny scenario): a high horizon with trees and buildings behind the obstacle.
double SceneGenerator::Impl::raiseHorizon(Rng& rb) {
  const double Hd = H;
  const double horizon = Hd * rb.uniform(0.55, 0.62);
  bg.trees = std::max(bg.trees, 0.7f);
  bg.buildings = std::max(bg.buildings, 0.35f);
  return horizon;
}

// noise: stronger sensor noise; the thermal mode always has some column fixed-pattern noise.
void SceneGenerator::Impl::chooseNoiseLevels() {
  noise_sigma = mono16 ? 6.0f : 1.0f;
  fpn_sigma = mono16 ? 4.0f : 0.0f;
  if (flags.noise) {
    noise_sigma = mono16 ? 45.0f : 5.5f;
    fpn_sigma = mono16 ? 25.0f : 2.0f;
  }
  if (base_name == "demo") noise_sigma = mono16 ? 20.0f : 2.5f;
}

// blur: a whole frame period of exposure and an erratic zig-zag of the main obstacle.
void SceneGenerator::Impl::addErraticMotion() {
  const double Wd = W, Hd = H;
  exposure = 1.0;
  auto f = tracks[0].at;
  tracks[0].at = [=](double t) {
    TrackPose p = f(t);
    p.pose.centre.x += static_cast<float>(0.06 * Wd * sinTurn(1.1 * t));
    p.pose.centre.y += static_cast<float>(0.035 * Hd * sinTurn(1.7 * t + 0.3));
    return p;
  };
}

cv::Rect2f SceneGenerator::Impl::mainBoundsAt(double t) const {
  std::vector<ProjectedPlate> pl;
  projectShape(tracks[0].model, tracks[0].at(t).pose, pl);
  return projectedBounds(pl);
}

// glare: the sun just beside the main obstacle at mid-sequence.
void SceneGenerator::Impl::addGlare(SceneryLayout& layout) {
  const double Wd = W, Hd = H;
  const cv::Rect2f b = mainBoundsAt(0.5 * duration);
  layout.sun = cv::Point2d(core::boxCentre(cv::Rect2d(b)).x + 0.12 * Wd + 0.5 * b.width, b.y - 0.08 * Hd);
  bg.glare = 0.9f;
}

// flock: birds (distractors) passing near the main obstacle at mid-sequence.
void SceneGenerator::Impl::addFlock() {
  const double Wd = W, Hd = H, D = duration;
  const double t_mid = 0.5 * D;
  Rng rf(hashCombine(cfg.seed, 4));
  const cv::Rect2f b = mainBoundsAt(t_mid);
  const cv::Point2d b_centre = core::boxCentre(cv::Rect2d(b));
  const cv::Point2d c_mid(b_centre.x + rf.uniform(-0.05, 0.05) * Wd, b_centre.y + rf.uniform(-0.08, 0.08) * Hd);
  const double vx = (rf.chance(0.5) ? 1.0 : -1.0) * 1.2 * Wd / D;
  const double vy = rf.uniform(-0.15, 0.15) * Hd / D;
  const int n = rf.uniformInt(12, 22);
  for (int k = 0; k < n; ++k) {
    const double ox = rf.uniform(-0.12, 0.12) * Wd, oy = rf.uniform(-0.06, 0.06) * Hd;
    const double sc = std::max(2.0, rf.uniform(0.012, 0.024) * Wd);
    const double ph = rf.uniform(0, 1), fr = rf.uniform(3.0, 4.5), wob = rf.uniform(0.004, 0.012) * Wd;
    const float yaw = static_cast<float>((vx > 0 ? 0.0 : kPi) + rf.uniform(-0.4, 0.4));
    addTrack(101 + k, ObstacleClass::kBird, [=](double t) {
      TrackPose p;
      const double dt = t - t_mid;
      p.pose.centre = cv::Point2f(static_cast<float>(c_mid.x + ox + vx * dt + wob * sinTurn(0.5 * t + ph)),
                                  static_cast<float>(c_mid.y + oy + vy * dt + wob * sinTurn(0.7 * t + 2 * ph)));
      p.pose.scale = static_cast<float>(sc);
      p.pose.yaw = yaw;
      p.pose.elevation = -0.3f;
      p.pose.flap = static_cast<float>(0.2 + 0.6 * sinTurn(fr * t + ph));
      return p;
    }, true);
  }
}

// occlusion: a dense cloud drifting across the main obstacle.
void SceneGenerator::Impl::addOcclusion() {
  const double Wd = W, Hd = H, D = duration;
  const double t_mid = 0.5 * D;
  Rng ro(hashCombine(cfg.seed, 5));
  const cv::Rect2f b = mainBoundsAt(t_mid);
  const cv::Rect2f b2 = mainBoundsAt(t_mid + 0.05);
  const cv::Point2d c_t = core::boxCentre(cv::Rect2d(b));
  const cv::Point2d v_t = (core::boxCentre(cv::Rect2d(b2)) - c_t) * (1.0 / 0.05);
  const double min_rel = 0.45 * Wd / D;
  Occluder oc;
  oc.t_mid = t_mid;
  oc.velocity = cv::Point2d(0, 0);
  double v_rel = std::fabs(v_t.x);
  if (v_rel < min_rel) {
    const double s = v_t.x >= 0 ? 1.0 : -1.0;
    oc.velocity = cv::Point2d(v_t.x - s * min_rel, v_t.y);
    v_rel = min_rel;
  }
  // Fully hidden for about 15 % of the sequence: the opaque core (about 3/4 of the sprite's
  // width, renderCloudSprite) must exceed the obstacle by the distance travelled meanwhile.
  const double core_w = std::max<double>(b.width, b.height) * 1.1 + v_rel * 0.15 * D;
  const int sw = static_cast<int>(std::min(core_w / 0.75, 1.5 * Wd)) + 8;
  const int sh = static_cast<int>(std::min(std::max(0.65 * sw, 2.4 * b.height + 8.0), 1.2 * Hd)) + 8;
  oc.centre_mid = c_t + cv::Point2d(0, ro.uniform(-0.1, 0.1) * b.height);
  renderCloudSprite(cv::Size(sw, sh), hashCombine(cfg.seed, 6), mono16, oc.premul, oc.alpha);
  occluders.push_back(std::move(oc));
}

// jitter (and the demo, gentler): camera shake, a sum of low- and high-frequency oscillations.
void SceneGenerator::Impl::addJitter() {
  const double Hd = H;
  Rng rj(hashCombine(cfg.seed, 7));
  const double a = (base_name == "demo" ? 0.0025 : 0.006) * Hd;
  double ph[6];
  for (double& p : ph) p = rj.uniform(0, 1);
  camera_parts.push_back([=](double t) {
    return cv::Point2d(a * (0.6 * sinTurn(0.8 * t + ph[0]) + 0.3 * sinTurn(2.3 * t + ph[1]) + 0.25 * sinTurn(7.1 * t + ph[2])),
                       a * (0.5 * sinTurn(0.6 * t + ph[3]) + 0.3 * sinTurn(2.9 * t + ph[4]) + 0.2 * sinTurn(8.3 * t + ph[5])));
  });
}

// jerk: sudden camera jerks (two frames), held, then re-centred; about one every three seconds.
void SceneGenerator::Impl::addJerks() {
  const double Wd = W, D = duration;
  Rng rj(hashCombine(cfg.seed, 8));
  struct Jerk { double t0, rise, hold, ret; cv::Point2d v; };
  std::vector<Jerk> jerks;
  const int n = std::max(2, static_cast<int>(D / 3.0));
  for (int k = 0; k < n; ++k) {
    Jerk j;
    j.t0 = D * (k + rj.uniform(0.15, 0.5)) / n;
    j.rise = 2.0 / fps;
    j.hold = rj.uniform(0.5, 1.0);
    j.ret = rj.uniform(0.3, 0.6);
    const double ang = rj.uniform(0, 2 * kPi), mag = rj.uniform(0.06, 0.12) * Wd;
    j.v = cv::Point2d(detCos(ang) * mag, detSin(ang) * mag * 0.7);
    jerks.push_back(j);
  }
  camera_parts.push_back([=](double t) {
    cv::Point2d d(0, 0);
    for (const auto& j : jerks)
      d += j.v * (smooth01(j.t0, j.t0 + j.rise, t) - smooth01(j.t0 + j.rise + j.hold, j.t0 + j.rise + j.hold + j.ret, t));
    return d;
  });
}

}  // namespace scene
}  // namespace obstacle_tracker
