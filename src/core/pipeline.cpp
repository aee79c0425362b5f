// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The closed detection-tracking loop of Bharati et al. (T-IV 2018), extended to several
// obstacles and looming (looming.h, docs/looming.md).
//
// Per track, per frame:
//   tracking     KcfTracker::update. peak >= peak_threshold: the new box is kept. Otherwise the
//                track re-detects in the same frame.
//   re-detecting the filter's own answer (update without learning) counts when its peak passes the
//                re-detection test; otherwise the candidates are the salient
//                regions inside search_window_scale x the box around the prediction (constant
//                velocity since the last good frame); each gets a prior from its saliency, its
//                distance to the prediction and its size/aspect against the last box; the best
//                few are verified by correlating the filter model at them (KcfTracker::evaluate,
//                no state change) and the best verified one whose peak >= redetect_min_peak is
//                accepted: the filter restarts (init) on its box, so the box takes the object's
//                current size and shape. After a failed frame, a candidate alone in the window
//                (high prior, no rival) is accepted at redetect_solo_peak x the peak threshold
//                (the target's surroundings changed under the model). A frame without an
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
// Reported confidence = KcfResult::confidence (mapping in kcf.h) of the frame's final answer.
#include "obstacle_tracker/core/pipeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "obstacle_tracker/core/kcf.h"
#include "obstacle_tracker/core/looming.h"
#include "obstacle_tracker/core/saliency.h"
#include "obstacle_tracker/core/segmentation.h"
#include "obstacle_tracker/core/target_contrast.h"
#include "obstacle_tracker/core/warmup.h"

namespace obstacle_tracker {
namespace core {

namespace {

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
constexpr float kVerifyMinImageMotion = 2.0f;  // verify(): px an overlay never moves in the image
constexpr double kStillShare = 0.5;          // verify(): a box with this share of still pixels is an overlay
constexpr float kMaxResize = 1.5f;           // a re-detected box side is within 1/1.5..1.5 x the last

float iou(const cv::Rect2f& a, const cv::Rect2f& b) {
  const float inter = (a & b).area();
  const float uni = a.area() + b.area() - inter;
  return uni > 0.0f ? inter / uni : 0.0f;
}

cv::Point2f centre(const cv::Rect2f& b) { return {b.x + 0.5f * b.width, b.y + 0.5f * b.height}; }

cv::Rect2f centredAt(const cv::Point2f& c, const cv::Size2f& s) {
  return {c.x - 0.5f * s.width, c.y - 0.5f * s.height, s.width, s.height};
}

// Keeps the box's centre inside the frame (the box may still stick out).
cv::Rect2f clampCentre(const cv::Rect2f& b, const cv::Size& frame) {
  cv::Point2f c = centre(b);
  c.x = std::min(std::max(c.x, 0.0f), static_cast<float>(frame.width - 1));
  c.y = std::min(std::max(c.y, 0.0f), static_cast<float>(frame.height - 1));
  return centredAt(c, b.size());
}

bool usableBox(const cv::Rect2f& b, const cv::Size& frame) {
  if (!std::isfinite(b.x) || !std::isfinite(b.y) || !std::isfinite(b.width) ||
      !std::isfinite(b.height) || b.width < 1.0f || b.height < 1.0f) {
    return false;
  }
  return (b & cv::Rect2f(0.0f, 0.0f, static_cast<float>(frame.width), static_cast<float>(frame.height)))
             .area() > 0.0f;
}

int stateRank(TrackState s) {
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

}  // namespace

struct Pipeline::Impl {
  struct Track {
    explicit Track(const Params& p) : kcf(p) { looming.setParams(p.looming_rate_noise, p.looming_from_pixels); }
    int id = -1;
    KcfTracker kcf;
    LoomingEstimator looming;
    TrackState state = TrackState::kTracking;
    cv::Rect2f box;             // box reported this frame
    cv::Rect2f good_box;        // last box accepted with a good peak
    double good_stamp = 0.0;
    cv::Point2f velocity{0.0f, 0.0f};  // px/s, centre
    bool have_velocity = false;
    int failures = 0;
    int age = 0;
    KcfResult result;
    // Running means of the peak and PSR on good frames (LMCF, Wang et al. CVPR 2017).
    float ref_peak = 0.0f, ref_psr = 0.0f;
    int ref_count = 0;
    float learn_gate = -1.0f;  // learn_threshold currently set in the filter
    bool learning = true;      // learning_rate currently set in the filter (else 0)
    // Verification of an auto-started track (verify()): it counts as an obstacle once it has
    // moved like one, or grown; until then it may give way to a challenger.
    bool verified = true;
    int watched = 0;                  // checks while unverified (one per auto-init frame)
    cv::Point2f start_centre{0.0f, 0.0f};
    cv::Point2d start_background{0.0, 0.0};
    float start_log_size = 0.0f;
    float max_image_motion = 0.0f;
    // A challenger (search()): tracked but not reported until it replaces an unverified track.
    bool probation = false;
    float contrast_ref = 0.0f;  // TargetContrast of the box the filter (re)started on
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
  cv::Size frame_size;
  bool autoinit_fresh = true;

  static void checkFrame(const cv::Mat& frame, const char* who) {
    if (frame.empty()) throw std::invalid_argument(std::string(who) + ": empty frame");
    if (frame.type() != CV_8UC1 && frame.type() != CV_8UC3) {
      throw std::invalid_argument(std::string(who) +
                                  ": frame must be CV_8UC1 (grey) or CV_8UC3 (BGR), got type " +
                                  std::to_string(frame.type()));
    }
  }

  void resetAll() {
    while (!tracks.empty()) {
      pool.push_back(std::move(tracks.back()));
      tracks.pop_back();
    }
    autoinit.reset();
    autoinit_fresh = true;
    out.clear();
    last_stamp = -std::numeric_limits<double>::infinity();
    frame_index = 0;
  }

  void applyPending() {
    if (!have_pending) return;
    params = pending;
    have_pending = false;
    saliency.setParams(params);
    autoinit.setParams(params);
    for (auto& t : tracks) {
      t->kcf.setParams(params);
      t->learn_gate = -1.0f;  // the filter has the plain params now: configureFilter sets its gate again
      t->looming.setParams(params.looming_rate_noise, params.looming_from_pixels);
    }
    for (auto& t : pool) t->kcf.setParams(params);
    // The surplus of a smaller max_obstacles goes from the back; a challenger is not one of the
    // max_obstacles tracks and stays.
    int kept = 0;
    for (const auto& t : tracks) kept += t->probation ? 0 : 1;
    for (std::size_t i = tracks.size(); i-- > 0 && kept > params.max_obstacles;) {
      if (tracks[i]->probation) continue;
      pool.push_back(std::move(tracks[i]));
      tracks.erase(tracks.begin() + static_cast<long>(i));
      --kept;
    }
  }

  // Frame bookkeeping shared by process() and startTrack().
  void beginFrame(const cv::Mat& frame, double stamp, const char* who) {
    checkFrame(frame, who);
    if (!std::isfinite(stamp)) throw std::invalid_argument(std::string(who) + ": stamp is not finite");
    applyPending();
    if (stamp < last_stamp || (frame_size.area() > 0 && frame.size() != frame_size)) resetAll();
    frame_size = frame.size();
    last_stamp = stamp;
    ++frame_index;
    // Tracks reported lost last frame are gone now.
    for (std::size_t i = 0; i < tracks.size();) {
      if (tracks[i]->state == TrackState::kLost) {
        pool.push_back(std::move(tracks[i]));
        tracks.erase(tracks.begin() + static_cast<long>(i));
      } else {
        ++i;
      }
    }
  }

  Track& newTrack(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
    std::unique_ptr<Track> t;
    if (!pool.empty()) {
      t = std::move(pool.back());
      pool.pop_back();
      t->kcf.setParams(params);
      t->looming.setParams(params.looming_rate_noise, params.looming_from_pixels);
    } else {
      t = std::make_unique<Track>(params);
    }
    t->kcf.init(frame, box);
    t->id = next_id++;
    t->state = TrackState::kTracking;
    t->box = box;
    t->good_box = box;
    t->good_stamp = stamp;
    t->velocity = {0.0f, 0.0f};
    t->have_velocity = false;
    t->failures = 0;
    t->age = 0;
    t->result = KcfResult();
    t->result.box = box;
    t->result.peak = 1.0f;
    t->result.psr = KcfTracker::kConfidencePsrFull;
    t->result.confidence = 1.0f;
    t->result.model_updated = true;
    t->ref_peak = t->ref_psr = 0.0f;
    t->ref_count = 0;
    t->learn_gate = -1.0f;
    t->learning = true;
    t->looming.start(frame, stamp, box);
    t->contrast_ref = contrast.measure(frame, box);
    t->verified = true;
    t->watched = 0;
    t->probation = false;
    tracks.push_back(std::move(t));
    return *tracks.back();
  }

  // A track started by auto-initialisation: watched until it moves like an obstacle.
  Track& newAutoTrack(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
    Track& t = newTrack(frame, stamp, box);
    if (params.auto_init_verify_frames > 0 && params.auto_init_min_motion > 0.0) {
      t.verified = false;
      t.start_centre = centre(box);
      t.start_background = autoinit.backgroundMotion();
      t.start_log_size = 0.5f * std::log(std::max(1.0f, box.area()));
      t.max_image_motion = 0.0f;
    }
    return t;
  }

  void acceptGood(Track& t, const cv::Rect2f& box, double stamp) {
    const double dt = stamp - t.good_stamp;
    // Stamps microseconds apart (or a huge jump) give no usable velocity: a float overflow to
    // infinity here became a NaN box in predict() (fuzz_pipeline, test_robust_fuzz.cpp).
    if (dt > kMinVelocityDt) {
      const cv::Point2f v = (centre(box) - centre(t.good_box)) * static_cast<float>(1.0 / dt);
      if (std::isfinite(v.x) && std::isfinite(v.y)) {
        t.velocity = t.have_velocity ? (1.0f - kVelocitySmoothing) * t.velocity + kVelocitySmoothing * v : v;
        t.have_velocity = true;
      }
    }
    t.box = box;
    t.good_box = box;
    t.good_stamp = stamp;
    t.state = TrackState::kTracking;
    t.failures = 0;
  }

  cv::Rect2f predict(const Track& t, double stamp) const {
    cv::Point2f shift(0.0f, 0.0f);
    if (t.have_velocity) {
      shift = t.velocity * static_cast<float>(stamp - t.good_stamp);
      const float cap = kMaxPredictionBoxes * std::max(t.good_box.width, t.good_box.height);
      const float n = std::hypot(shift.x, shift.y);
      if (!std::isfinite(n)) {
        shift = cv::Point2f(0.0f, 0.0f);  // e.g. a stamp jump of years times a velocity
      } else if (n > cap) {
        shift *= cap / n;
      }
    }
    return clampCentre(centredAt(centre(t.good_box) + shift, t.good_box.size()), frame_size);
  }

  // One re-detection attempt; true when a candidate was accepted (the filter restarted).
  bool redetect(Track& t, const cv::Mat& frame, double stamp) {
    // The filter's own answer already failed this frame (step()); candidates are salient regions.
    const cv::Rect2f pred = predict(t, stamp);
    // The window grows while the re-detection fails (the object keeps moving) and never gets
    // too small for a tiny target (a few-pixel drone moves farther than its size per frame).
    const float grow = std::min(kMaxWindowGrowth, 1.0f + kWindowGrowthPerFailure * static_cast<float>(t.failures));
    const cv::Size2f search_size(std::max(kMinSearchBoxSide, pred.width * grow),
                                 std::max(kMinSearchBoxSide, pred.height * grow));
    const cv::Rect2f search_box = centredAt(centre(pred), search_size);
    const cv::Rect window = SaliencyDetector::searchWindow(frame_size, search_box, params.search_window_scale);
    candidates.clear();
    if (window.area() > 0) {
      const std::vector<SalientRegion>& regions = saliency.detectInWindow(frame, search_box);
      float best_score = 0.0f;
      for (const auto& r : regions) best_score = std::max(best_score, r.score);
      const float side = static_cast<float>(std::max(window.width, window.height));
      const float sigma_d = kDistanceSigma * side;
      const float last_area = std::max(1.0f, t.good_box.area());
      const float last_aspect = t.good_box.width / std::max(1.0f, t.good_box.height);
      for (const auto& r : regions) {
        if (!usableBox(r.box, frame_size)) continue;
        const cv::Point2f d = centre(r.box) - centre(pred);
        const float dist = std::exp(-(d.x * d.x + d.y * d.y) / (2.0f * sigma_d * sigma_d));
        const float la = 0.5f * std::log(std::max(1.0f, r.box.area()) / last_area);
        const float lr = std::log((r.box.width / std::max(1.0f, r.box.height)) / std::max(1e-3f, last_aspect));
        const float size = std::exp(-(la * la + 0.25f * lr * lr) / (2.0f * kSizeSigma * kSizeSigma));
        const float sal = best_score > 0.0f ? std::sqrt(std::max(0.0f, r.score) / best_score) : 0.0f;
        Candidate c;
        c.box = r.box;
        c.prior = sal * dist * size;
        c.region = &r;
        candidates.push_back(c);
      }
    }
    // Best priors first.
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.prior > b.prior; });
    const std::size_t verify =
        std::min<std::size_t>(candidates.size(), static_cast<std::size_t>(params.redetect_candidates));
    // A new region must match the model about as well as the target usually does (a background
    // patch or a passing bird correlates weakly but often above the tracking threshold).
    const float accept = acceptPeak(t);
    int best = -1;
    float best_final = 0.0f;
    KcfResult best_result, first_result;
    for (std::size_t i = 0; i < verify; ++i) {
      KcfResult r = t.kcf.evaluate(frame, candidates[i].box);
      if (i == 0) first_result = r;
      if (!(r.peak >= accept)) continue;
      const float final_score = r.peak * (0.5f + 0.5f * candidates[i].prior);
      if (final_score > best_final) {
        best_final = final_score;
        best = static_cast<int>(i);
        best_result = r;
      }
    }
    // The paper's re-detection trusts saliency alone. Verification against the model protects
    // from distractors but fails when the target's surroundings change (a drone crossing from
    // sky into a dark ground band: the model, learned on sky, answers 0.08-0.10 there against
    // 0.05-0.07 for clutter, below the relative test). So a candidate that is alone in the
    // window in the saliency sense (prior >= kSoloPrior, every other prior below kSoloMargin x
    // its own), is accepted on a weaker verification (redetect_solo_peak x peak_threshold) once
    // the ordinary verification has failed on an earlier frame. It bypasses the relative test
    // that keeps occluders and birds out, so it is a parameter (0 switches it off).
    if (best < 0 && params.redetect_solo_peak > 0.0 && t.failures > 0 && verify > 0 &&
        candidates[0].prior >= kSoloPrior &&
        (candidates.size() < 2 || candidates[1].prior < kSoloMargin * candidates[0].prior) &&
        first_result.peak >= static_cast<float>(params.redetect_solo_peak * params.peak_threshold)) {
      best = 0;
      best_result = first_result;
    }
    // A split: with room for more tracks, a clearly separated, strong salient region that is
    // not the accepted one becomes a new track (handled by the caller after the loop).
    if (params.max_obstacles > 1) {
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (static_cast<int>(i) == best || candidates[i].prior < 0.5f) continue;
        if (best >= 0 && iou(candidates[i].box, candidates[static_cast<std::size_t>(best)].box) > 0.0f) continue;
        spawn.push_back(candidates[i].box);
        break;
      }
    }
    if (best < 0) return false;
    const Candidate& c = candidates[static_cast<std::size_t>(best)];
    // The salient region's own box, so the box takes the object's current size and shape (the
    // paper's re-initialisation), grown from the region's bright core to the object's extent.
    cv::Rect2f box = extent.grow(frame, c.box, params.extent_contrast);
    {
      // The region's size and shape, within a band around the last good box: Otsu regions of a
      // few-pixel target are often only its hot core, and one bad segmentation must not
      // collapse or blow up the box.
      const cv::Size2f last = t.good_box.size();
      const cv::Size2f size(std::min(std::max(box.width, last.width / kMaxResize), last.width * kMaxResize),
                            std::min(std::max(box.height, last.height / kMaxResize), last.height * kMaxResize));
      box = centredAt(centre(box), size);
    }
    if (!usableBox(box, frame_size)) return false;
    t.kcf.init(frame, box);
    t.contrast_ref = contrast.measure(frame, box);
    t.looming.restart(frame, stamp, box);
    t.result = best_result;
    t.result.box = box;
    t.result.model_updated = true;
    acceptGood(t, box, stamp);
    return true;
  }

  // The peak a frame needs to count as good: the paper's absolute test plus a fraction of the
  // track's running mean peak (so that an occluder that still correlates with the background
  // context is not taken for the target).
  float goodPeak(const Track& t) const {
    float th = static_cast<float>(params.peak_threshold);
    if (t.ref_count >= kRefWarmup) th = std::max(th, static_cast<float>(params.relative_peak_threshold) * t.ref_peak);
    return th;
  }

  // The peak a re-detected answer needs (a salient region, or the filter finding the target
  // again on its own): the tracking test, and redetect_relative_threshold x the running mean.
  float acceptPeak(const Track& t) const {
    float accept = goodPeak(t);
    if (t.ref_count >= kRefWarmup) {
      accept = std::max(accept, static_cast<float>(params.redetect_relative_threshold) * t.ref_peak);
    }
    return accept;
  }

  // Filter settings for the next update. While tracking: learning gated by learn_threshold,
  // raised to the confidence of a response at learn_relative_threshold x the running mean peak
  // and PSR (LMCF's rule, Wang et al. CVPR 2017), capped so that a perfect history does not
  // freeze the model. While re-detecting: no learning at all (learning_rate 0), the filter only
  // searches around its last position.
  void configureFilter(Track& t, bool learn) {
    float gate = static_cast<float>(params.learn_threshold);
    if (t.ref_count >= kRefWarmup && params.learn_relative_threshold > 0.0) {
      const float k = static_cast<float>(params.learn_relative_threshold);
      gate = std::max(gate, std::min(kMaxLearnGate, KcfTracker::confidenceFrom(k * t.ref_peak, k * t.ref_psr)));
    }
    if (std::abs(gate - t.learn_gate) > 1e-3f || learn != t.learning) {
      Params p = params;
      p.learn_threshold = gate;
      if (!learn) p.learning_rate = 0.0;
      t.kcf.setParams(p);
      t.learn_gate = gate;
      t.learning = learn;
    }
  }

  static void updateRefs(Track& t, const KcfResult& r) {
    if (t.ref_count == 0) {
      t.ref_peak = r.peak;
      t.ref_psr = r.psr;
    } else {
      const float a = t.ref_count < kRefWarmup ? 1.0f / static_cast<float>(t.ref_count + 1) : kRefSmoothing;
      t.ref_peak += a * (r.peak - t.ref_peak);
      t.ref_psr += a * (r.psr - t.ref_psr);
    }
    ++t.ref_count;
  }

  float inFrameFraction(const cv::Rect2f& b) const {
    const cv::Rect2f f(0.0f, 0.0f, static_cast<float>(frame_size.width), static_cast<float>(frame_size.height));
    return b.area() > 0.0f ? (b & f).area() / b.area() : 0.0f;
  }

  void step(Track& t, const cv::Mat& frame, double stamp) {
    ++t.age;
    // The filter first, in both states (re-detecting: without learning).
    configureFilter(t, t.state == TrackState::kTracking);
    const KcfResult r = t.kcf.update(frame);
    t.result = r;
    // A box mostly outside the frame is an obstacle leaving the view: the filter's answer there
    // correlates mostly padding and background, so it does not count as tracking.
    const float needed = t.state == TrackState::kTracking ? goodPeak(t) : acceptPeak(t);
    if (r.peak >= needed && usableBox(r.box, frame_size) && inFrameFraction(r.box) >= kMinInFrame) {
      updateRefs(t, r);
      t.looming.track(frame, stamp, r.box);
      acceptGood(t, r.box, stamp);
      // A peak on a box that no longer holds the contrasted object it started on is the filter
      // following the background (target_contrast.h): reported as no better than re-detecting.
      if (TargetContrast::lost(t.contrast_ref, contrast.measure(frame, r.box))) {
        t.result.confidence = std::min(t.result.confidence, static_cast<float>(params.learn_threshold));
      }
      return;
    }
    t.state = TrackState::kRedetecting;
    // Salient regions around the prediction (also on the frame where the peak fell).
    if (redetect(t, frame, stamp)) return;
    ++t.failures;
    t.box = predict(t, stamp);
    t.result.confidence = std::min(t.result.confidence, static_cast<float>(params.learn_threshold));
    t.result.model_updated = false;
    if (t.failures > params.max_redetect_failures) {
      t.state = TrackState::kLost;
      t.result.confidence = 0.0f;
    } else {
      t.state = TrackState::kRedetecting;
    }
  }

  bool overlapsTrack(const cv::Rect2f& b, float max_iou) const {
    for (const auto& t : tracks) {
      if (t->state == TrackState::kLost) continue;
      if (iou(b, t->box) > max_iou || t->box.contains(centre(b)) || b.contains(centre(t->box))) return true;
    }
    return false;
  }

  int activeTracks() const {
    int n = 0;
    for (const auto& t : tracks) n += t->state != TrackState::kLost && !t->probation ? 1 : 0;
    return n;
  }

  void mergeTracks() {
    for (std::size_t i = 0; i < tracks.size(); ++i) {
      for (std::size_t j = i + 1; j < tracks.size();) {
        Track& a = *tracks[i];
        Track& b = *tracks[j];
        if (a.state != TrackState::kLost && b.state != TrackState::kLost &&
            iou(a.box, b.box) > params.merge_iou) {
          // Keep the one in the better state, then the older one.
          const bool keep_a = a.probation != b.probation          ? b.probation
                              : stateRank(a.state) != stateRank(b.state) ? stateRank(a.state) < stateRank(b.state)
                                                                         : a.age >= b.age;
          const std::size_t drop = keep_a ? j : i;
          pool.push_back(std::move(tracks[drop]));
          tracks.erase(tracks.begin() + static_cast<long>(drop));
          if (!keep_a) {
            j = i + 1;  // tracks[i] is now another track: recheck from its successor
            continue;
          }
        } else {
          ++j;
        }
      }
    }
  }

  // Auto-initialisation confirms a candidate from a few frames of evidence, and sometimes
  // confirms a scene object (a building in a panning view, a changing digit of the camera's
  // on-screen display); with one track allowed, such a track would hold the slot for good. So an
  // auto-started track is verified over a longer time with a motion test like the
  // confirmation's: it is an obstacle once its box has moved from where it started against the
  // background (AutoInitializer::backgroundMotion) by 2 x auto_init_min_motion plus half the
  // background's own displacement, and either as far in the image or (a target the camera keeps
  // in view) a little, with pixels that change; or once it has grown by auto_init_min_growth in
  // ln sqrt(area).
  // While a track is unverified the AutoInitializer keeps running, and a candidate it confirms
  // elsewhere becomes a challenger: tracked and verified the same way, but not reported. A
  // challenger that passes replaces a track still unverified after auto_init_verify_frames
  // (settleChallenge). A verified track is never replaced; an unverified one is replaced only by
  // a challenger that has proved itself a mover, so an obstacle on a collision course, which
  // neither moves nor grows much at first, is not given up for a candidate that has not proved
  // more (an auto-started obstacle that hovers in a still view never verifies and would give way
  // to a mover). While a track is unverified the AutoInitializer costs what it costs while
  // searching (and allocates as it does: the feature tracks of background_motion.h).
  void verify(Track& t) {
    if (t.verified || t.state == TrackState::kLost) return;
    if (params.auto_init_verify_frames <= 0 || params.auto_init_min_motion <= 0.0) {
      t.verified = true;  // switched off since the track started
      return;
    }
    ++t.watched;
    // On the camera's on-screen display: never an obstacle, however it seems to move.
    if (autoinit.overlayShare(t.box) >= AutoInitializer::kOverlayShare) return;
    const cv::Point2d bg_d = autoinit.backgroundMotion() - t.start_background;
    const cv::Point2f bg(static_cast<float>(bg_d.x), static_cast<float>(bg_d.y));
    const cv::Point2f in_image = centre(t.box) - t.start_centre;
    const float image_motion = std::hypot(in_image.x, in_image.y);
    const float bg_motion = std::hypot(bg.x, bg.y);
    const float own_motion = std::hypot(in_image.x - bg.x, in_image.y - bg.y);
    t.max_image_motion = std::max(t.max_image_motion, image_motion);
    // Twice the confirmation's distance, whatever the size (the filter's box does not fluctuate
    // with the segmentation as a candidate's region does), plus a share of the background's own
    // displacement: the global estimate lags a fast pan (by about half on antiuav_ir_04's pan over
    // sky and a tree line) and a near object moves unlike the distant background (parallax), so
    // a scene object seems to move against the background in proportion to the pan.
    const float need = 2.0f * static_cast<float>(params.auto_init_min_motion) + kVerifyPanShare * bg_motion;
    // Moved against the background, and in the image too, or (a target the camera keeps in view)
    // at least a little in the image with pixels that change: an overlay is pixel-locked.
    const bool moved = own_motion >= need &&
                       (image_motion >= need || (t.max_image_motion >= kVerifyMinImageMotion &&
                                                 autoinit.stillShare(t.box) < kStillShare));
    const float growth = 0.5f * std::log(std::max(1.0f, t.box.area())) - t.start_log_size;
    const bool grew = params.auto_init_min_growth > 0.0 && growth >= static_cast<float>(params.auto_init_min_growth);
    if (moved || grew) t.verified = true;
  }

  // The unverified track (not a challenger) watched longest past auto_init_verify_frames, or none.
  Track* replaceableTrack() {
    Track* best = nullptr;
    for (auto& t : tracks) {
      if (t->verified || t->probation || t->state == TrackState::kLost ||
          t->watched < params.auto_init_verify_frames) {
        continue;
      }
      if (best == nullptr || t->watched > best->watched) best = t.get();
    }
    return best;
  }

  bool anyUnverified() const {
    for (const auto& t : tracks) {
      if (!t->verified && !t->probation && t->state != TrackState::kLost) return true;
    }
    return false;
  }

  Track* challenger() {
    for (auto& t : tracks) {
      if (t->probation) return t.get();
    }
    return nullptr;
  }

  void removeTrack(const Track* victim) {
    for (auto& t : tracks) {
      if (t.get() != victim) continue;
      std::swap(t, tracks.back());
      pool.push_back(std::move(tracks.back()));
      tracks.pop_back();
      return;
    }
  }

  // A challenger that proved itself a mover takes the place of the unverified track; one that
  // did not within twice the verification time, or was lost, is dropped.
  void settleChallenge() {
    Track* c = challenger();
    if (c == nullptr) return;
    if (c->state == TrackState::kLost || (!c->verified && c->watched > 2 * params.auto_init_verify_frames)) {
      removeTrack(c);
      return;
    }
    if (activeTracks() < params.max_obstacles) {
      c->probation = false;  // the slot became free
      return;
    }
    if (!c->verified) return;
    if (Track* stale = replaceableTrack()) {
      removeTrack(stale);
      c = challenger();
      c->probation = false;
    }
  }

  void search(const cv::Mat& frame, double stamp) {
    const bool full = activeTracks() >= params.max_obstacles;
    if (full && !anyUnverified()) {
      if (Track* c = challenger()) removeTrack(c);
      if (!autoinit_fresh) {
        autoinit.reset();
        autoinit_fresh = true;
      }
      return;
    }
    if ((frame_index - 1) % params.detection_interval != 0) return;
    autoinit_fresh = false;
    const std::vector<SalientRegion>& found = autoinit.update(frame, stamp);
    for (auto& t : tracks) verify(*t);
    settleChallenge();
    for (const auto& r : found) {
      if (!usableBox(r.box, frame_size) || overlapsTrack(r.box, kSpawnMaxIou)) continue;
      if (activeTracks() < params.max_obstacles) {
        newAutoTrack(frame, stamp, r.box);
      } else if (anyUnverified() && challenger() == nullptr) {
        newAutoTrack(frame, stamp, r.box).probation = true;
      }
    }
  }

  void spawnSplits(const cv::Mat& frame, double stamp) {
    for (const auto& b : spawn) {
      if (activeTracks() >= params.max_obstacles) break;
      if (!usableBox(b, frame_size) || overlapsTrack(b, kSpawnMaxIou)) continue;
      newTrack(frame, stamp, b);
    }
    spawn.clear();
  }

  void report() {
    // Best first (state, then age), stable. An insertion sort over the few tracks: std::stable_sort
    // takes a temporary buffer from the heap on every call (test_pipeline_memory).
    const auto before = [](const Track& a, const Track& b) {
      const int ra = stateRank(a.state), rb = stateRank(b.state);
      if (ra != rb) return ra < rb;
      return a.age > b.age;
    };
    for (std::size_t i = 1; i < tracks.size(); ++i) {
      for (std::size_t j = i; j > 0 && before(*tracks[j], *tracks[j - 1]); --j) std::swap(tracks[j], tracks[j - 1]);
    }
    out.clear();
    for (const auto& t : tracks) {
      if (t->probation) continue;
      Obstacle o;
      o.id = t->id;
      o.box = t->box;
      o.confidence = std::min(1.0f, std::max(0.0f, t->result.confidence));
      o.confirmed = t->verified;
      if (!o.confirmed) o.confidence = std::min(o.confidence, kUnconfirmedConfidenceCap);
      o.peak = t->result.peak;
      o.psr = t->result.psr;
      o.state = t->state;
      o.expansion_rate = t->looming.expansionRate();
      o.expansion_rate_sigma = t->looming.expansionRateSigma();
      o.time_to_contact = t->looming.timeToContact();
      o.time_to_contact_sigma = t->looming.timeToContactSigma();
      o.age = t->age;
      o.model_updated = t->result.model_updated;
      out.push_back(o);
    }
  }

  const std::vector<Obstacle>& run(const cv::Mat& frame, double stamp, const cv::Rect2f* start_box) {
    spawn.clear();
    for (auto& t : tracks) step(*t, frame, stamp);
    if (start_box != nullptr) {
      // Make room: the given box wins over the weakest track.
      while (activeTracks() >= params.max_obstacles && !tracks.empty()) {
        report();  // sorts best first
        pool.push_back(std::move(tracks.back()));
        tracks.pop_back();
      }
      newTrack(frame, stamp, *start_box);
    }
    spawnSplits(frame, stamp);
    if (params.max_obstacles > 1) mergeTracks();
    search(frame, stamp);
    report();
    return out;
  }

  static constexpr int kRefWarmup = 3;         // good frames before the relative tests apply
  static constexpr float kRefSmoothing = 0.2f;   // EMA weight of the newest good frame
  static constexpr float kMinInFrame = 0.5f;     // share of a tracked box inside the frame
  static constexpr float kMaxLearnGate = 0.75f;
};

Pipeline::Pipeline(const Params& params) : impl_(new Impl(params)) {}

Pipeline::~Pipeline() { delete impl_; }

void Pipeline::setParams(const Params& params) {
  impl_->pending = params;
  validate(impl_->pending);
  impl_->have_pending = true;
}

const Params& Pipeline::params() const { return impl_->have_pending ? impl_->pending : impl_->params; }

const std::vector<Obstacle>& Pipeline::process(const cv::Mat& frame, double stamp) {
  impl_->beginFrame(frame, stamp, "Pipeline::process");
  return impl_->run(frame, stamp, nullptr);
}

const std::vector<Obstacle>& Pipeline::startTrack(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
  impl_->checkFrame(frame, "Pipeline::startTrack");
  if (!usableBox(box, frame.size())) {
    throw std::invalid_argument("Pipeline::startTrack: the box must be finite, at least 1x1 px and overlap the frame");
  }
  impl_->beginFrame(frame, stamp, "Pipeline::startTrack");
  return impl_->run(frame, stamp, &box);
}

void Pipeline::reset() { impl_->resetAll(); }

void Pipeline::prepare(cv::Size size, int type) {
  Impl::checkFrame(cv::Mat(1, 1, type), "Pipeline::prepare");
  if (size.width < kWarmupMinSide || size.height < kWarmupMinSide) return;  // nothing worth warming
  const WarmupClip clip = makeWarmupClip(size, type);
  const int next_id = impl_->next_id;
  auto forget = [&] {  // as if never prepared: no track, the same next id, no frame size
    impl_->resetAll();
    impl_->next_id = next_id;
    impl_->frame_size = cv::Size();
  };
  try {
    impl_->resetAll();
    // Searching first (whole-frame saliency, auto-initialisation over a frame pair), then a
    // filter started on the box and tracking.
    process(clip.frames[0], 0.0);
    process(clip.frames[1], 1.0 / 30.0);
    impl_->resetAll();
    for (std::size_t i = 0; i < clip.frames.size(); ++i) {
      const double stamp = static_cast<double>(i) / 30.0;
      if (i == 0) {
        startTrack(clip.frames[0], stamp, clip.box);
      } else {
        process(clip.frames[i], stamp);
      }
    }
  } catch (...) {
    forget();
    throw;
  }
  forget();
}

TrackState Pipeline::state() const {
  const auto& out = impl_->out;
  return out.empty() ? TrackState::kSearching : out.front().state;
}

}  // namespace core
}  // namespace obstacle_tracker
