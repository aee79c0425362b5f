// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/size_filter.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace obstacle_tracker {
namespace core {

void SizeFilter::reset(double stamp, double size, double size_sigma) {
  const double l = std::log(std::max(size, 1e-6));
  x_ << l, 0.0, l;
  p_.setZero();
  p_(0, 0) = p_(2, 2) = p_(0, 2) = p_(2, 0) = size_sigma * size_sigma;
  p_(1, 1) = kInitialRateSigma * kInitialRateSigma;
  stamp_ = stamp;
  initialized_ = true;
}

void SizeFilter::predict(double stamp) {
  if (!initialized_) return;
  // Clone first: the relative measurement of this frame is against the l of the last frame.
  x_(2) = x_(0);
  p_.row(2) = p_.row(0);
  p_.col(2) = p_.col(0);
  const double dt = stamp - stamp_;
  if (!(dt > 0.0) || !std::isfinite(dt)) return;
  stamp_ = stamp;
  // v dt is kept below kMaxRateTimesDt: the model's contact time must not fall inside the step.
  const double v = x_(1);
  const double vdt = std::min(v * dt, kMaxRateTimesDt);
  const double k = 1.0 / (1.0 - vdt);
  Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
  f(0, 1) = dt * k;      // d l' / d v
  f(1, 1) = k * k;       // d v' / d v
  x_(0) -= std::log(1.0 - vdt);
  x_(1) = v * k;
  p_ = f * p_ * f.transpose();
  p_(0, 0) += kSizeNoise * kSizeNoise * dt;
  p_(1, 1) += rate_noise_ * rate_noise_ * dt;
}

void SizeFilter::update(const Eigen::RowVector3d& h, double innovation, double variance) {
  if (!initialized_ || !std::isfinite(innovation) || !(variance > 0.0) || !std::isfinite(variance)) return;
  const Eigen::Vector3d ph = p_ * h.transpose();
  const double s = h.dot(ph) + variance;
  // Innovation gate: a measurement kGate standard deviations from the prediction is an outlier
  // (an occluder aligned instead of the object), not evidence.
  if (innovation * innovation > kGate * kGate * s) return;
  const Eigen::Vector3d gain = ph / s;
  x_ += gain * innovation;
  // Joseph form: stays symmetric and positive through many small updates.
  const Eigen::Matrix3d ikh = Eigen::Matrix3d::Identity() - gain * h;
  p_ = ikh * p_ * ikh.transpose() + gain * variance * gain.transpose();
}

void SizeFilter::updateExpansion(double log_ratio, double sigma) {
  const Eigen::RowVector3d h(1.0, 0.0, -1.0);
  update(h, log_ratio - (x_(0) - x_(2)), sigma * sigma);
}

void SizeFilter::updateSize(double size, double sigma) {
  if (!(size > 0.0)) return;
  const Eigen::RowVector3d h(1.0, 0.0, 0.0);
  update(h, std::log(size) - x_(0), sigma * sigma);
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

double SizeFilter::logSizeSigma() const { return std::sqrt(std::max(0.0, p_(0, 0))); }

double SizeFilter::expansionRateSigma() const { return std::sqrt(std::max(0.0, p_(1, 1))); }

double SizeFilter::timeToContact() const {
  return x_(1) > 0.0 ? 1.0 / x_(1) : std::numeric_limits<double>::infinity();
}

double SizeFilter::timeToContactSigma() const {
  return x_(1) > 0.0 ? expansionRateSigma() / (x_(1) * x_(1)) : std::numeric_limits<double>::infinity();
}

}  // namespace core
}  // namespace obstacle_tracker
