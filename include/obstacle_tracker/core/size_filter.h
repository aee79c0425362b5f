// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The size of a tracked obstacle and its expansion rate, with their uncertainty: an extended
// Kalman filter on l = ln s (s = sqrt(w h), px) and its rate v = dl/dt.
//
// Motion model: an object closing (or receding) at a constant speed along the line of sight has
// s(t) = s0 T / (T - t), so v = 1 / (T - t) and dv/dt = v^2 (Lee, Perception 1976: the expansion
// rate is the inverse of the time to contact). Over dt the prediction is exact for that motion:
//   v' = v / (1 - v dt),  l' = l - ln(1 - v dt),
// and a constant-size object (v = 0) stays constant. Deviations (acceleration, pose changes) are
// process noise on v (rate_noise^2 dt) and on l (kSizeNoise^2 dt).
//
// Measurements:
//   - expansion between the previous frame and this one (expansion_meter.h): ln s_k - ln s_{k-1}.
//     The state carries a copy of the previous l (stochastic cloning, Roumeliotis & Burdick, ICRA
//     2002), so this relative measurement is used as one, with its own variance;
//   - a size (the correlation filter's box): ln s_k.
// A measurement whose innovation is beyond kGate standard deviations is dropped as an outlier,
// once kGateAfter measurements were taken; kMaxGatedInARow outliers in a row make the rate
// unknown again (its variance grows by kInitialRateSigma^2) and the last one is taken.
// A step where v dt would reach kMaxRateTimesDt (contact inside the step) grows the size by that
// much and keeps the rate; a gap over kMaxGap keeps the size and forgets the rate. A state that
// is no longer finite ends the filter (initialized() false): the caller starts it again.
//
// time to contact = 1 / v when v > 0 (+inf otherwise); its standard deviation by first-order
// propagation, sigma_v / v^2.
#pragma once

#include <limits>

#include <Eigen/Core>

namespace obstacle_tracker {
namespace core {

class SizeFilter {
 public:
  static constexpr double kSizeNoise = 0.05;     // ln units / sqrt(s): pose changes, segmentation
  static constexpr double kInitialRateSigma = 2.0;  // 1/s: a time to contact of 0.5 s is plausible
  static constexpr double kMaxRateTimesDt = 0.5;    // v dt beyond this is contact within two frames
  static constexpr double kGate = 4.0;              // innovations beyond this many sigmas are dropped
  static constexpr int kGateAfter = 5;              // ... once this many measurements were taken
  static constexpr int kMaxGatedInARow = 3;         // this many in a row: the rate changed
  static constexpr double kMaxGap = 2.0;            // s: a longer gap forgets the rate

  explicit SizeFilter(double rate_noise = 0.3) : rate_noise_(rate_noise) {}

  void setRateNoise(double rate_noise) { rate_noise_ = rate_noise; }

  // Starts on a size (px, > 0) with standard deviation size_sigma in ln units; the rate is 0 +-
  // kInitialRateSigma.
  void reset(double stamp, double size, double size_sigma);
  bool initialized() const { return initialized_; }

  // Advances to `stamp` (s). The current l is copied into the clone first (the reference of
  // this frame's expansion measurement); a stamp not after the last one changes nothing else.
  void predict(double stamp);

  // ln(s now / s at the previous predict()) measured with standard deviation sigma. False when
  // the measurement was not used (gated, not finite, or the filter not initialised).
  bool updateExpansion(double log_ratio, double sigma);
  // ln s now measured with standard deviation sigma (size in px, > 0). False as above.
  bool updateSize(double size, double sigma);
  // A discontinuity (a box re-detected at another size): l and its copy restart at size with
  // standard deviation sigma, uncorrelated; the rate and its uncertainty are kept.
  void restartSize(double size, double sigma);

  double size() const;               // px
  double logSize() const { return x_(0); }
  double logSizeSigma() const;
  double expansionRate() const { return x_(1); }  // 1/s, positive when growing
  double expansionRateSigma() const;
  double timeToContact() const;      // s; +inf when not closing
  double timeToContactSigma() const; // s; +inf when not closing

 private:
  bool update(const Eigen::RowVector3d& h, double innovation, double variance);

  double rate_noise_;
  bool initialized_ = false;
  int accepted_ = 0;  // measurements taken since reset()
  int gated_ = 0;     // measurements gated in a row
  double stamp_ = 0.0;
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();  // l, v, l at the previous predict()
  Eigen::Matrix3d p_ = Eigen::Matrix3d::Zero();
};

}  // namespace core
}  // namespace obstacle_tracker
