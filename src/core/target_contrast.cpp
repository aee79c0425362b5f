// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// TargetContrast (target_contrast.h): the object's contrast against the robust statistics of a
// ring around its box, the same statistics ExtentGrower (extent.cpp) grows an object on.
#include "obstacle_tracker/core/target_contrast.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "obstacle_tracker/core/grey_histogram.h"

namespace obstacle_tracker {
namespace core {

namespace {

constexpr double kMadToSigma = 1.4826;
constexpr int kMinRingPixels = 16;

}  // namespace

float TargetContrast::measure(const cv::Mat& frame, const cv::Rect2f& box) const {
  if (frame.empty() || (frame.type() != CV_8UC1 && frame.type() != CV_8UC3)) return 0.0f;
  if (!std::isfinite(box.x) || !std::isfinite(box.y) || !std::isfinite(box.width) ||
      !std::isfinite(box.height) || box.width < 1.0f || box.height < 1.0f) {
    return 0.0f;
  }
  const float fw = static_cast<float>(frame.cols), fh = static_cast<float>(frame.rows);
  auto clampX = [&](float v) { return static_cast<int>(std::min(std::max(v, 0.0f), fw)); };
  auto clampY = [&](float v) { return static_cast<int>(std::min(std::max(v, 0.0f), fh)); };
  const float margin = std::max(kMinMargin, 0.5f * std::max(box.width, box.height));
  const int wx0 = clampX(std::floor(box.x - margin)), wy0 = clampY(std::floor(box.y - margin));
  const int wx1 = clampX(std::ceil(box.x + box.width + margin));
  const int wy1 = clampY(std::ceil(box.y + box.height + margin));
  const int bx0 = clampX(std::round(box.x)), by0 = clampY(std::round(box.y));
  const int bx1 = clampX(std::round(box.x + box.width)), by1 = clampY(std::round(box.y + box.height));
  if (bx1 <= bx0 || by1 <= by0) return 0.0f;
  const int channels = frame.channels();
  const int step = std::max(1, (std::max(wx1 - wx0, wy1 - wy0) + kMaxSamples - 1) / kMaxSamples);
  auto inBox = [&](int x, int y) { return x >= bx0 && x < bx1 && y >= by0 && y < by1; };

  std::array<GreyHistogram, 3> hist{};
  int ring_count = 0;
  for (int y = wy0; y < wy1; y += step) {
    const uchar* row = frame.ptr<uchar>(y);
    for (int x = wx0; x < wx1; x += step) {
      if (inBox(x, y)) {
        while (x + step < bx1) x += step;  // jump over the box
        continue;
      }
      for (int ch = 0; ch < channels; ++ch) ++hist[static_cast<std::size_t>(ch)][row[x * channels + ch]];
      ++ring_count;
    }
  }
  if (ring_count < kMinRingPixels) return 0.0f;
  std::array<int, 3> bg{0, 0, 0};
  for (int ch = 0; ch < channels; ++ch) {
    bg[static_cast<std::size_t>(ch)] = histogramQuantile(hist[static_cast<std::size_t>(ch)], ring_count, 0.5);
  }

  GreyHistogram ring_hist{}, box_hist{};
  for (int y = wy0; y < wy1; y += step) {
    const uchar* row = frame.ptr<uchar>(y);
    for (int x = wx0; x < wx1; x += step) {
      int v = 0;
      for (int ch = 0; ch < channels; ++ch) {
        v = std::max(v, std::abs(static_cast<int>(row[x * channels + ch]) - bg[static_cast<std::size_t>(ch)]));
      }
      ++(inBox(x, y) ? box_hist : ring_hist)[static_cast<std::size_t>(v)];
    }
  }
  const double noise = std::max(1.0, kMadToSigma * histogramGroupedMedian(ring_hist, ring_count));
  int box_count = 0;
  for (const int n : box_hist) box_count += n;
  const int rank = std::max(kSignalRank, box_count / kSignalShareInverse);
  return static_cast<float>(histogramRankFromTop(box_hist, rank) / noise);
}

bool TargetContrast::lost(float reference, float current) {
  return reference >= kMinReference && current < std::min(kFloor, kKeepShare * reference);
}

}  // namespace core
}  // namespace obstacle_tracker
