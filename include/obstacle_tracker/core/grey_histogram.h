// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Robust statistics of 8-bit values from a 256-bin histogram (no sort, no allocation): the ring
// statistics of ExtentGrower (extent_grower.cpp) and TargetContrast (target_contrast.cpp).
#pragma once

#include <algorithm>
#include <array>

namespace obstacle_tracker {
namespace core {

using GreyHistogram = std::array<int, 256>;

// Median absolute deviation to the standard deviation of Gaussian noise: 1 / Phi^-1(3/4).
constexpr double kMadToSigma = 1.4826;

// Smallest level v with more than `share` of the histogram's `count` at or below it.
inline int histogramQuantile(const GreyHistogram& h, int count, double share) {
  const double target = share * count;
  int acc = 0;
  for (int v = 0; v < 256; ++v) {
    acc += h[static_cast<std::size_t>(v)];
    if (acc > target) return v;
  }
  return 255;
}

// The median as grouped data (level v spans v - 0.5 .. v + 0.5): the MAD of sensor noise of one
// or two grey levels is otherwise rounded to a whole level, off by up to 50 %.
inline double histogramGroupedMedian(const GreyHistogram& h, int count) {
  const double target = 0.5 * count;
  int acc = 0;
  for (int v = 0; v < 256; ++v) {
    const int n = h[static_cast<std::size_t>(v)];
    if (n > 0 && acc + n >= target) return std::max(0.0, v - 0.5 + (target - acc) / n);
    acc += n;
  }
  return 255.0;
}

// The highest level with at least `rank` counts at or above it (0 when there are fewer).
inline int histogramRankFromTop(const GreyHistogram& h, int rank) {
  int acc = 0;
  for (int v = 255; v > 0; --v) {
    acc += h[static_cast<std::size_t>(v)];
    if (acc >= rank) return v;
  }
  return 0;
}

}  // namespace core
}  // namespace obstacle_tracker
