// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The usual interval between the frames a tracker is given, from their stamps: the median of the
// last kWindow positive intervals. Frames dropped upstream (a camera driver or a nodelet queue
// behind a busy tracker) show as intervals of several usual ones; the median ignores them while
// fewer than half of the recent intervals are such gaps. Fixed storage: add() never allocates.
#pragma once

#include <array>

namespace obstacle_tracker {
namespace core {

class FrameInterval {
 public:
  static constexpr int kWindow = 16;

  // One frame's stamp (seconds). A stamp that goes backwards starts over (as the pipeline does).
  void add(double stamp);
  void reset();

  // The usual interval (s); 0 until two frames were seen.
  double usual() const { return usual_; }
  // The interval before the last frame (s); 0 for the first frame.
  double last() const { return last_; }
  // Time beyond the usual interval before the last frame (s): what the frames dropped just
  // before it lasted. 0 when the last interval was within half a usual interval of the usual.
  double dropped() const;

 private:
  std::array<double, kWindow> intervals_{};
  int next_ = 0;   // ring position of the next interval
  int count_ = 0;  // intervals kept, at most kWindow
  bool have_stamp_ = false;
  double stamp_ = 0.0, last_ = 0.0, usual_ = 0.0;
};

}  // namespace core
}  // namespace obstacle_tracker
