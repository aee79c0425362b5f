// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// AutoInitializer::Impl, shared by auto_init.cpp (the frame's steps, background, still pixels,
// confirmation), auto_init_candidates.cpp (candidate map and candidates), auto_init_cells.cpp
// (where candidates start: cell peaks) and auto_init_tracks.cpp (candidate tracks and their
// motion and growth cues). Private to the core.
//
// Multi-frame auto-initialisation (auto_init.h, AutoInitializer). One frame's saliency picks the
// wrong object on real footage (on-screen text, sunlit ground, parked aircraft outrank the
// target), so candidates are followed over the first frames and confirmed by cues
// that one frame cannot give. Per frame, on the grey image:
//   0. a frame wider than auto_init_max_width is shrunk to that width first (one area resize, or
//      a resize and a colour conversion at the small size); every step below runs at that size,
//      so a 1080p camera costs about what a 640 px one does. Boxes are mapped back to the
//      frame's pixels and refined there (step 6). The pixel parameters (auto_init_min_motion,
//      min_object_area) and constants below are in working pixels: the front end sees every
//      camera as one of at most that width, whose cues were chosen on such footage;
//   1. background motion (background_motion.h: feature tracks and a robust similarity, phase
//      correlation over featureless sky) from the previous frame, summed at the frame centre:
//      where the background has moved to since the start; and the overlay mask (overlay_mask.h):
//      pixels that stay locked to the image while the background moves;
//   2. candidate map P = local contrast at working resolution (|3x3 mean - 21x21 mean|: keeps
//      targets of a few pixels that a 300 px saliency map loses) x MBD saliency at half
//      resolution (suppresses ground, trees and buildings connected to the frame border);
//      auto_init_local_contrast = false uses the MBD map alone;
//   3. candidates: peaks of P that are maxima of their 16x16 cell and its 8 neighbours, the best
//      auto_init_candidates of them; box = the 8-connected pixels >= 0.3 x the peak around it;
//      regions touching the frame border are dropped when reject_border_regions is set, and
//      regions with at least kOverlayShare of their pixels on the overlay mask always, and so
//      are bands (cut at kGrowRadius and kBandElongation x as long as wide). Beside
//      them, up to kIsolatedCandidates isolated peaks of the local contrast map (at least
//      kMinIsolation x the clutter of the cells around them), grown on that map: a small target
//      on plain sky that P's MBD factor, normalised to the frame's most salient object, hides;
//   4. candidates are associated with the tracks of earlier frames (nearest predicted position
//      within a gate); a track is confirmed once seen auto_init_frames times (persistence, at
//      least 60 % of the frames since it appeared) and, when auto_init_min_motion > 0, once it
//      has moved that far against both the image (an overlay or a target the camera keeps still
//      stays put in the image) and the background (a static scene object moves exactly with the
//      background) and vacated its old place (the local contrast there, carried with the
//      background, has fallen under half of what it was: a peak wandering along a static lattice
//      or edge leaves the structure behind), or, when auto_init_min_growth > 0, once its object
//      pixels (>= 0.1 x its peak around the core, on the map it was grown on) have grown
//      steadily by that much in
//      ln sqrt(pixels) over its history: an obstacle on a collision course keeps its bearing and
//      only grows. Still candidates (pixels unchanged for 3 frames) are kept for this cue only;
//   5. score of a confirmed track: mean of P at its peaks x seen share x min(1, motion / (3 x
//      auto_init_min_motion)) (or growth / (3 x auto_init_min_growth));
//   6. the box of a confirmed track is refined by the saliency detector (FastMBD + Otsu) in a
//      window of 4 x the box (at least 32 px) at native resolution, when its best region
//      contains the track's centre, then grown to the object's visible extent (ExtentGrower,
//      extent_contrast: Otsu keeps the bright core of a blurred target of a few pixels).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/auto_init.h"
#include "obstacle_tracker/core/background_motion.h"
#include "obstacle_tracker/core/extent_grower.h"
#include "obstacle_tracker/core/mat_arena.h"
#include "obstacle_tracker/core/mbd_saliency.h"
#include "obstacle_tracker/core/overlay_mask.h"
#include "obstacle_tracker/core/saliency.h"
#include "obstacle_tracker/core/salient_region.h"

namespace obstacle_tracker {
namespace core {
namespace auto_init_detail {

constexpr int kCell = 16;           // candidate cell side (px)
constexpr int kGrowRadius = 64;     // largest half-side of a candidate box (px)
constexpr int kBandElongation = 4;  // a region cut at kGrowRadius this elongated is a band
constexpr int kMaxMissed = 3;       // frames a track may go unseen before it is dropped
constexpr size_t kMaxTracks = 96;
constexpr int kPoolFactor = 4;      // peaks grown per frame, x auto_init_candidates
constexpr int kStillFrames = 3;     // frames a pixel must be unchanged to count as still
constexpr int kStillLevel = 3;      // grey levels of change still counted as unchanged
constexpr float kStillShare = 0.85f;
constexpr float kGrowShare = 0.3f;
constexpr double kRefineWindowScale = 4.0;  // window around a confirmed candidate for its box
constexpr float kRefineMaxGrowth = 16.0f;   // a refined box may cover at most 16 x the candidate's
constexpr double kMinLinearity = 0.5;   // share of position variance a steady motion explains
constexpr float kSizeShare = 0.1f;      // growth cue: object pixels are P >= this x the peak
constexpr int kMinGrowthSamples = 12;  // history points before growth can confirm a track
constexpr double kMinGrowthFit = 0.6;   // share of the log-size variance the growth line explains
constexpr double kVacated = 0.5;        // motion cue: contrast at the old place now / then
constexpr int kLag = 4;                 // frames back for the appearance-change test
constexpr double kMinChange = 0.5;      // appearance change / local contrast of a moving target
constexpr float kMinPeakLevel = 8.0f;   // candidate peaks: at least this grey level of P ...
constexpr float kMinPeakShare = 0.1f;   // ... and this share of the frame's strongest cell
constexpr float kGateMinPx = 8.0f;      // association gate: at least this radius (px) ...
constexpr float kGateBoxShare = 0.75f;  // ... or this share of the track's longer box side,
constexpr float kGatePxPerMissed = 2.0f;  // ... plus this per frame the track went unseen
constexpr double kMinSeenShare = 0.6;   // a track must have been found on this share of its frames
constexpr double kWithBackgroundMinPx = 1.0;  // rms image scatter (px) over which moving with the background shows
// Isolated candidates (isolatedPeaks), on the doubled local contrast map: a cell maximum at least
constexpr float kMinIsolation = 3.0f;  // this factor over the clutter of the ring around it,
constexpr float kClutterFloor = 8.0f;  // taken as at least this (so the maximum is at least 24:
                                       // 12 grey levels of local contrast)
constexpr int kClutterRank = 4;             // clutter: the 4th loudest cell of the ring
constexpr int kIsolatedCandidates = 8;      // kept per frame beside auto_init_candidates
constexpr double kCueSaturation = 3.0;  // a cue counts in full at this multiple of its threshold

struct Candidate {
  cv::Rect box;
  cv::Point2f centre;
  int area = 0;
  float peak = 0.0f, mean = 0.0f;
  float strength = 0.0f;   // P at its peak: what scores its track (the two sources' peaks differ in units)
  float isolation = 0.0f;  // contrast source: its contrast over the clutter around it
  bool from_contrast = false;  // found by isolatedPeaks (grown on the contrast map), not on P
  bool touches_border = false;
  bool truncated = false;  // its region reached kGrowRadius from the seed
  int stamp = -1;  // label of its region in the stamp image
  int size_px = 0;  // pixels of the object above kSizeShare x its peak (growth cue)
  bool still = false;  // its pixels have not changed for kStillFrames frames
};

constexpr int kHistory = 32;  // positions kept per track for the motion fit

inline cv::Point2f apply(const cv::Matx33d& h, cv::Point2f p) {
  const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1.0);
  return {static_cast<float>(q[0] / q[2]), static_cast<float>(q[1] / q[2])};
}

struct Track {
  // Ring buffer of (frame, image position, position in the first frame's background coordinates).
  std::array<int, kHistory> frames;
  std::array<cv::Point2f, kHistory> img, rel;
  std::array<float, kHistory> log_size;  // ln sqrt(size_px): the growth cue's size
  std::array<int, kHistory> contrast;    // local contrast at the position then (vacated test)
  int count = 0;
  void remember(int frame, cv::Point2f p, const cv::Matx33d& image_to_first, int size_px, int local_contrast) {
    const int k = count % kHistory;
    frames[k] = frame;
    contrast[k] = local_contrast;
    log_size[k] = 0.5f * std::log(static_cast<float>(std::max(1, size_px)));
    img[k] = p;
    rel[k] = apply(image_to_first, p);
    ++count;
  }
  cv::Point2f centre, velocity;
  cv::Rect box;
  int first_frame = 0, last_frame = 0, hits = 0, area = 0;
  double sum_peak = 0.0, last_mean = 0.0;
  bool touches_border = false;
  bool still = false;  // its last candidate was still (can only be confirmed by growth)
  // Its persistence start had its chance (AutoInitializer::setAsidePersistent).
  bool set_aside = false;
};

}  // namespace auto_init_detail

struct AutoInitializer::Impl {
  using Candidate = auto_init_detail::Candidate;
  using Track = auto_init_detail::Track;
  static constexpr int kLag = auto_init_detail::kLag;
  static constexpr std::size_t kMaxTracks = auto_init_detail::kMaxTracks;

  SaliencyParams params;
  cv::Size work_size;          // the size every step runs at (step 0)
  cv::Point2d work_scale{1.0, 1.0};  // working / frame pixels, per axis
  MbdSaliency mbd;
  SaliencyDetector refiner;
  ExtentGrower extent;
  MatArena grey_arena, work_arena, half_arena, up_arena, sal_arena, blur_arena, box_arena, contrast_arena, prob_arena;
  BackgroundMotion motion;
  OverlayMask overlay;
  cv::Point2d background{0.0, 0.0};       // working px, since the last restart
  cv::Point2d background_base{0.0, 0.0};  // frame px: carried over a change of working size
  // The background's motion since the first frame (first-frame coordinates -> this frame's) and
  // its inverse.
  cv::Matx33d first_to_image = cv::Matx33d::eye(), image_to_first = cv::Matx33d::eye();
  cv::Size size;
  int frame_index = 0;
  std::vector<int> stamp, queue;
  int stamp_value = 0;
  std::vector<float> cell_max, cell_contrast;
  std::vector<Candidate> isolated;
  cv::Mat prev_grey, still, diff;  // persistent: previous grey frame, per-pixel still count
  std::array<cv::Mat, kLag + 1> past;          // grey frames t, t-1, ..., t-kLag (ring)
  std::array<cv::Matx33d, kLag + 1> past_image_to_first;
  cv::Mat contrast_map;  // this frame's doubled local contrast (CV_8U): isolated candidates, lag test
  std::vector<Candidate> candidates;
  std::vector<Track> tracks;
  std::vector<SalientRegion> confirmed, raw;
  int persistent = -1;  // index in tracks of the best unconfirmed persistent track, or -1
  double persistent_score = 0.0;

  Impl() {
    candidates.reserve(4 * 64 + 4 * 8);  // kPoolFactor x (the largest auto_init_candidates + kIsolatedCandidates)
    tracks.reserve(kMaxTracks + 64);
    confirmed.reserve(64);
    raw.reserve(64);
  }

  // auto_init.cpp
  void reset();
  void setWorkingSize(cv::Size frame_size);
  cv::Mat workingGrey(const cv::Mat& frame);
  cv::Rect2f toFrame(const cv::Rect2f& working_box) const;
  SalientRegion toFrame(SalientRegion working_region) const;  // box and area
  cv::Rect2f toWorking(const cv::Rect2f& frame_box) const;
  void globalMotion(const cv::Mat& grey);
  double overlayShare(const std::vector<int>& pixels, int cols) const;
  void updateStill(const cv::Mat& grey);
  int stillPixels(const cv::Rect& r) const;
  static SalientRegion toRegion(const cv::Rect& box, int area, double mean, double score, bool border);
  void refine(const cv::Mat& frame, SalientRegion& region);
  void confirm(const cv::Mat& frame);

  // auto_init_candidates.cpp
  cv::Mat candidateMap(const cv::Mat& grey);
  void findCandidates(const cv::Mat& p);
  void keepBest(size_t kept);
  void growRegion(const cv::Mat& p, cv::Point seed, Candidate& c);
  bool keepCandidate(Candidate& c, int cols, double max_area);

  // auto_init_cells.cpp
  void cellPeaks(const cv::Mat& p);
  void isolatedPeaks(const cv::Mat& p);
  static void cellMaxima(const cv::Mat& m, std::vector<float>& cells);
  static bool isCellMaximum(const std::vector<float>& cells, int gx, int gy, int gw, int gh);
  static cv::Point2f cellArgmax(const cv::Mat& m, int gx, int gy, float v);
  static float ringClutter(const std::vector<float>& cells, int gx, int gy, int gw, int gh);

  // auto_init_tracks.cpp
  void associate();
  bool changedAgainstBackground(const cv::Rect& box) const;
  int contrastAround(cv::Point2f c) const;
  bool vacated(const Track& t) const;
  static double motionOf(const Track& t, double* linearity = nullptr, bool* with_background = nullptr);
  static double growthOf(const Track& t, double* fit);
};

}  // namespace core
}  // namespace obstacle_tracker
