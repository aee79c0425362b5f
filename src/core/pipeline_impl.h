// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Pipeline::Impl, shared by pipeline.cpp (frame bookkeeping, track start, report),
// pipeline_tracking.cpp (a track's frame: filter, re-detection) and pipeline_search.cpp
// (auto-initialisation, verification of auto-started tracks, merges). Private to the core.
//
// The closed detection-tracking loop of Bharati et al. (T-IV 2018), extended to several
// obstacles and looming (looming.h, docs/looming.md).
//
// Per track, per frame:
//   tracking     KcfTracker::update. peak >= peak_threshold and a box that still holds the
//                contrasted object the filter started on (target_contrast.h): the new box is
//                kept. Otherwise the track re-detects in the same frame. After dropped frames the
//                search may start at the constant-velocity prediction instead (bridgeDroppedFrames).
//   re-detecting the filter's own answer (update without learning) counts when its peak passes the
//                re-detection test; otherwise the candidates are the salient
//                regions inside search_window_scale x the box around the prediction (constant
//                velocity since the last good frame); each gets a prior from its saliency, its
//                distance to the prediction and its size/aspect against the last box; the best
//                few are verified by correlating the filter model at them (KcfTracker::evaluate,
//                no state change) and the best verified one whose peak >= redetect_min_peak is
//                accepted: the filter restarts (init) there, the region giving the centre and
//                each side the last box's fused with the region's extent. After a failed frame,
//                a candidate alone in the window (high prior, no rival) is accepted at
//                redetect_solo_peak x the peak threshold (the target's surroundings changed
//                under the model). Once a box has lost the
//                object since the last restart (the model followed the background), a candidate
//                the model does not verify may be taken on its own contrast; the track is then
//                unverified, as an auto-started one. A frame without an
//                accepted candidate is a failure; more than max_redetect_failures consecutive failures end the track (reported once
//                with state kLost, then removed).
//   searching    while there is room for a track, AutoInitializer is fed every
//                detection_interval frames; confirmed candidates that do not overlap a track
//                become tracks. An auto-started track is verified (verify()): until it has moved
//                like an obstacle, the AutoInitializer keeps running beside it and a candidate it
//                confirms elsewhere is tracked unreported as a challenger, which replaces the
//                track if it passes the same test first (auto_init_verify_frames).
// Boxes from saliency (auto-initialisation and re-detection) are grown from the region's bright
// core to the object's visible extent (ExtentGrower, extent_contrast).
// With max_obstacles > 1: tracks overlapping by more than merge_iou are merged (the older one
// stays), and in a re-detection a second well-separated salient region that verifies poorly
// against the model (a split) starts a new track when there is room.
//
// Reported confidence = KcfResult::confidence (mapping in kcf.h) of the frame's final answer,
// capped at learn_threshold while re-detecting (a box that lost the contrasted object the filter
// started on, target_contrast.h, counts as a failed frame), at kUnconfirmedConfidenceCap while
// unverified; 0 when lost.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "obstacle_tracker/core/auto_init.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/extent_grower.h"
#include "obstacle_tracker/core/frame_interval.h"
#include "obstacle_tracker/core/kcf.h"
#include "obstacle_tracker/core/looming.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/core/saliency.h"
#include "obstacle_tracker/core/target_contrast.h"

namespace obstacle_tracker {
namespace core {
namespace pipeline_detail {

constexpr float kVelocitySmoothing = 0.5f;   // weight of the newest displacement in the EMA
constexpr double kMinVelocityDt = 1e-4;      // s; shorter frame intervals give no velocity
constexpr float kMaxPredictionBoxes = 2.0f;  // predicted shift capped at this many box sides
constexpr float kDistanceSigma = 0.5f;       // distance prior sigma, fraction of the window side
constexpr float kSizeSigma = 0.7f;           // size prior sigma on |ln(area ratio)| / 2
constexpr float kSpawnMaxIou = 0.05f;        // a new track must not overlap an existing one
constexpr float kMinSearchBoxSide = 16.0f;   // px; the window is search_window_scale x this at least
constexpr float kWindowGrowthPerFailure = 0.5f;
constexpr float kMaxWindowGrowth = 3.0f;
constexpr float kSoloPrior = 0.8f;           // re-detection: a candidate alone in the window ...
constexpr float kSoloMargin = 0.5f;          // ... (every other prior below this x its own)
constexpr float kVerifyPanShare = 0.5f;     // verify(): share of the background's displacement added
constexpr float kVerifyMinImageMotion = 2.0f;  // verify(): working px (auto_init_max_width) an overlay never moves
constexpr double kVerifyStillShare = 0.5;    // verify(): a box with this share of still pixels is an overlay
constexpr double kVerifyMaxLineCoherence = 0.85;  // verify(): gradients this aligned are a line, no motion evidence
constexpr float kMaxResize = 1.5f;           // a re-detected box side is within 1/1.5..1.5 x the last
constexpr float kGivenBoxSigma = 0.05f;      // ln units: a given box's sides (the default scale step, 5 %)
constexpr float kExtentErrorPx = 1.5f;       // px: a segmented extent's error per side
constexpr double kMaxSizeVariance = 1.0;     // ln units^2: redetectedSize()'s prior at most
constexpr float kReacquireContrastShare = 0.5f;  // contrastedCandidate(): of the reference's contrast
// contrastedCandidate(): a TargetContrast ratio at least this. Contrast alone also takes clutter,
// and a region that stands out of the sky by less is too often a cloud's edge; a faint target
// that was lost is taken back by the filter's verification of a candidate instead.
constexpr float kReacquireMinContrast = TargetContrast::kFirmReference;
constexpr float kReacquireMinPrior = 0.1f;       // contrastedCandidate(): a candidate's least prior

// Variances of ln(width) and ln(height) of a segmented region's box: kExtentErrorPx per side.
inline cv::Vec2f extentVariance(const cv::Size2f& size) {
  const float ew = kExtentErrorPx / std::max(1.0f, size.width), eh = kExtentErrorPx / std::max(1.0f, size.height);
  return cv::Vec2f(ew * ew, eh * eh);
}

// Keeps the box's centre inside the frame (the box may still stick out).
inline cv::Rect2f clampCentre(const cv::Rect2f& b, const cv::Size& frame) {
  cv::Point2f c = boxCentre(b);
  c.x = std::min(std::max(c.x, 0.0f), static_cast<float>(frame.width - 1));
  c.y = std::min(std::max(c.y, 0.0f), static_cast<float>(frame.height - 1));
  return boxCentredAt(c, b.size());
}

inline bool usableBox(const cv::Rect2f& b, const cv::Size& frame) {
  if (!boxHasPixels(b)) return false;
  return (b & cv::Rect2f(0.0f, 0.0f, static_cast<float>(frame.width), static_cast<float>(frame.height)))
             .area() > 0.0f;
}

// Report order: tracking, re-detecting, lost.
inline int stateRank(TrackState s) {
  switch (s) {
    case TrackState::kTracking:
      return 0;
    case TrackState::kRedetecting:
      return 1;
    case TrackState::kLost:
      return 2;
    case TrackState::kSearching:
      break;
  }
  return 3;
}

}  // namespace pipeline_detail

struct Pipeline::Impl {
  // One obstacle's state; newTrack() resets each part as a whole (the filter and the looming
  // estimator by their own init and start).
  struct Track {
    // What is reported for the track this frame, and how it stands.
    struct Status {
      int id = -1;
      TrackState state = TrackState::kTracking;
      cv::Rect2f box;  // box reported this frame
      int failures = 0;  // consecutive frames without an accepted box
      int age = 0;       // frames since the start
      // A challenger (search()): tracked but not reported until it replaces an unverified track.
      bool probation = false;
    };
    // Where the object was last seen well and how its centre moves (px/s, an EMA of the good
    // frames' displacements): the re-detection's prediction.
    struct Motion {
      cv::Rect2f good_box;  // last box accepted with a good peak
      double good_stamp = 0.0;
      cv::Point2f velocity{0.0f, 0.0f};
      bool have_velocity = false;
      // How well the box's sides are known (variances of their logarithms) as of size_stamp (the
      // start or the last re-detection): the given or detected box's, then fused with each
      // re-detection's extent (redetectedSize()).
      cv::Vec2f size_var{0.0f, 0.0f};
      double size_stamp = 0.0;
    };
    // What a frame's answer is judged against: the contrast of the box the filter (re)started on
    // (TargetContrast), and the running means of the peak and PSR on good frames (LMCF, Wang et
    // al. CVPR 2017). lost_object: an answer's box lost the contrasted object since the last
    // (re)start or accepted frame (the model may have followed the background, so it cannot
    // verify a re-detection alone).
    struct References {
      TargetContrast::Reading contrast;
      bool lost_object = false;
      float peak = 0.0f, psr = 0.0f;
      int count = 0;  // good frames in the means
    };
    // What is currently set in the filter (configureFilter sets it only when it changes).
    struct FilterGate {
      float learn_gate = -1.0f;  // learn_threshold currently set in the filter
      bool learning = true;      // learning_rate currently set in the filter (else 0)
    };
    // Verification of an auto-started track (verify()): it counts as an obstacle once it has
    // moved like one, or grown; until then it may give way to a challenger.
    struct Verification {
      bool verified = true;
      int watched = 0;  // checks while unverified (one per auto-init frame)
      cv::Point2f start_centre{0.0f, 0.0f};
      cv::Point2d start_background{0.0, 0.0};
      float start_log_size = 0.0f;
      float max_image_motion = 0.0f;
      double coherence_sum = 0.0;  // lineCoherence of the box, summed over the motion checks
      int coherence_checks = 0;
      bool provisional = false;  // started on persistence alone: any confirmed candidate replaces it
      // The start (centre, background, size) is taken at the next auto-initialisation frame: a
      // track re-acquired in step() is re-placed before search() has measured this frame's motion.
      bool start_pending = false;
    };

    Track(const TrackerParams& filter, const LoopParams& loop) : kcf(filter) {
      looming.setParams(loop.looming_rate_noise, loop.looming_from_pixels);
    }
    KcfTracker kcf;
    LoomingEstimator looming;
    Status status;
    KcfResult result;  // the filter's answer this frame
    Motion motion;
    References refs;
    FilterGate gate;
    Verification verification;
  };

  struct Candidate {
    cv::Rect2f box;
    float prior = 0.0f;
    const SalientRegion* region = nullptr;
  };

  explicit Impl(const Params& p) : params(p), saliency(p), autoinit(p) {
    validate(params);
    saliency.setParams(params);
    autoinit.setParams(params);
    tracks.reserve(16);
    pool.reserve(16);
    out.reserve(16);
    candidates.reserve(64);
    spawn.reserve(16);
  }

  Params params;
  Params pending;
  bool have_pending = false;
  SaliencyDetector saliency;
  AutoInitializer autoinit;
  ExtentGrower extent;
  TargetContrast contrast;
  std::vector<std::unique_ptr<Track>> tracks;
  std::vector<std::unique_ptr<Track>> pool;  // ended tracks, reused (their filter buffers too)
  std::vector<Obstacle> out;
  std::vector<Candidate> candidates;
  std::vector<cv::Rect2f> spawn;
  int next_id = 0;
  long frame_index = 0;
  double last_stamp = -std::numeric_limits<double>::infinity();
  FrameInterval frame_interval;  // the usual frame interval, and the frames dropped before this one
  cv::Size frame_size;
  bool autoinit_fresh = true;
  // pipeline.cpp
  void resetAll();
  void applyPending();
  void beginFrame(const cv::Mat& frame, double stamp, const char* who);
  Track& newTrack(const cv::Mat& frame, double stamp, const cv::Rect2f& box, bool given = false);
  Track& newAutoTrack(const cv::Mat& frame, double stamp, const cv::Rect2f& box);
  void beginVerification(Track& t, const cv::Rect2f& box);
  void setVerificationStart(Track& t, const cv::Rect2f& box);
  void restartVerification(Track& t);
  void placeVerificationStart(Track& t);
  bool verificationOn() const { return params.auto_init_verify_frames > 0 && params.auto_init_min_motion > 0.0; }
  void report();
  const std::vector<Obstacle>& run(const cv::Mat& frame, double stamp, const cv::Rect2f* start_box);

  // pipeline_tracking.cpp
  void acceptGood(Track& t, const cv::Rect2f& box, double stamp);
  cv::Rect2f predict(const Track& t, double stamp) const;
  bool redetect(Track& t, const cv::Mat& frame, double stamp);
  void gatherCandidates(const Track& t, const cv::Mat& frame, const cv::Rect2f& pred);
  int chooseCandidate(Track& t, const cv::Mat& frame, KcfResult& chosen, bool& by_contrast);
  int contrastedCandidate(Track& t, const cv::Mat& frame, KcfResult& chosen);
  bool lostObject(Track& t, const cv::Mat& frame, const cv::Rect2f& box);
  void noteSplit(int best);
  struct RedetectedSize {
    float side[2];      // width, height (px)
    cv::Vec2f variance;  // of their logarithms
  };
  static RedetectedSize redetectedSize(const Track::Motion& motion, double stamp, const cv::Size2f& measured);
  bool restartOn(Track& t, const cv::Mat& frame, double stamp, const cv::Rect2f& region,
                 const KcfResult& verified_result);
  float goodPeak(const Track& t) const;
  float acceptPeak(const Track& t) const;
  void configureFilter(Track& t, bool learn);
  static void updateRefs(Track& t, const KcfResult& r);
  float inFrameFraction(const cv::Rect2f& b) const;
  void step(Track& t, const cv::Mat& frame, double stamp);
  void bridgeDroppedFrames(Track& t, const cv::Mat& frame);

  // pipeline_search.cpp
  bool overlapsTrack(const cv::Rect2f& b, float max_iou) const;
  int activeTracks() const;
  void mergeTracks();
  void verify(Track& t);
  Track* replaceableTrack();
  bool anyUnverified() const;
  Track* challenger();
  Track* provisionalTrack();
  void setAsideMotionlessTrack(const cv::Mat& frame);
  void confirmProvisional(const cv::Rect2f& box);
  void removeTrack(const Track* victim);
  void settleChallenge();
  void search(const cv::Mat& frame, double stamp);
  void spawnSplits(const cv::Mat& frame, double stamp);

  static constexpr int kRefWarmup = 3;         // good frames before the relative tests apply
  static constexpr float kRefSmoothing = 0.2f;   // EMA weight of the newest good frame
  static constexpr float kMinInFrame = 0.5f;     // share of a tracked box inside the frame
  static constexpr float kMaxLearnGate = 0.75f;
};

}  // namespace core
}  // namespace obstacle_tracker
