// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// How much a tracked object grew between two frames, measured from its own pixels and not by the
// correlation filter's scale search: the reference frame's patch around the box is aligned onto
// the new frame's patch under a scale + shift warp (scale_alignment.h), and the fitted scale is
// the expansion.
//
// Both patches cover the same square window, kContext x the reference box's longer side, centred
// on the reference box in the reference frame and on the box's new centre in the new frame, and
// are resampled to kPatchSide x kPatchSide grey pixels (patch_sampler.h). A common resampling
// does not change a scale, so the measurement is in frame terms; the centring leaves only a small
// shift to fit; a square window keeps the frame's aspect (a thin box stretched to a square would
// be blurred along its short side); and the fixed size means no allocation per frame.
//
// Why not Median Flow (Kalal et al., ICPR 2010: the median of pairwise distance ratios of
// Lucas-Kanade point tracks), which was tried first: on the generated approach scenes, whose
// aircraft is a smooth disc with two faint wings, few points have the texture Lucas-Kanade needs
// and those on the sky behind pull the median towards no growth, so the time to contact came
// out far too long (docs/looming.md has the comparison). The region alignment uses every pixel's
// gradient, the outline's included.
#pragma once

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/patch_sampler.h"
#include "obstacle_tracker/core/scale_alignment.h"

namespace obstacle_tracker {
namespace core {

struct ExpansionMeasurement {
  bool valid = false;
  double log_ratio = 0.0;  // ln(size now / size in the reference frame)
  double sigma = 0.0;      // its standard deviation
};

class ExpansionMeter {
 public:
  static constexpr int kPatchSide = 64;           // px of the resampled patches
  static constexpr float kContext = 2.0f;         // window side / the box's longer side
  static constexpr float kMinBoxSide = 6.0f;      // px, longer side; a smaller box has too few pixels
  static constexpr float kMinRegionSide = 12.0f;  // patch px: the aligned region around a thin box
  // The aligned region is the box enlarged by this: a region ending at the object's outline sees
  // only the inner half of the edge's profile, and the expansions read short.
  static constexpr float kRegionMargin = 1.2f;
  // The fit's own standard deviation assumes independent pixel noise; neighbouring pixels are
  // not independent, and on rendered objects the errors were several times the fit's figure,
  // so it is not taken below this.
  static constexpr double kMinSigma = 0.005;
  // Nor below kOutlinePx / sqrt(w h) of the box: an object's outline is rendered (and its
  // pixels quantised) to about half a pixel in each frame, which is a large share of a small
  // object (a 20 px object growing by 0.3 px a frame shows its growth in 1 px steps).
  static constexpr double kOutlinePx = 0.3;

  ExpansionMeter();

  // Forgets the reference.
  void reset() {
    have_reference_ = false;
    measured_frame_ = nullptr;
  }
  bool hasReference() const { return have_reference_; }

  // Keeps the patch around box in frame (CV_8UC1 or CV_8UC3) as the reference of the next
  // measure(). A box whose longer side is below kMinBoxSide, or not finite, leaves no reference.
  void setReference(const cv::Mat& frame, const cv::Rect2f& box);

  // The object's expansion from the reference frame to this one, where its box is centred at
  // `centre`. Invalid without a reference or when the region has too little gradient to tell.
  ExpansionMeasurement measure(const cv::Mat& frame, cv::Point2f centre);

 private:
  void toGrey(const cv::Mat& sampled, cv::Mat& grey) const;

  PatchSampler sampler_;
  ScaleAlignment align_;
  cv::Mat sampled_, reference_grey_, current_grey_;
  cv::Size2f window_;  // frame pixels covered by the reference patch
  cv::Rect region_;    // the reference box x kRegionMargin in patch px (at least kMinRegionSide a side)
  double reference_size_ = 1.0;  // sqrt(w h) of the reference box, frame px
  // Where the last measure() sampled its patch: when setReference() asks for the same window of
  // the same frame (the box kept its size), that patch is reused instead of resampled.
  const uchar* measured_frame_ = nullptr;
  cv::Point2f measured_centre_;
  cv::Size2f measured_window_;
  bool have_reference_ = false;
};

}  // namespace core
}  // namespace obstacle_tracker
