// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Small float-image helpers of the patch aligner (scale_alignment.h): binomial smoothing,
// 2x2-mean halving, central-difference gradients and bilinear sampling. Written out because the
// OpenCV equivalents (cv::GaussianBlur, cv::pyrDown, cv::Sobel) allocate per call and round differently per CPU
// (the aligners run every frame and must give the same numbers everywhere: docs/portability.md).
#pragma once

#include <cmath>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

// dst (CV_32F, half the size, rounded down) = means of 2x2 blocks of src (CV_32F). A pixel (x, y)
// of dst is centred on src's (2x + 0.5, 2y + 0.5).
void halveImage(const cv::Mat& src, cv::Mat& dst);

// In place: img (CV_32F) smoothed by the 5-tap binomial kernel [1 4 6 4 1] / 16 along rows and
// columns (a Gaussian of sigma 1 px; edge pixels replicated); tmp is a buffer of img's size.
void binomialBlur(cv::Mat& img, cv::Mat& tmp);

// Central differences of img (CV_32F), one-sided at the border.
void centralGradients(const cv::Mat& img, cv::Mat& grad_x, cv::Mat& grad_y);

// Bilinear value of a CV_32F image at (x, y); the caller keeps 0 <= x < cols - 1, 0 <= y < rows - 1.
inline float bilinearAt(const cv::Mat& m, float x, float y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const float a = x - static_cast<float>(x0), b = y - static_cast<float>(y0);
  const float* r0 = m.ptr<float>(y0) + x0;
  const float* r1 = m.ptr<float>(y0 + 1) + x0;
  const float top = r0[0] + a * (r0[1] - r0[0]);
  const float bot = r1[0] + a * (r1[1] - r1[0]);
  return top + b * (bot - top);
}

// Whether bilinearAt may read (x, y) of m.
inline bool bilinearInside(const cv::Mat& m, float x, float y) {
  return x >= 0.0f && y >= 0.0f && x < static_cast<float>(m.cols - 1) && y < static_cast<float>(m.rows - 1);
}

}  // namespace core
}  // namespace obstacle_tracker
