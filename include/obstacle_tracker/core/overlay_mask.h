// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Pixels locked to the image: what the camera (or its recorder) draws over the scene, on-screen
// text, reticle lines and corner brackets, clocks, logos. They are not obstacles and must never
// become a candidate, nor carry a feature track of the background.
//
// Told apart by how they move, not by how they look: between two frames with the background
// motion A (background_motion.h), a pixel is explained either by the image-locked hypothesis
// (current = previous at the same place) or by the background hypothesis (current = previous
// warped by A). Where the two hypotheses predict clearly different values (|warp(previous) -
// previous| >= min_separation grey levels), the frame votes: locked when the image-locked
// prediction's error is under locked_error_share of the background one's and of the separation
// and the pixel lies on an edge of the current frame (3x3 morphological gradient >=
// min_separation: inside a uniform region "unchanged" says nothing about motion), moved when the
// image-locked prediction does not explain it. Votes accumulate per pixel in a score (locked +1, moved -moved_penalty,
// clamped to [0, max_score]); the mask is score >= mask_score, grown by one pixel.
//
// A mover votes "moved" where it passes, and passes on; a target the camera keeps centred still
// wobbles and changes, so it does not collect mask_score votes while an overlay collects one per
// frame of camera motion. Under a still camera nothing is separable and the mask does not
// change: there, overlays and the static scene look alike (the still-pixel cue of the
// auto-initialiser handles both). Likewise a straight line is revealed only by motion across it:
// a reticle arm under a pan exactly along it collects no votes until the camera also tilts.
//
// Everything runs on the background-motion estimator's shrunk frames (its working size).
#pragma once

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

struct OverlayMaskSettings {
  int min_separation = 12;           // grey levels between the two hypotheses' predictions
  float locked_error_share = 0.35f;  // locked: image-locked error < this x the other's and x separation
  int moved_penalty = 2;             // score lost per "moved" vote
  int mask_score = 8;                // score from which a pixel is in the mask
  int max_score = 24;                // ceiling: how long an overlay stays masked once it is gone
  double min_background_shift = 0.25; // working px (largest over the frame) for a frame to vote
};

class OverlayMask {
 public:
  explicit OverlayMask(const OverlayMaskSettings& settings = OverlayMaskSettings());

  void reset();

  // `previous`, `current`: CV_8UC1 working frames of the same size; `previous_to_current`: the
  // background motion between them in working coordinates. A frame of another size restarts the
  // mask.
  void update(const cv::Mat& previous, const cv::Mat& current, const cv::Matx23d& previous_to_current);

  // CV_8UC1 of the working size, 255 = locked to the image (empty before the first update).
  const cv::Mat& mask() const { return mask_; }
  // Share of `box` (working coordinates) inside the mask; 0 when there is no mask yet.
  double share(const cv::Rect& box) const;

 private:
  OverlayMaskSettings settings_;
  cv::Mat score_, mask_, warped_, valid_, separation_, locked_error_, moved_error_, separable_, locked_, edges_,
      scratch_;
};

}  // namespace core
}  // namespace obstacle_tracker
