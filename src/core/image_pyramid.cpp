// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/image_pyramid.h"

#include <algorithm>
#include <cstddef>

namespace obstacle_tracker {
namespace core {

void halveImage(const cv::Mat& src, cv::Mat& dst) {
  dst.create(src.rows / 2, src.cols / 2, CV_32F);
  for (int y = 0; y < dst.rows; ++y) {
    const float* a = src.ptr<float>(2 * y);
    const float* b = src.ptr<float>(2 * y + 1);
    float* o = dst.ptr<float>(y);
    for (int x = 0; x < dst.cols; ++x) o[x] = 0.25f * (a[2 * x] + a[2 * x + 1] + b[2 * x] + b[2 * x + 1]);
  }
}

namespace {

// One 5-tap binomial pass along a line of n values `step` apart: src -> dst (edges replicated).
void binomialLine(const float* src, float* dst, int n, std::ptrdiff_t src_step, std::ptrdiff_t dst_step) {
  const auto at = [&](int k) { return src[std::min(std::max(k, 0), n - 1) * src_step]; };
  const auto tap = [](float a, float b, float c, float d, float e) {
    return (a + 4.0f * b + 6.0f * c + 4.0f * d + e) * (1.0f / 16.0f);
  };
  for (int i = 0; i < n; ++i) {
    if (i >= 2 && i < n - 2) {  // interior: no clamping
      const float* p = src + (i - 2) * src_step;
      dst[i * dst_step] = tap(p[0], p[src_step], p[2 * src_step], p[3 * src_step], p[4 * src_step]);
    } else {
      dst[i * dst_step] = tap(at(i - 2), at(i - 1), at(i), at(i + 1), at(i + 2));
    }
  }
}

}  // namespace

void binomialBlur(cv::Mat& img, cv::Mat& tmp) {
  tmp.create(img.size(), CV_32F);
  for (int y = 0; y < img.rows; ++y) binomialLine(img.ptr<float>(y), tmp.ptr<float>(y), img.cols, 1, 1);
  const std::ptrdiff_t src_step = static_cast<std::ptrdiff_t>(tmp.step1());
  const std::ptrdiff_t dst_step = static_cast<std::ptrdiff_t>(img.step1());
  for (int x = 0; x < img.cols; ++x) binomialLine(tmp.ptr<float>(0) + x, img.ptr<float>(0) + x, img.rows, src_step, dst_step);
}

void centralGradients(const cv::Mat& img, cv::Mat& grad_x, cv::Mat& grad_y) {
  grad_x.create(img.size(), CV_32F);
  grad_y.create(img.size(), CV_32F);
  for (int y = 0; y < img.rows; ++y) {
    const float* up = img.ptr<float>(std::max(0, y - 1));
    const float* row = img.ptr<float>(y);
    const float* down = img.ptr<float>(std::min(img.rows - 1, y + 1));
    float* gx = grad_x.ptr<float>(y);
    float* gy = grad_y.ptr<float>(y);
    for (int x = 0; x < img.cols; ++x) {
      gx[x] = 0.5f * (row[std::min(img.cols - 1, x + 1)] - row[std::max(0, x - 1)]);
      gy[x] = 0.5f * (down[x] - up[x]);
    }
  }
}

}  // namespace core
}  // namespace obstacle_tracker
