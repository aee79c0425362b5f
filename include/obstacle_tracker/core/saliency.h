// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Saliency detector: FastMBD minimum-barrier-distance saliency (Zhang et al., ICCV 2015), Otsu
// segmentation and connected salient regions (Bharati et al., T-IV 2018, Algorithm 1), on the
// whole frame or inside a search window around the last box.
//
// INTERFACE CONTRACT (used by the pipeline; keep these members and their meaning, add freely).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/params.h"

namespace obstacle_tracker {
namespace core {

struct SalientRegion {
  cv::Rect2f box;               // full-frame pixel coordinates
  float area = 0.0f;            // region pixels, in full-frame pixels^2
  float mean_saliency = 0.0f;   // [0, 1]
  float score = 0.0f;           // ranking score, higher is better (documented in saliency.cpp)
  bool touches_border = false;  // touches the frame (or window) border
};

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

// Auto-initialisation from several frames (on the dev clips one frame's saliency picks the wrong
// object on real footage). Feed every frame while searching; returns the candidates confirmed by
// the multi-frame cues (full-frame coordinates, best first), empty while nothing is confirmed.
class AutoInitializer {
 public:
  // A candidate or track with this share of its pixels on the overlay mask is part of the overlay.
  static constexpr double kOverlayShare = 0.5;

  explicit AutoInitializer(const SaliencyParams& params = SaliencyParams());
  ~AutoInitializer();
  AutoInitializer(const AutoInitializer&) = delete;
  AutoInitializer& operator=(const AutoInitializer&) = delete;

  void setParams(const SaliencyParams& params);
  void reset();
  const std::vector<SalientRegion>& update(const cv::Mat& frame, double stamp);

  // Added (not part of the contract): the last frame's raw candidates (best peak first, score =
  // peak of the candidate map in [0, 1]) and the accumulated background displacement in pixels
  // (the frame centre's displacement summed over the frames: where the scene content at the
  // centre has moved to since the first frame), for tools and tests.
  const std::vector<SalientRegion>& candidates() const;
  cv::Point2d backgroundMotion() const;
  // Share of the box's pixels unchanged (within 3 grey levels) for the last 3 frames: an
  // overlay, or a scene under a still camera. 0 when unknown (auto_init_reject_static off).
  double stillShare(const cv::Rect2f& box) const;
  // Share of the box on the overlay mask (overlay_mask.h): pixels locked to the image while the
  // background moves, the camera's on-screen display. 0 before the camera has moved.
  double overlayShare(const cv::Rect2f& box) const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace core
}  // namespace obstacle_tracker
