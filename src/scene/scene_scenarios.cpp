// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The base scenarios: for each name, its default length and the obstacles it places. Each
// obstacle is a path t -> pose, a closure that copies its parameters: it outlives the set-up.
#include <algorithm>
#include <stdexcept>

#include "scene_generator_impl.h"

namespace obstacle_tracker {
namespace scene {

namespace {

// Flapping with glides: amplitude modulated by a slow envelope.
float flapAt(double t, double freq, double phase) {
  const double env = 0.55 + 0.45 * sinTurn(0.17 * t + phase);
  return static_cast<float>(0.2 + 0.65 * env * sinTurn(freq * t + phase));
}

// An aircraft flying straight towards the camera or away from it: its image centre moves along
// a line through `focus` (the point it flies at or from), at `offset` from it when its size
// factor k is 1, and its attitude stays fixed.
struct LineOfSight {
  cv::Point2d focus, offset;
  float yaw = 0.0f, elevation = 0.0f, bank = 0.0f;
  double flap_phase = 0.0;
};

LineOfSight drawLineOfSight(Rng& rt, cv::Point2d focus, double Wd, double Hd, double offset_scale) {
  LineOfSight l;
  l.focus = focus;
  const double ang = rt.uniform(0.0, 2.0 * kPi);
  l.offset = cv::Point2d(detCos(ang) * 0.09 * Wd, detSin(ang) * 0.06 * Hd) * offset_scale;
  l.yaw = static_cast<float>(0.5 * kPi + rt.uniform(-0.45, 0.45));
  l.elevation = static_cast<float>(rt.uniform(-0.18, 0.04));
  l.bank = static_cast<float>(rt.uniform(-0.12, 0.12));
  l.flap_phase = rt.uniform(0, 1);
  return l;
}

// The pose at time t with size factor k (1 at the reference size span0).
Pose poseOnLineOfSight(const LineOfSight& l, double span0, double k, double t) {
  Pose p;
  p.centre = cv::Point2f(l.focus + l.offset * k);
  p.scale = static_cast<float>(span0 * k);
  p.yaw = l.yaw;
  p.elevation = l.elevation;
  p.bank = l.bank;
  p.flap = flapAt(t, 3.2, l.flap_phase);
  return p;
}

}  // namespace

const SceneGenerator::Impl::BaseScenario& SceneGenerator::Impl::findBaseScenario(const std::string& name) {
  static const BaseScenario kScenarios[] = {
      {"demo", 240, &Impl::placeDemo},
      {"approach", 180, &Impl::placeApproach},
      {"recede", 180, &Impl::placeRecede},
      {"crossing", 180, &Impl::placeCrossing},
      {"rotation", 180, &Impl::placeRotation},
      {"out_of_view", 240, &Impl::placeOutOfView},
      {"multi", 210, &Impl::placeMulti},
      {"bird", 150, &Impl::placeBird},
      {"tiny", 180, &Impl::placeTiny},
  };
  for (const auto& s : kScenarios)
    if (name == s.name) return s;
  throw std::logic_error("scene: base scenario '" + name + "' is listed but has no set-up");
}

void SceneGenerator::Impl::placeDemo(const ObstaclePlacement& at, Rng& rt) { placeCollisionCourse(at, rt, 0.045, 6.0); }
void SceneGenerator::Impl::placeApproach(const ObstaclePlacement& at, Rng& rt) { placeCollisionCourse(at, rt, 0.035, 12.0); }

// The apparent size grows by `ratio` over the scene (at most to 90 % of the frame width).
void SceneGenerator::Impl::placeCollisionCourse(const ObstaclePlacement& at, Rng& rt, double span_frac, double ratio) {
  const double Wd = at.width, Hd = at.height, D = at.duration;
  const ObstacleClass c = at.mainClass(ObstacleClass::kFixedWing);
  const double span0 = span_frac * Wd * at.size_mult;
  ratio = std::max(1.5, std::min(ratio, 0.9 * Wd / std::max(span0, 1e-6)));
  const double T = D * ratio / (ratio - 1.0);
  // The focus of expansion: where the aircraft is headed in the image.
  const cv::Point2d focus(Wd * (0.5 + rt.uniform(-0.12, 0.12)),
                          flags.clutter ? at.horizon - 0.05 * Hd : Hd * (0.4 + rt.uniform(-0.06, 0.04)));
  const LineOfSight line = drawLineOfSight(rt, focus, Wd, Hd, 1.0 / ratio);
  addTrack(1, c, [=](double t) {
    TrackPose p;
    p.pose = poseOnLineOfSight(line, span0, T / (T - t), t);
    p.ttc = T - t;
    return p;
  });
  tracks.back().ttc0 = T;
}

// Flying away: the distance grows linearly, so the apparent size falls as s0 T / (T + t) to
// 1 / `kRecedeRatio` of its start over the scene, and the centre converges on the point the
// aircraft flies towards. Not closing: time to contact +inf.
void SceneGenerator::Impl::placeRecede(const ObstaclePlacement& at, Rng& rt) {
  constexpr double kRecedeRatio = 6.0;
  const double Wd = at.width, Hd = at.height, D = at.duration;
  const ObstacleClass c = at.mainClass(ObstacleClass::kFixedWing);
  // At most 0.55 of the frame width, so that with the focus and the offset (at most 0.21 of the
  // width from the centre) the whole aircraft is in view at the start (`large`).
  const double span0 = std::min(0.3 * Wd * at.size_mult, 0.55 * Wd);
  const double T = D / (kRecedeRatio - 1.0);
  // The focus of contraction: where the aircraft is headed in the image (in front of the raised
  // horizon under `clutter`, as for the approach).
  const cv::Point2d focus(Wd * (0.5 + rt.uniform(-0.12, 0.12)),
                          flags.clutter ? at.horizon - 0.05 * Hd : Hd * (0.4 + rt.uniform(-0.06, 0.04)));
  const LineOfSight line = drawLineOfSight(rt, focus, Wd, Hd, 1.0);
  addTrack(1, c, [=](double t) {
    TrackPose p;
    p.pose = poseOnLineOfSight(line, span0, T / (T + t), t);
    return p;
  });
}

void SceneGenerator::Impl::placeCrossing(const ObstaclePlacement& at, Rng& rt) {
  const double Wd = at.width, Hd = at.height, D = at.duration;
  const ObstacleClass c = at.mainClass(ObstacleClass::kFixedWing);
  const double span = 0.16 * Wd * at.size_mult;
  const bool ltr = rt.chance(0.5);
  const double x0 = ltr ? 0.12 * Wd : 0.88 * Wd, x1 = ltr ? 0.88 * Wd : 0.12 * Wd;
  const double v = (x1 - x0) / D;
  const double y0 = at.sky_y + rt.uniform(-0.08, 0.05) * Hd;
  const double ph = rt.uniform(0, 1);
  const float yaw = static_cast<float>((ltr ? 0.0 : kPi) + rt.uniform(-0.35, 0.35));
  const float elev = static_cast<float>(rt.uniform(-0.15, 0.05));
  addTrack(1, c, [=](double t) {
    TrackPose p;
    p.pose.centre = cv::Point2f(static_cast<float>(x0 + v * t), static_cast<float>(y0 + 0.04 * Hd * sinTurn(0.7 * t / D + ph)));
    p.pose.scale = static_cast<float>(span);
    p.pose.yaw = yaw;
    p.pose.elevation = elev;
    p.pose.bank = static_cast<float>(0.06 * sinTurn(0.3 * t + ph));
    p.pose.flap = flapAt(t, 3.0, ph);
    return p;
  });
  // The camera pans slowly after the obstacle.
  camera_parts.push_back([=](double t) { return cv::Point2d(0.3 * v * t, 0.0); });
}

void SceneGenerator::Impl::placeRotation(const ObstaclePlacement& at, Rng& rt) {
  const double Wd = at.width, Hd = at.height, D = at.duration, sky_y = at.sky_y;
  const ObstacleClass c = at.mainClass(ObstacleClass::kMultirotor);
  const double span = 0.16 * Wd * at.size_mult;
  const double ph = rt.uniform(0, 1), yaw0 = rt.uniform(0, 2 * kPi);
  addTrack(1, c, [=](double t) {
    TrackPose p;
    p.pose.centre = cv::Point2f(static_cast<float>(0.5 * Wd + 0.12 * Wd * sinTurn(t / D + ph)),
                                static_cast<float>(sky_y + 0.06 * Hd * sinTurn(2.0 * t / D + ph)));
    p.pose.scale = static_cast<float>(span);
    p.pose.yaw = static_cast<float>(yaw0 + 2.0 * kPi * t / 4.0);
    p.pose.roll = static_cast<float>(0.6 * sinTurn(t / 5.0));
    p.pose.elevation = static_cast<float>(-0.35 + 0.45 * sinTurn(t / 6.0 + ph));
    p.pose.bank = static_cast<float>(0.25 * sinTurn(t / 3.0));
    p.pose.flap = flapAt(t, 3.5, ph);
    return p;
  });
}

void SceneGenerator::Impl::placeOutOfView(const ObstaclePlacement& at, Rng& rt) {
  const double Wd = at.width, Hd = at.height, D = at.duration, sky_y = at.sky_y;
  const ObstacleClass c = at.mainClass(ObstacleClass::kMultirotor);
  const double span = 0.1 * Wd * at.size_mult;
  const double ph = rt.uniform(0, 1);
  const double dir = rt.chance(0.5) ? 1.0 : -1.0;
  addTrack(1, c, [=](double t) {
    TrackPose p;
    const double s = sinTurn(t / D);
    p.pose.centre = cv::Point2f(static_cast<float>(0.5 * Wd + dir * 0.72 * Wd * s),
                                static_cast<float>(sky_y + 0.05 * Hd * sinTurn(1.5 * t / D + ph)));
    p.pose.scale = static_cast<float>(span);
    p.pose.yaw = static_cast<float>(0.3 * dir);
    p.pose.elevation = -0.3f;
    p.pose.bank = static_cast<float>(0.25 * detCos(2.0 * kPi * t / D) * dir);
    p.pose.flap = flapAt(t, 3.5, ph);
    return p;
  });
}

// Three paths crossing near the frame centre at mid-sequence, at different distances.
void SceneGenerator::Impl::placeMulti(const ObstaclePlacement& at, Rng& rt) {
  const double Wd = at.width, Hd = at.height, D = at.duration, size_mult = at.size_mult;
  const double ph = rt.uniform(0, 1);
  const double yc = at.sky_y;
  addTrack(1, at.mainClass(ObstacleClass::kMultirotor), [=](double t) {
    TrackPose p;
    p.pose.centre = cv::Point2f(static_cast<float>(Wd * (0.1 + 0.8 * t / D)), static_cast<float>(yc + 0.04 * Hd * sinTurn(t / D + ph)));
    p.pose.scale = static_cast<float>(0.09 * Wd * size_mult);
    p.pose.yaw = 0.2f;
    p.pose.elevation = -0.3f;
    p.pose.bank = 0.15f;
    p.pose.flap = 0.3f;
    return p;
  });
  addTrack(2, ObstacleClass::kFixedWing, [=](double t) {
    TrackPose p;
    p.pose.centre = cv::Point2f(static_cast<float>(Wd * (0.92 - 0.84 * t / D)), static_cast<float>(yc - 0.05 * Hd + 0.05 * Hd * t / D));
    p.pose.scale = static_cast<float>(0.14 * Wd);
    p.pose.yaw = static_cast<float>(kPi - 0.25);
    p.pose.elevation = -0.08f;
    return p;
  });
  addTrack(3, ObstacleClass::kBird, [=](double t) {
    TrackPose p;
    p.pose.centre = cv::Point2f(static_cast<float>(Wd * (0.32 + 0.36 * t / D)), static_cast<float>(yc + Hd * (-0.3 + 0.6 * t / D)));
    p.pose.scale = static_cast<float>(0.06 * Wd);
    p.pose.yaw = 0.5f;
    p.pose.elevation = -0.2f;
    p.pose.flap = static_cast<float>(0.2 + 0.6 * sinTurn(3.8 * t));
    return p;
  });
}

void SceneGenerator::Impl::placeBird(const ObstaclePlacement& at, Rng& rt) {
  const double Wd = at.width, Hd = at.height, D = at.duration, sky_y = at.sky_y;
  const ObstacleClass c = at.mainClass(ObstacleClass::kBird);
  const double span = 0.08 * Wd * at.size_mult;
  const bool ltr = rt.chance(0.5);
  const double x0 = ltr ? 0.1 * Wd : 0.9 * Wd, x1 = ltr ? 0.9 * Wd : 0.1 * Wd;
  const double ph = rt.uniform(0, 1);
  const float yaw = static_cast<float>((ltr ? 0.0 : kPi) + rt.uniform(-0.4, 0.4));
  addTrack(1, c, [=](double t) {
    TrackPose p;
    p.pose.centre = cv::Point2f(static_cast<float>(x0 + (x1 - x0) * t / D), static_cast<float>(sky_y + 0.07 * Hd * sinTurn(0.5 * t + ph)));
    p.pose.scale = static_cast<float>(span);
    p.pose.yaw = yaw;
    p.pose.elevation = -0.25f;
    p.pose.bank = static_cast<float>(0.15 * sinTurn(0.4 * t + ph));
    p.pose.flap = flapAt(t, 3.6, ph);
    return p;
  });
}

void SceneGenerator::Impl::placeTiny(const ObstaclePlacement& at, Rng& rt) {
  const double Wd = at.width, Hd = at.height, D = at.duration;
  const ObstacleClass c = at.mainClass(ObstacleClass::kMultirotor);
  const double span = std::max(2.5, 0.014 * Wd * at.size_mult);
  const double ph = rt.uniform(0, 1);
  const double yb = at.horizon - 0.07 * Hd;
  addTrack(1, c, [=](double t) {
    TrackPose p;
    p.pose.centre = cv::Point2f(static_cast<float>(Wd * (0.3 + 0.4 * t / D)), static_cast<float>(yb + 0.035 * Hd * sinTurn(0.8 * t / D + ph)));
    p.pose.scale = static_cast<float>(span);
    p.pose.yaw = static_cast<float>(0.3 * sinTurn(0.1 * t));
    p.pose.elevation = -0.35f;
    p.pose.bank = 0.1f;
    p.pose.flap = flapAt(t, 3.5, ph);
    return p;
  });
}

}  // namespace scene
}  // namespace obstacle_tracker
