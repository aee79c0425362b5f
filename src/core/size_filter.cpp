// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/size_filter.h"

#include <cmath>

#include <Eigen/Dense>

namespace obstacle_tracker {
namespace core {

void SizeFilter::reset(double stamp, double size, double size_sigma) {
  initialized_ = false;
  if (!std::isfinite(stamp) || !(size > 0.0) || !std::isfinite(size) || !(size_sigma > 0.0) ||
      !std::isfinite(size_sigma)) {
    return;
  }
  const double l = std::log(size);
  x_ << l, 0.0, l;
  p_.setZero();
  p_(0, 0) = p_(2, 2) = p_(0, 2) = p_(2, 0) = size_sigma * size_sigma;
  p_(1, 1) = kInitialRateSigma * kInitialRateSigma;
  stamp_ = stamp;
  accepted_ = 0;
  gated_ = 0;
  initialized_ = true;
}

void SizeFilter::predict(double stamp) {
  if (!initialized_) return;
  // Clone first: the relative measurement of this frame is against the l of the last frame.
  x_(2) = x_(0);
  p_.row(2) = p_.row(0);
  p_.col(2) = p_.col(0);
  const double dt = stamp - stamp_;
  if (!(dt > 0.0) || !std::isfinite(dt)) return;  // the same stamp again, or one from the past
  stamp_ = stamp;
  if (dt > kMaxGap) {
    // A gap the motion model cannot bridge: the size stays, the rate is unknown again.
    x_(1) = 0.0;
    p_.row(1).setZero();
    p_.col(1).setZero();
    p_(1, 1) = kInitialRateSigma * kInitialRateSigma;
    p_(0, 0) += kSizeNoise * kSizeNoise * kMaxGap;
    return;
  }
  const double v = x_(1);
  Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
  if (v * dt < kMaxRateTimesDt) {
    // Exact for a constant closing speed: v' = v / (1 - v dt), l' = l - ln(1 - v dt).
    const double k = 1.0 / (1.0 - v * dt);
    f(0, 1) = dt * k;  // d l' / d v
    f(1, 1) = k * k;   // d v' / d v
    x_(0) -= std::log(1.0 - v * dt);
    x_(1) = v * k;
  } else {
    // Contact would fall inside this step: the size grows by the factor that v dt =
    // kMaxRateTimesDt gives and the rate stays (extrapolating it further would run away).
    f(1, 1) = 1.0;
    x_(0) -= std::log(1.0 - kMaxRateTimesDt);
  }
  p_ = f * p_ * f.transpose();
  p_(0, 0) += kSizeNoise * kSizeNoise * dt;
  p_(1, 1) += rate_noise_ * rate_noise_ * dt;
  if (!x_.allFinite() || !p_.allFinite()) initialized_ = false;  // the caller starts again
}

bool SizeFilter::update(const Eigen::RowVector3d& h, double innovation, double variance) {
  if (!initialized_ || !std::isfinite(innovation) || !(variance > 0.0) || !std::isfinite(variance)) return false;
  Eigen::Vector3d ph = p_ * h.transpose();
  double s = h.dot(ph) + variance;
  // Innovation gate: a measurement kGate standard deviations from the prediction is an outlier
  // (an occluder aligned instead of the object), not evidence; but not before the rate has
  // been measured a few times (a track may start on an obstacle already closing fast), and
  // several outliers in a row say the rate changed: it is taken as unknown again.
  if (accepted_ >= kGateAfter && innovation * innovation > kGate * kGate * s) {
    if (++gated_ < kMaxGatedInARow) return false;
    p_(1, 1) += kInitialRateSigma * kInitialRateSigma;
    ph = p_ * h.transpose();
    s = h.dot(ph) + variance;
  }
  gated_ = 0;
  ++accepted_;
  const Eigen::Vector3d gain = ph / s;
  x_ += gain * innovation;
  // Joseph form: stays symmetric and positive through many small updates.
  const Eigen::Matrix3d ikh = Eigen::Matrix3d::Identity() - gain * h;
  p_ = ikh * p_ * ikh.transpose() + gain * variance * gain.transpose();
  if (!x_.allFinite() || !p_.allFinite()) initialized_ = false;
  return true;
}

bool SizeFilter::updateExpansion(double log_ratio, double sigma) {
  const Eigen::RowVector3d h(1.0, 0.0, -1.0);
  return update(h, log_ratio - (x_(0) - x_(2)), sigma * sigma);
}

bool SizeFilter::updateSize(double size, double sigma) {
  if (!(size > 0.0)) return false;
  const Eigen::RowVector3d h(1.0, 0.0, 0.0);
  return update(h, std::log(size) - x_(0), sigma * sigma);
}

void SizeFilter::restartSize(double size, double sigma) {
  if (!initialized_ || !(size > 0.0) || !std::isfinite(size) || !(sigma > 0.0)) return;
  const double l = std::log(size);
  const double var_v = p_(1, 1);
  x_(0) = x_(2) = l;
  p_.setZero();
  p_(0, 0) = p_(2, 2) = p_(0, 2) = p_(2, 0) = sigma * sigma;
  p_(1, 1) = var_v;
}

double SizeFilter::size() const { return std::exp(x_(0)); }

double SizeFilter::logSizeSigma() const { return std::sqrt(p_(0, 0)); }

double SizeFilter::expansionRateSigma() const { return std::sqrt(p_(1, 1)); }

double SizeFilter::timeToContact() const {
  return x_(1) > 0.0 ? 1.0 / x_(1) : std::numeric_limits<double>::infinity();
}

double SizeFilter::timeToContactSigma() const {
  return x_(1) > 0.0 ? expansionRateSigma() / (x_(1) * x_(1)) : std::numeric_limits<double>::infinity();
}

}  // namespace core
}  // namespace obstacle_tracker
