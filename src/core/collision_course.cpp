// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/collision_course.h"

#include <cmath>
#include <utility>

namespace obstacle_tracker {
namespace core {

const CollisionCourse::State* CollisionCourse::find(int id) const {
  for (const auto& s : states_) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

void CollisionCourse::update(double stamp, std::vector<Track>& tracks) {
  const bool usable_stamp = std::isfinite(stamp);
  if (!usable_stamp || (have_stamp_ && stamp < last_stamp_)) states_.clear();  // time went back
  next_.clear();
  for (Track& t : tracks) {
    t.bearing_rate = 0.0;
    t.collision_course = false;
    const double norm = cv::norm(t.bearing);
    if (!usable_stamp || !t.has_bearing || !(norm > 0.0) || !std::isfinite(norm)) continue;
    State s;
    s.id = t.id;
    s.bearing = t.bearing / norm;
    s.stamp = stamp;
    s.since = stamp;
    if (const State* prev = find(t.id)) {
      s.since = prev->since;
      s.rate = prev->rate;
      s.have_rate = prev->have_rate;
      const double dt = stamp - prev->stamp;
      if (dt > 0.0) {  // the same stamp again (a frame delivered twice) adds no rate
        // The angle between unit vectors from the cross and dot products: exact also for tiny
        // angles, where acos of a dot product near 1 is not.
        const double angle = std::atan2(cv::norm(prev->bearing.cross(s.bearing)), prev->bearing.dot(s.bearing));
        const double a = 1.0 - std::exp(-dt / kRateTimeConstant);
        s.rate = s.have_rate ? s.rate + a * (angle / dt - s.rate) : angle / dt;
        s.have_rate = true;
      } else {
        s.bearing = prev->bearing;
        s.stamp = prev->stamp;
      }
    }
    if (s.have_rate) {
      t.bearing_rate = s.rate;
      const bool closing = t.expansion_rate > 0.0 && t.expansion_rate > kClosingSigmas * t.expansion_rate_sigma;
      t.collision_course = closing && stamp - s.since >= kMinHistory && s.rate < max_rate_;
    }
    next_.push_back(s);
  }
  std::swap(states_, next_);
  if (usable_stamp) {
    last_stamp_ = stamp;
    have_stamp_ = true;
  }
}

}  // namespace core
}  // namespace obstacle_tracker
