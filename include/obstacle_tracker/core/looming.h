// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Looming of a track: its expansion rate and time to contact, with their uncertainty.
//
// s = sqrt(w h) of the obstacle's image. An object closing at a constant speed has
// s(t) = s0 T / (T - t) and d ln s / dt = 1 / (T - t): the expansion rate is the inverse of the
// time left before contact (Lee, Perception 1976). A SizeFilter (size_filter.h, an extended
// Kalman filter on ln s and its rate under that motion model) is fed, per tracked frame, the
// object's expansion since the previous frame measured from its own pixels (expansion_meter.h).
// The correlation filter's box size is used only on frames without that measurement (a target
// too small or too smooth, or an outlier): its scale search moves in steps of scale_step with a
// preference for no change and lags growth, so its sizes would pull the rate down. A
// re-detection restarts the size at the re-detected box and keeps the rate (a re-sized box is
// not an expansion).
//
// The reported box stays the correlation filter's: the pixel expansions are good for the rate
// over a few frames, but their small per-frame errors add up over hundreds of frames, and a
// box driven by them drifts (docs/looming.md).
#pragma once

#include <array>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/expansion_meter.h"
#include "obstacle_tracker/core/size_filter.h"

namespace obstacle_tracker {
namespace core {

class LoomingEstimator {
 public:
  static constexpr double kStartSigma = 0.05;   // ln units: a given, detected or re-detected box
  static constexpr double kBoxSizeSigma = 0.05;  // ln units: the scale search's step (5 %)

  // rate_noise: Params::looming_rate_noise; use_pixels: Params::looming_from_pixels.
  void setParams(double rate_noise, bool use_pixels);

  // A new track on box at stamp (s).
  void start(const cv::Mat& frame, double stamp, const cv::Rect2f& box);
  // A frame the correlation filter tracked: its box.
  void track(const cv::Mat& frame, double stamp, const cv::Rect2f& box);
  // A re-detection restarted the filter on box (the object may have moved far or been hidden:
  // no expansion is measured across the gap; the size restarts, the rate is kept).
  void restart(const cv::Mat& frame, double stamp, const cv::Rect2f& box);

  // The size trend over the last kTrendFrames tracked frames, from the object's own pixels: +1
  // when the measured expansions add up to more than kTrendLogSize, -1 below minus that, 0
  // otherwise or when fewer than half of those frames were measured. What
  // KcfTracker::setSizeTrend takes. A sum over frames, not the filter's rate against its standard
  // deviation: the rate's uncertainty is held up by its process noise (about 0.27/s at the
  // default), so a slow approach (0.2/s, 0.06 in 10 frames at 30 Hz) never counted as growth.
  // The threshold is about 1.5 scale steps of 5 %: the pixel expansions share part of the scale
  // search's bias (both see the background moving inside the box), and on the flying clips a
  // lower one let through more of the steps the confirmation holds back (docs/measurements.md).
  // The sum must also stand out of the expansions' own scatter: their mean at least
  // kTrendStandardErrors standard errors from zero (a one-sample t test). A target of 10-15 px
  // gives expansions that scatter by 2-3 % a frame around no change, and sums of ten of them pass
  // the threshold on a quarter of the frames; a real change is steady from frame to frame.
  int sizeTrend() const;
  static constexpr int kTrendFrames = 10;
  static constexpr double kTrendLogSize = 0.075;  // ln units
  static constexpr double kTrendStandardErrors = 2.0;
  double expansionRate() const { return filter_.expansionRate(); }           // 1/s
  double expansionRateSigma() const { return filter_.expansionRateSigma(); } // 1/s
  double timeToContact() const { return filter_.timeToContact(); }           // s, +inf if not closing
  double timeToContactSigma() const { return filter_.timeToContactSigma(); } // s, +inf if not closing

 private:
  void recordExpansion(const ExpansionMeasurement& m);

  bool use_pixels_ = true;
  std::array<double, kTrendFrames> recent_{};  // the last frames' ln expansions (NaN: not measured)
  int recent_count_ = 0;                       // frames recorded since the track (re)started
  SizeFilter filter_;
  ExpansionMeter meter_;
};

}  // namespace core
}  // namespace obstacle_tracker
