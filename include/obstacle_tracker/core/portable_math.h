// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Element-wise float operations whose results do not depend on the CPU. OpenCV picks SSE, AVX2 or
// AVX-512 kernels at run time, and some of the ones the correlation filter used round differently
// between them: cv::addWeighted (the model's running average, eq. 4.3 of Bolme et al. 2010) and
// cv::Mat::dot (the features' energy ||z||^2, whose summation order follows the vector width).
// The loop's decisions (peak thresholds, the best scale) then flip on tiny differences, and the
// same clip tracked differently on two machines. These loops round every operation the same way
// on any machine (built with -ffp-contract=off). cv::exp (the Gaussian kernel, Henriques et al.
// 2015 eq. 31) also differs in its last bit between dispatch paths, and the C library's exp picks
// an FMA variant on the CPUs that have it: expInPlace is ours for that reason.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

// model = (1 - eta) * model + eta * update, element-wise, CV_32F of any channel count.
inline void blendInPlace(cv::Mat& model, const cv::Mat& update, float eta) {
  CV_Assert(model.depth() == CV_32F && model.type() == update.type() && model.size() == update.size());
  const float keep = 1.0f - eta;
  for (int r = 0; r < model.rows; ++r) {
    float* m = model.ptr<float>(r);
    const float* u = update.ptr<float>(r);
    const int n = model.cols * model.channels();
    for (int i = 0; i < n; ++i) m[i] = keep * m[i] + eta * u[i];
  }
}

// Sum of m's squared elements, CV_32F, accumulated in double in memory order.
inline double sumOfSquares(const cv::Mat& m) {
  CV_Assert(m.depth() == CV_32F);
  double sum = 0.0;
  for (int r = 0; r < m.rows; ++r) {
    const float* p = m.ptr<float>(r);
    const int n = m.cols * m.channels();
    for (int i = 0; i < n; ++i) sum += static_cast<double>(p[i]) * static_cast<double>(p[i]);
  }
  return sum;
}

// v[i] = e^v[i] for n floats, the same on every machine: in double, x = k ln 2 + r with
// |r| <= ln 2 / 2 (Cody & Waite's two-part ln 2), e^r by its Taylor series to r^11 (relative error
// about 1e-14, far under a float's half ulp of 6e-8), then times 2^k built from its bits. On
// [-87.3, 88] that is e^x correctly rounded to float (every float there checked against the double
// exp rounded); below, the result is subnormal or 0 (from about -87.7), still the same on every
// machine. Inputs are clamped to [-100, 88]; NaN stays NaN. About 10x the time of cv::exp's
// vector code: a few tens of microseconds per frame for the kernels of a 40 x 40-cell window.
inline void expInPlace(float* v, int n) {
  constexpr double kLog2e = 1.4426950408889634;
  constexpr double kLn2Hi = 0.6931471805598903, kLn2Lo = 5.497923018708371e-14;
  constexpr double kRound = 6755399441055744.0;  // 1.5 x 2^52: adding it rounds to an integer
  for (int i = 0; i < n; ++i) {
    double x = v[i];
    if (x != x) continue;  // NaN: left as it is (converting it to int below would be undefined)
    x = x < -100.0 ? -100.0 : (x > 88.0 ? 88.0 : x);
    const double k = (x * kLog2e + kRound) - kRound;
    const double r = (x - k * kLn2Hi) - k * kLn2Lo;
    double p = 1.0 / 39916800.0;  // 1 / 11!
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    const int biased = static_cast<int>(k) + 127;  // 2^k as a float's exponent field
    const std::int32_t bits = (biased > 0 ? biased : 0) << 23;
    float two_to_k;
    std::memcpy(&two_to_k, &bits, sizeof two_to_k);
    v[i] = static_cast<float>(p) * two_to_k;  // exact unless the result is subnormal
  }
}

}  // namespace core
}  // namespace obstacle_tracker
