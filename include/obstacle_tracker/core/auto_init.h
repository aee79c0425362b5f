// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// AutoInitializer: the first box without help, from saliency candidates followed over several
// frames (docs/saliency.md). It reports SalientRegions (salient_region.h) as SaliencyDetector does.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/salient_region.h"

namespace obstacle_tracker {
namespace core {

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

  // Added (not part of the contract): the last frame's raw candidates (the peaks of the candidate
  // map best first, then the isolated ones most isolated first; score = the candidate map at the
  // peak, in [0, 1]) and the accumulated background displacement in pixels
  // (the frame centre's displacement summed over the frames: where the scene content at the
  // centre has moved to since the first frame), for tools and tests.
  const std::vector<SalientRegion>& candidates() const;
  cv::Point2d backgroundMotion() const;
  // Frames wider than auto_init_max_width are searched shrunk to that width, and the front end's
  // pixel parameters (auto_init_min_motion, min_object_area) are pixels of that working frame:
  // this is how many of the frame's own pixels one of them spans (1 for narrower frames).
  double framePixelsPerWorkingPixel() const;
  // The boxes below are in the frame's pixels, as are the regions returned.
  // Share of the box's pixels unchanged (within 3 grey levels) for the last 3 frames: an
  // overlay, or a scene under a still camera. 0 when unknown (auto_init_reject_static off).
  double stillShare(const cv::Rect2f& box) const;
  // Share of the box on the overlay mask (overlay_mask.h): pixels locked to the image while the
  // background moves, the camera's on-screen display. 0 before the camera has moved.
  double overlayShare(const cv::Rect2f& box) const;
  // The last frame's most persistent candidate track that no cue has confirmed (seen on
  // 2 x auto_init_frames frames, its pixels not still, not carried by the background's motion),
  // its box refined as a confirmed one's; false when there is none. Evidence weaker than a cue's:
  // the pipeline starts a provisional track on it that any confirmed candidate replaces
  // (docs/saliency.md, "Persistence start").
  bool persistentRegion(const cv::Mat& frame, SalientRegion* region);
  // The candidates at `box` had their chance: the track started there was not verified in time
  // and never moved. persistentRegion() passes them over for the next most persistent candidate
  // until every candidate has had its chance; then the round starts again.
  void setAsidePersistent(const cv::Rect2f& box);
  // Coherence of the last frame's gradients in the box, ((l1 - l2) / (l1 + l2)) of their
  // structure tensor: 1 for a straight edge or line crossing it, near 0 for a blob or texture.
  double lineCoherence(const cv::Rect2f& box) const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace core
}  // namespace obstacle_tracker
