// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The scale (and shift) that maps a region of one grey patch onto the next: image alignment of
// the whole region under a similarity warp without rotation, W(x) = c + s (x - c) + t, by the
// inverse compositional algorithm (Baker & Matthews, "Lucas-Kanade 20 Years On", IJCV 2004,
// sec. 3.2) on a two-level pyramid of patches smoothed by a sigma = 1 px binomial kernel, with
// Huber weights on the residuals (iteratively reweighted least squares) so that background
// pixels that do not follow the object count less.
//
// Point tracks need corners; a small or smooth obstacle (a head-on aircraft is a disc and two thin
// wings) has almost none, but its outline still says how much it grew: every pixel of the region
// with a gradient constrains s. Allocation-free once the buffers exist, and float and double
// arithmetic in a fixed order, so the result does not depend on the CPU's vector units.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

struct ScaleEstimate {
  bool valid = false;
  double log_scale = 0.0;  // ln s
  double sigma = 0.0;      // standard deviation of ln s from the fit (Gauss-Newton covariance)
  cv::Point2f shift;       // t, patch pixels
};

class ScaleAlignment {
 public:
  static constexpr int kLevels = 2;
  static constexpr int kIterations = 15;       // per level, at most
  static constexpr double kEpsilon = 1e-4;       // |d ln s| below this ...
  static constexpr double kShiftEpsilon = 0.01;  // ... and |dt| below this (px): converged
  static constexpr double kHuber = 1.345;      // x the residuals' robust standard deviation
  static constexpr double kMaxLogScale = 0.3;  // a larger fitted change is a failure, not growth

  // reference and current: CV_8UC1 patches of the same size; region: the object's box in the
  // reference patch (its centre is the warp's centre). The region must lie inside the patch.
  ScaleEstimate estimate(const cv::Mat& reference, const cv::Mat& current, const cv::Rect& region);

 private:
  struct Level {
    cv::Mat ref, cur, grad_x, grad_y;  // CV_32F
  };
  bool alignLevel(const Level& lv, const cv::Rect2f& region, double& a, cv::Point2d& t, double& var_ls);

  Level levels_[kLevels];
  std::vector<float> residuals_;  // |residual| per region pixel, for the robust scale
  cv::Mat blur_buffer_;
};

}  // namespace core
}  // namespace obstacle_tracker
