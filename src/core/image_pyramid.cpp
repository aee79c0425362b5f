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

void binomialBlur(cv::Mat& img, cv::Mat& tmp) {
  tmp.create(img.size(), CV_32F);
  const int w = img.cols, h = img.rows;
  const auto tap = [](const float* p, int i, int n, int step) {
    const auto at = [&](int k) { return p[static_cast<std::ptrdiff_t>(std::min(std::max(k, 0), n - 1)) * step]; };
    return (at(i - 2) + 4.0f * at(i - 1) + 6.0f * at(i) + 4.0f * at(i + 1) + at(i + 2)) * (1.0f / 16.0f);
  };
  for (int y = 0; y < h; ++y) {  // rows: img -> tmp
    const float* src = img.ptr<float>(y);
    float* dst = tmp.ptr<float>(y);
    for (int x = 0; x < w; ++x) dst[x] = tap(src, x, w, 1);
  }
  const int step = static_cast<int>(tmp.step1());
  for (int x = 0; x < w; ++x) {  // columns: tmp -> img
    const float* src = tmp.ptr<float>(0) + x;
    for (int y = 0; y < h; ++y) img.ptr<float>(y)[x] = tap(src, y, h, step);
  }
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
