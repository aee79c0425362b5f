// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// How the background moved between two consecutive frames: the camera's pan, tilt, roll and zoom
// as one similarity transform (4 degrees of freedom), from sparse feature tracks.
//
//   1. The frame is area-shrunk once to at most BackgroundMotionSettings::working_width pixels
//      wide; everything after runs at that size, so the cost does not grow with the camera's
//      resolution beyond that one pass.
//   2. Corners of the previous frame (Shi & Tomasi 1994, cv::goodFeaturesToTrack), an equal
//      number per cell of a 6 x 4 grid (each relative to its cell's best, so that one strongly
//      textured region, e.g. on-screen text, cannot outvote the rest of the frame) and spread by
//      a minimum distance; none on pixels the caller excludes (an overlay mask: on-screen text
//      and reticles do not move with the background and must not vote for its motion). The
//      background points of the last estimate are followed on; a cell is searched for new
//      corners only when it has lost half of its share.
//   3. Pyramidal Lucas-Kanade (Bouguet 2000, cv::calcOpticalFlowPyrLK) forward to the current
//      frame and back; a track whose round trip misses its start by more than
//      max_forward_backward_error is dropped (Kalal et al., ICPR 2010: the forward-backward error
//      flags occlusions and drift).
//   4. A similarity fitted robustly (cv::estimateAffinePartial2D, RANSAC): the background is the
//      motion most tracks agree on; movers and the target are outliers. Quality = inliers /
//      consistent tracks. Then refitted, twice, on the tracks within refine_threshold of the
//      current fit only: under a slow pan, points that do not move at all (on-screen text
//      before the overlay mask has it) lie within RANSAC's threshold of the background's motion,
//      and a fit to all of RANSAC's inliers is pulled towards zero (a 1 px-per-frame pan read
//      0.85 px); the tight refit leaves them out. (A tight RANSAC threshold alone would not do:
//      a pan slower than the threshold can never be told from still points by it.)
//   Fallback over featureless sky (fewer than min_tracks consistent tracks, or no motion that
//   min_inlier_share of them agree on: sensor noise gives corners without a motion): phase correlation of
//   the two shrunk frames (Kuglin & Hines 1975, cv::phaseCorrelate), a translation only, with its
//   response as quality, kept only if it explains most of the frame better than no motion (over
//   a plain sky the one textured object in view, often the target, decides the peak). If
//   not, the estimate is the identity with Source::kNone: the frame says nothing about the
//   background, and callers treat it as unknown (no motion).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

struct BackgroundMotionSettings {
  int working_width = 320;                  // px; wider frames are shrunk to this width first
  int max_features = 96;                    // corners per frame (4 per grid cell)
  double feature_quality = 0.01;            // share of the best corner's response a corner needs
  double feature_spacing = 8.0;             // working px between corners
  int flow_window = 11;                     // Lucas-Kanade window side, working px
  int flow_levels = 2;                      // pyramid levels above the base (motion up to ~30 working px)
  double max_forward_backward_error = 0.5;  // working px
  double ransac_threshold = 1.0;            // working px, reprojection error of an inlier
  double refine_threshold = 0.2;            // working px, of the tracks the final fit uses
  int min_tracks = 12;                      // consistent tracks (and inliers) the feature estimate needs
  double min_inlier_share = 0.5;            // of the consistent tracks; fewer: no agreed motion
  double min_phase_response = 0.2;          // phase correlation's fallback needs this peak
};

struct BackgroundMotionEstimate {
  enum class Source { kNone, kFeatures, kPhaseCorrelation };
  // x_current = A (x_previous, 1): full-resolution pixel coordinates.
  cv::Matx23d previous_to_current = cv::Matx23d(1, 0, 0, 0, 1, 0);
  Source source = Source::kNone;
  double quality = 0.0;  // features: inlier share of the consistent tracks; phase: its response
  int tracks = 0;        // forward-backward consistent tracks
  int inliers = 0;       // of those, agreeing with the fitted motion

  bool known() const { return source != Source::kNone; }
  // Where the background at image point p of the previous frame is now, minus p.
  cv::Point2d displacementAt(const cv::Point2d& p) const;
};

class BackgroundMotion {
 public:
  explicit BackgroundMotion(const BackgroundMotionSettings& settings = BackgroundMotionSettings());

  void reset();

  // `grey`: CV_8UC1 frame. `excluded`: empty, or CV_8UC1 of workingSize(grey.size()), non-zero
  // where no corner may be taken (in the previous frame's coordinates). The first frame, and a
  // frame of another size than the one before, have no previous frame: Source::kNone.
  const BackgroundMotionEstimate& update(const cv::Mat& grey, const cv::Mat& excluded = cv::Mat());

  const BackgroundMotionEstimate& estimate() const { return estimate_; }
  // The shrunk frames of the last update (the overlay mask works on them) and the scale from
  // full resolution to them (working = scale x full).
  const cv::Mat& currentWorkingFrame() const { return current_; }
  const cv::Mat& previousWorkingFrame() const { return previous_; }
  // Pixel centres map as x_working = scale.x (x_full + 0.5) - 0.5 (cv::resize's convention), per
  // axis: rounding the shrunk height makes the two scales differ by up to half a row.
  cv::Point2d workingScale() const { return scale_; }
  // The estimate in working-frame coordinates.
  cv::Matx23d workingTransform() const;
  cv::Size workingSize(cv::Size full) const;

 private:
  bool fromFeatures(const cv::Mat& excluded);
  bool fromPhaseCorrelation();
  cv::Matx23d refitOnTightInliers(const cv::Matx23d& fitted);

  BackgroundMotionSettings settings_;
  BackgroundMotionEstimate estimate_;
  cv::Mat previous_, current_, hann_, previous_float_, current_float_, corner_mask_, shifted_, moved_error_,
      still_error_, gain_;
  std::vector<cv::Point2f> corners_, cell_corners_, kept_, forward_, backward_, from_, to_, tight_from_, tight_to_;
  std::vector<int> cell_count_;
  std::vector<unsigned char> forward_status_, backward_status_, inlier_flags_;
  std::vector<float> flow_error_;
  cv::Point2d scale_{1.0, 1.0};
};

}  // namespace core
}  // namespace obstacle_tracker
