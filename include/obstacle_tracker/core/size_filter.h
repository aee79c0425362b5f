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
//   - expansion between the previous frame and this one (expansion_flow.h): ln s_k - ln s_{k-1}.
//     The state carries a copy of the previous l (stochastic cloning, Roumeliotis & Burdick, ICRA
//     2002), so this relative measurement is used as one, with its own variance;
//   - a size (the correlation filter's box): ln s_k.
// A measurement whose innovation is beyond kGate standard deviations is dropped as an outlier.
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
  static constexpr double kInitialRateSigma = 0.5;  // 1/s: a time to contact of 2 s is plausible
  static constexpr double kMaxRateTimesDt = 0.5;    // v dt beyond this is contact within two frames
  static constexpr double kGate = 4.0;              // innovations beyond this many sigmas are dropped

  explicit SizeFilter(double rate_noise = 0.3) : rate_noise_(rate_noise) {}

  void setRateNoise(double rate_noise) { rate_noise_ = rate_noise; }

  // Starts on a size (px, > 0) with standard deviation size_sigma in ln units; the rate is 0 +-
  // kInitialRateSigma.
  void reset(double stamp, double size, double size_sigma);
  bool initialized() const { return initialized_; }

  // Advances to `stamp` (s); a stamp not after the last one changes nothing. The previous l is
  // copied into the clone first.
  void predict(double stamp);

  // ln(s now / s at the previous predict()) measured with standard deviation sigma.
  void updateExpansion(double log_ratio, double sigma);
  // ln s now measured with standard deviation sigma (size in px, > 0).
  void updateSize(double size, double sigma);
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
  void update(const Eigen::RowVector3d& h, double innovation, double variance);

  double rate_noise_;
  bool initialized_ = false;
  double stamp_ = 0.0;
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();  // l, v, l at the previous predict()
  Eigen::Matrix3d p_ = Eigen::Matrix3d::Zero();
};

}  // namespace core
}  // namespace obstacle_tracker
