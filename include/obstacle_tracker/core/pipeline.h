// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The closed detection-tracking loop (Bharati et al., T-IV 2018, plus several obstacles and
// looming): searching -> tracking -> re-detecting -> lost -> searching.
//
// The nodelet and the tools use this class only through the members below.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/types.h"

namespace obstacle_tracker {
namespace core {

class Pipeline {
 public:
  explicit Pipeline(const Params& params = Params());
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  // Applies from the next process() call. Values are validated (clamped) first.
  void setParams(const Params& params);
  const Params& params() const;

  // One call per frame. frame: CV_8UC1 (grey/thermal) or CV_8UC3 (BGR); stamp in seconds,
  // increasing. Returns the obstacles in this frame, best first (empty when nothing is there:
  // never a stale box). Throws std::invalid_argument for an empty frame or another type.
  // A stamp that goes backwards resets the tracks.
  const std::vector<Obstacle>& process(const cv::Mat& frame, double stamp);

  // Starts a track on a given box (e.g. --init gt) instead of waiting for auto-initialisation;
  // the frame is processed as the track's first frame. Returns the obstacles of this frame.
  const std::vector<Obstacle>& startTrack(const cv::Mat& frame, double stamp, const cv::Rect2f& box);

  // Forgets every track; the next frame starts searching.
  void reset();

  // Runs the pipeline once over a few synthetic frames of this size and type (CV_8UC1 or
  // CV_8UC3), then forgets them: buffers, OpenCV's lazily built tables and threads exist before
  // the first real frame, whose processing time is then that of any other. Tracks, ids and
  // results afterwards are those of a pipeline that was never prepared. A size with a side below
  // 16 px is not worth warming up (nothing happens); another type throws std::invalid_argument.
  void prepare(cv::Size size, int type);

  // State of the main (first) track, kSearching when there is none.
  TrackState state() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace core
}  // namespace obstacle_tracker
