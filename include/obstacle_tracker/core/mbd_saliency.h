// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// MBD saliency map of an image (CV_8U, 0..255, max-normalised) at the image's own resolution:
// FastMBD (mbd.h) plus the optional MB+ terms. A building block of the saliency detector
// (saliency.h), exposed for tests, benchmarks and tools.
#pragma once

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/mat_arena.h"
#include "obstacle_tracker/core/params.h"

namespace obstacle_tracker {
namespace core {

// Input CV_8UC1 or CV_8UC3 BGR. Colour: CIE Lab (8-bit OpenCV scaling), the three channel MBD
// maps summed. Options from SaliencyParams: saliency_median, saliency_passes,
// saliency_backgroundness, saliency_postprocess.
class MbdSaliency {
 public:
  // `out` must be a CV_8UC1 Mat of image.size() (a view is fine); it is written in place.
  void compute(const cv::Mat& image, const SaliencyParams& params, cv::Mat& out);

 private:
  void sumChannels(const cv::Mat& dist, int cn, cv::Mat& f);
  void addBackgroundness(const cv::Mat& src, cv::Mat& f);
  void postprocess(cv::Mat& out);

  MatArena lab_, median_, dist_, upper_, lower_, fmap_, fbg_, tmp_a_, tmp_b_;
};

}  // namespace core
}  // namespace obstacle_tracker
