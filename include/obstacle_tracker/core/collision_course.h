// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Collision course, the pilot's rule: an object whose bearing stays constant while its range
// decreases is on a collision course (constant bearing, decreasing range). Per track, the
// bearing's angular rate is |angle between successive bearings| / dt, smoothed over
// kRateTimeConstant; the track is on a collision course once it has kMinHistory of bearings, that
// rate is below the threshold (Params::collision_bearing_rate) and it is closing beyond doubt
// (expansion rate above kClosingSigmas of its standard deviation, looming.h).
//
// Bearings are unit vectors in one frame for all tracks (the nodelet's target_frame): in a
// frame fixed to the world (or to the vehicle's body, turned with it by tf), the camera's own
// rotation is taken out by the transform; in the camera's frame it is not.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

class CollisionCourse {
 public:
  static constexpr double kRateTimeConstant = 0.5;  // s: smoothing of the angular rate
  static constexpr double kMinHistory = 0.3;        // s of bearings before a track can be flagged
  static constexpr double kClosingSigmas = 2.0;     // expansion rate > this x its sigma: closing

  // One track of one frame: inputs, then the two outputs update() fills in.
  struct Track {
    int id = -1;
    bool has_bearing = false;
    cv::Vec3d bearing;               // unit vector (any length > 0 is normalised)
    double expansion_rate = 0.0;     // 1/s
    double expansion_rate_sigma = 0.0;
    double bearing_rate = 0.0;       // out: rad/s, smoothed; 0 until two bearings were seen
    bool collision_course = false;   // out
  };

  // rad/s: a closing track whose bearing turns slower than this is on a collision course.
  void setMaxBearingRate(double rad_per_s) { max_rate_ = rad_per_s; }

  // The tracks of the frame at `stamp` (s). A track without a bearing, or missing from the list,
  // starts again when it next has one; a stamp not after the previous frame's forgets every track.
  void update(double stamp, std::vector<Track>& tracks);

  void reset() { states_.clear(); }

 private:
  struct State {
    int id = -1;
    cv::Vec3d bearing;
    double stamp = 0.0;
    double since = 0.0;  // stamp of the track's first bearing
    double rate = 0.0;
    bool have_rate = false;
  };
  const State* find(int id) const;

  double max_rate_ = 0.05;
  double last_stamp_ = 0.0;
  bool have_stamp_ = false;
  std::vector<State> states_, next_;
};

}  // namespace core
}  // namespace obstacle_tracker
