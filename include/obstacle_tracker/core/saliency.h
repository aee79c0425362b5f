// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Saliency detector: FastMBD minimum-barrier-distance saliency (Zhang et al., ICCV 2015), Otsu
// segmentation and connected salient regions (Bharati et al., T-IV 2018, Algorithm 1), on the
// whole frame or inside a search window around the last box.
//
// The pipeline (pipeline_impl.h) relies on the members below and their meaning.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/salient_region.h"

namespace obstacle_tracker {
namespace core {

class SaliencyDetector {
 public:
  explicit SaliencyDetector(const SaliencyParams& params = SaliencyParams());
  ~SaliencyDetector();
  SaliencyDetector(const SaliencyDetector&) = delete;
  SaliencyDetector& operator=(const SaliencyDetector&) = delete;

  void setParams(const SaliencyParams& params);

  // Whole-frame detection. frame: CV_8UC1 (grey/thermal) or CV_8UC3 (BGR), non-empty.
  // Returns the salient regions ranked best first (empty when nothing qualifies). Throws
  // std::invalid_argument on an empty frame or an unsupported type.
  const std::vector<SalientRegion>& detect(const cv::Mat& frame);

  // Re-detection inside searchWindow(frame.size(), last_box, params.search_window_scale);
  // regions come back in full-frame coordinates, ranked best first.
  const std::vector<SalientRegion>& detectInWindow(const cv::Mat& frame, const cv::Rect2f& last_box);

  // search_window_scale x the box, centred on it, at least a few dozen pixels, clipped to the
  // frame. Empty when the box does not intersect the frame.
  static cv::Rect searchWindow(const cv::Size& frame_size, const cv::Rect2f& box, double scale);

  // The last saliency map (CV_8U, 0..255), at the resolution it was computed at, and the
  // full-frame rectangle it covers.
  const cv::Mat& saliencyMap() const;
  cv::Rect mapRegion() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace core
}  // namespace obstacle_tracker
