// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Element-wise float operations whose results do not depend on the CPU. OpenCV picks SSE, AVX2 or
// AVX-512 kernels at run time, and some of the ones the correlation filter used round differently
// between them: cv::addWeighted (the model's running average, eq. 4.3 of Bolme et al. 2010) and
// cv::Mat::dot (the features' energy ||z||^2, whose summation order follows the vector width).
// The loop's decisions (peak thresholds, the best scale) then flip on tiny differences, and the
// same clip tracked differently on two machines. These loops round every operation the same way
// on any machine (built with -ffp-contract=off). cv::exp (the Gaussian kernel, Henriques et al.
// 2015 eq. 31) also differs in its last bit between dispatch paths and is kept:
// docs/portability.md says why.
#pragma once

#include <cmath>

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

}  // namespace core
}  // namespace obstacle_tracker
