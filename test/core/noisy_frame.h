// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// For tests that build a frame in float: sensor noise (Gaussian, `sigma` grey levels, from
// cv::RNG(seed)) added, then the frame as 8-bit grey (saturating at 0 and 255).
#pragma once

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace testing {

inline cv::Mat withNoiseAs8Bit(cv::Mat scene, double sigma, unsigned seed) {
  cv::Mat noise(scene.size(), CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  scene += noise;
  cv::Mat out;
  scene.convertTo(out, CV_8U);
  return out;
}

}  // namespace testing
}  // namespace obstacle_tracker
