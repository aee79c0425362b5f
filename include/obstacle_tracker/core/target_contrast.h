// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#pragma once

#include <array>
#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

// How far the object in a box stands out of its surroundings: the signal-to-clutter ratio of
// small-target detection in infrared and sky images. Background: per channel, the median of a
// ring around the box (margin = half the box's longer side, at least kMinMargin px); contrast of a
// pixel: its largest channel difference to that background; noise: 1.4826 x the median contrast
// on the ring (MAD as a grouped median, at least one grey level); signal: the contrast that the
// brightest 1 % of the box's pixels, and at least kSignalRank of them, reach (a hot pixel alone is
// not an object). A box on plain sky or sensor noise measures about 2-2.6 (the 99th percentile of
// |Gaussian noise| is 2.58 sigma); a small aircraft or drone in it many times more. The ring is
// read on a grid of at most kMaxSamples per side, the box on its own grid of at most
// kMaxBoxSamples (bounded cost for a near obstacle at 1080p; a thin object is still seen).
// No heap allocation; frame CV_8UC1 or CV_8UC3. kUnknown for bad input, a box outside the frame,
// or too little ring inside the frame (a box that covers the view: an obstacle about to hit).
//
// Why the pipeline needs it: a correlation filter started on a small target in a box mostly of
// sky learns mostly sky; under a pan it can follow the sky's texture (clouds, the sensor's fixed
// pattern) with a perfect peak while the target flies on. The peak cannot tell; the box's
// contrast can: lost() is true when a box that started on a contrasted object (checkable():
// at least kFirmReference, or at least kMinReference and kStandOut x what the ring's own pixels
// read, as a small bird in a compressed video's smooth sky) holds nothing out of the noise any
// more (under kFloor, or kFloorShare of a start under 2 x kFloor, or kFadeShare of a start over
// kFloor / kFadeShare, of the larger of the ring's noise now and at the start, below), and the
// pipeline then takes the frame as failed and re-detects (pipeline_tracking.cpp). An object whose
// contrast merely fades stays found while it stays out of that noise (one that fades into it, or
// that fills only a small part of a box too large for it, reads lost); unknown is never lost. Nor is
// a ratio that fell because the ring's noise rose beyond kMaxNoiseRise x the reference's: the
// object moved in front of clutter (an aircraft taxiing past a hillside and runway markings),
// where a low ratio says nothing about the box. Where the ring's noise fell instead (the clouds
// around the start cleared), the ratio rises for anything in the box, so the signal (ratio x
// noise) is held against the larger of the two noises: a piece of cloud the filter started on
// leaves a faint remnant that stands out of the plain sky but not out of the clouds it stood out
// of, while an aircraft keeps its signal.
class TargetContrast {
 public:
  static constexpr float kUnknown = -1.0f;
  static constexpr float kMinMargin = 4.0f;
  static constexpr int kSignalRank = 4;
  static constexpr int kSignalShareInverse = 100;  // the brightest 1 %
  static constexpr int kMaxSamples = 128;
  static constexpr int kMaxBoxSamples = 512;
  static constexpr float kMinReference = 4.0f;
  static constexpr float kFirmReference = 6.0f;
  static constexpr float kStandOut = 2.0f;
  static constexpr float kFloor = 3.0f;
  static constexpr float kFloorShare = 0.5f;
  static constexpr float kFadeShare = 0.1f;
  static constexpr float kMaxNoiseRise = 2.0f;

  // A measurement: the ratio, and the ring's noise it divides by (grey levels; 0 when unknown).
  struct Reading {
    float ratio = kUnknown;
    float noise = 0.0f;
    float ring_ratio = kUnknown;  // what the ring's own brightest 1 % read, in the same units
  };
  Reading read(const cv::Mat& frame, const cv::Rect2f& box) const;
  float measure(const cv::Mat& frame, const cv::Rect2f& box) const { return read(frame, box).ratio; }
  // Whether a reading can serve as the reference of lost(): at least kStandOut x what the ring's
  // own pixels read, and that need kept within kMinReference..kFirmReference (an object in
  // clutter stands out of it no more than the clutter does, and then a low ratio later tells
  // nothing; a start of kFirmReference or more is checked whatever its ring). A reading whose
  // ring is unknown (built by hand) needs kFirmReference.
  static bool checkable(const Reading& reference);
  static bool lost(const Reading& reference, const Reading& current);
};

}  // namespace core
}  // namespace obstacle_tracker
