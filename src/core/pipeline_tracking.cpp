// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Pipeline::Impl (pipeline_impl.h): one track's frame. The filter's answer is tested (peak against
// the paper's threshold and the track's running mean); a failed frame re-detects among the salient
// regions around the motion prediction, verified against the filter's model.
#include <algorithm>
#include <cmath>

#include "pipeline_impl.h"

namespace obstacle_tracker {
namespace core {

using namespace pipeline_detail;  // NOLINT(build/namespaces): the pipeline's own constants

void Pipeline::Impl::acceptGood(Track& t, const cv::Rect2f& box, double stamp) {
  const double dt = stamp - t.motion.good_stamp;
  // Stamps microseconds apart (or a huge jump) give no usable velocity: a float overflow to
  // infinity here would make a NaN box in predict() (fuzz_pipeline, test_robust_fuzz.cpp).
  if (dt > kMinVelocityDt) {
    const cv::Point2f v = (boxCentre(box) - boxCentre(t.motion.good_box)) * static_cast<float>(1.0 / dt);
    if (std::isfinite(v.x) && std::isfinite(v.y)) {
      t.motion.velocity = t.motion.have_velocity ? (1.0f - kVelocitySmoothing) * t.motion.velocity + kVelocitySmoothing * v : v;
      t.motion.have_velocity = true;
    }
  }
  t.status.box = box;
  t.motion.good_box = box;
  t.motion.good_stamp = stamp;
  t.status.state = TrackState::kTracking;
  t.status.failures = 0;
}

cv::Rect2f Pipeline::Impl::predict(const Track& t, double stamp) const {
  cv::Point2f shift(0.0f, 0.0f);
  if (t.motion.have_velocity) {
    shift = t.motion.velocity * static_cast<float>(stamp - t.motion.good_stamp);
    const float cap = kMaxPredictionBoxes * std::max(t.motion.good_box.width, t.motion.good_box.height);
    const float n = std::hypot(shift.x, shift.y);
    if (!std::isfinite(n)) {
      shift = cv::Point2f(0.0f, 0.0f);  // e.g. a stamp jump of years times a velocity
    } else if (n > cap) {
      shift *= cap / n;
    }
  }
  return clampCentre(boxCentredAt(boxCentre(t.motion.good_box) + shift, t.motion.good_box.size()), frame_size);
}

// One re-detection attempt; true when a candidate was accepted (the filter restarted). The
// filter's own answer already failed this frame (step()); candidates are salient regions.
bool Pipeline::Impl::redetect(Track& t, const cv::Mat& frame, double stamp) {
  gatherCandidates(t, frame, predict(t, stamp));
  KcfResult chosen;
  bool by_contrast = false;
  const int best = chooseCandidate(t, frame, chosen, by_contrast);
  // A split: with room for more tracks, a clearly separated, strong salient region that is
  // not the accepted one becomes a new track (handled by the caller after the loop).
  if (params.max_obstacles > 1) noteSplit(best);
  if (best < 0) return false;
  if (!restartOn(t, frame, stamp, candidates[static_cast<std::size_t>(best)].box, chosen)) return false;
  // Taken on contrast alone, the region is a new detection: an obstacle once it has moved like
  // one (verify()), as an auto-started track is; until then its confidence stays below 0.5. It
  // is handled as an auto-started track from then on (it may give way to a challenger, or be set
  // aside when it does not move).
  if (by_contrast) restartVerification(t);
  return true;
}

// The salient regions in the search window around the prediction `pred`, each with a prior from
// its saliency, its distance to the prediction and its size and aspect against the last good
// box; best priors first.
void Pipeline::Impl::gatherCandidates(const Track& t, const cv::Mat& frame, const cv::Rect2f& pred) {
  // The window grows while the re-detection fails (the object keeps moving) and never gets
  // too small for a tiny target (a few-pixel drone moves farther than its size per frame).
  const float grow = std::min(kMaxWindowGrowth, 1.0f + kWindowGrowthPerFailure * static_cast<float>(t.status.failures));
  const cv::Size2f search_size(std::max(kMinSearchBoxSide, pred.width * grow),
                               std::max(kMinSearchBoxSide, pred.height * grow));
  const cv::Rect2f search_box = boxCentredAt(boxCentre(pred), search_size);
  const cv::Rect window = SaliencyDetector::searchWindow(frame_size, search_box, params.search_window_scale);
  candidates.clear();
  if (window.area() > 0) {
    const std::vector<SalientRegion>& regions = saliency.detectInWindow(frame, search_box);
    float best_score = 0.0f;
    for (const auto& r : regions) best_score = std::max(best_score, r.score);
    const float side = static_cast<float>(std::max(window.width, window.height));
    const float sigma_d = kDistanceSigma * side;
    const float last_area = std::max(1.0f, t.motion.good_box.area());
    const float last_aspect = t.motion.good_box.width / std::max(1.0f, t.motion.good_box.height);
    for (const auto& r : regions) {
      if (!usableBox(r.box, frame_size)) continue;
      const cv::Point2f d = boxCentre(r.box) - boxCentre(pred);
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
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.prior > b.prior; });
}

// The candidate that verifies best against the filter's model (KcfTracker::evaluate), or, when
// the model has followed the background, the contrasted one, or the solo rule's; -1 when none.
// `chosen` is its verification; by_contrast tells whether the model was left out.
int Pipeline::Impl::chooseCandidate(Track& t, const cv::Mat& frame, KcfResult& chosen, bool& by_contrast) {
  const std::size_t verify =
      std::min<std::size_t>(candidates.size(), static_cast<std::size_t>(params.redetect_candidates));
  // A new region must match the model about as well as the target usually does (a background
  // patch or a passing bird correlates weakly but often above the tracking threshold).
  const float accept = acceptPeak(t);
  int best = -1;
  float best_final = 0.0f;
  KcfResult first_result;
  for (std::size_t i = 0; i < verify; ++i) {
    KcfResult r = t.kcf.evaluate(frame, candidates[i].box);
    if (i == 0) first_result = r;
    if (!(r.peak >= accept)) continue;
    const float final_score = r.peak * (0.5f + 0.5f * candidates[i].prior);
    if (final_score > best_final) {
      best_final = final_score;
      best = static_cast<int>(i);
      chosen = r;
    }
  }
  by_contrast = false;
  // Only with the verification on: without it, clutter taken on contrast would be confident.
  if (best < 0 && t.refs.lost_object && verificationOn()) {
    best = contrastedCandidate(t, frame, chosen);
    if (best >= 0) {
      by_contrast = true;
      return best;
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
  if (best < 0 && params.redetect_solo_peak > 0.0 && t.status.failures > 0 && verify > 0 &&
      candidates[0].prior >= kSoloPrior &&
      (candidates.size() < 2 || candidates[1].prior < kSoloMargin * candidates[0].prior) &&
      first_result.peak >= static_cast<float>(params.redetect_solo_peak * params.peak_threshold)) {
    best = 0;
    chosen = first_result;
  }
  return best;
}

// A model that has followed the background learned the background (the filter kept learning
// on the frames before the box's contrast told), and a target that flew on answers it no better
// than clutter: verification against it fails on the very frames that need a re-detection. What
// still tells the object is what the loss was measured with: the salient region with the best
// prior (saliency, distance to the prediction, size; at least kReacquireMinPrior, so that a thin
// pole far from where the object left is not taken) whose contrast (TargetContrast) is at least
// kReacquireContrastShare of the contrast the filter started on, and at least
// kReacquireMinContrast. Clutter passes that too (a mast's lattice, runway markings), so
// the caller reports the track as unverified until it moves like an obstacle.
int Pipeline::Impl::contrastedCandidate(Track& t, const cv::Mat& frame, KcfResult& chosen) {
  const float need = std::max(kReacquireMinContrast, kReacquireContrastShare * t.refs.contrast.ratio);
  const std::size_t considered =
      std::min<std::size_t>(candidates.size(), static_cast<std::size_t>(params.redetect_candidates));
  for (std::size_t i = 0; i < considered; ++i) {
    if (candidates[i].prior < kReacquireMinPrior) break;  // sorted: none of the rest is plausible
    if (contrast.measure(frame, candidates[i].box) < need) continue;
    chosen = t.kcf.evaluate(frame, candidates[i].box);
    return static_cast<int>(i);
  }
  return -1;
}

void Pipeline::Impl::noteSplit(int best) {
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (static_cast<int>(i) == best || candidates[i].prior < 0.5f) continue;
    if (best >= 0 && boxIou(candidates[i].box, candidates[static_cast<std::size_t>(best)].box) > 0.0f) continue;
    spawn.push_back(candidates[i].box);
    break;
  }
}

// The size a re-detected box takes, and how well each side is known then. Each side's logarithm
// is a small Kalman filter: the last good box's side, with the variance carried in
// Track::Motion::size_var grown by SizeFilter::kSizeNoise^2 per second since the start or the
// last re-detection (the object turns, approaches, recedes; the scale search between them is not
// counted as a measurement), is fused with the region's measured extent, whose error is
// kExtentErrorPx per side (kExtentErrorPx / side in ln units), by their inverse variances, and
// kept within 1/kMaxResize..kMaxResize x the last. A large object's extent is measured to a few
// per cent and re-sizes the box (the paper's re-initialisation on the new box); a few-pixel
// target's Otsu region is often only its hot core, and one segmentation must not collapse the
// box a given start or many re-detections have settled. The prior's variance is capped at
// kMaxSizeVariance: beyond it the clamp decides anyway, and a long gap cannot overflow it. A side
// the clamp limited keeps the fused variance (it slightly overstates what is known then).
Pipeline::Impl::RedetectedSize Pipeline::Impl::redetectedSize(const Track::Motion& motion, double stamp,
                                                              const cv::Size2f& measured) {
  const double drift_var =
      SizeFilter::kSizeNoise * SizeFilter::kSizeNoise * std::max(0.0, stamp - motion.size_stamp);
  const cv::Vec2f measured_var = extentVariance(measured);
  const cv::Size2f last = motion.good_box.size();
  RedetectedSize fused;
  for (int k = 0; k < 2; ++k) {
    const float last_side = std::max(1.0f, k == 0 ? last.width : last.height);
    const float measured_side = std::max(1.0f, k == 0 ? measured.width : measured.height);
    const float prior_var =
        static_cast<float>(std::min(kMaxSizeVariance, static_cast<double>(motion.size_var[k]) + drift_var));
    const float gain = prior_var / (prior_var + measured_var[k]);
    const float side = last_side * std::exp(gain * std::log(measured_side / last_side));
    fused.side[k] = std::min(std::max(side, last_side / kMaxResize), last_side * kMaxResize);
    fused.variance[k] = (1.0f - gain) * prior_var;
  }
  return fused;
}

// Restarts the filter on a re-detected region (the paper's re-initialisation on the new box).
bool Pipeline::Impl::restartOn(Track& t, const cv::Mat& frame, double stamp, const cv::Rect2f& region,
                               const KcfResult& verified_result) {
  // The salient region, grown from its bright core to the object's extent, gives the centre;
  // each side is the last box's fused with the region's extent (redetectedSize()).
  cv::Rect2f box = extent.grow(frame, region, params.extent_contrast);
  const RedetectedSize fused = redetectedSize(t.motion, stamp, box.size());
  box = boxCentredAt(boxCentre(box), cv::Size2f(fused.side[0], fused.side[1]));
  if (!usableBox(box, frame_size)) return false;
  t.motion.size_var = fused.variance;
  t.motion.size_stamp = stamp;
  t.kcf.init(frame, box);
  t.refs.contrast = contrast.read(frame, box);
  t.refs.lost_object = false;
  t.looming.restart(frame, stamp, box);
  t.result = verified_result;
  t.result.box = box;
  t.result.model_updated = true;
  acceptGood(t, box, stamp);
  return true;
}

// The peak a frame needs to count as good: the paper's absolute test plus a fraction of the
// track's running mean peak (so that an occluder that still correlates with the background
// context is not taken for the target).
float Pipeline::Impl::goodPeak(const Track& t) const {
  float th = static_cast<float>(params.peak_threshold);
  if (t.refs.count >= kRefWarmup) th = std::max(th, static_cast<float>(params.relative_peak_threshold) * t.refs.peak);
  return th;
}

// The peak a re-detected answer needs (a salient region, or the filter finding the target
// again on its own): the tracking test, and redetect_relative_threshold x the running mean.
float Pipeline::Impl::acceptPeak(const Track& t) const {
  float accept = goodPeak(t);
  if (t.refs.count >= kRefWarmup) {
    accept = std::max(accept, static_cast<float>(params.redetect_relative_threshold) * t.refs.peak);
  }
  return accept;
}

// Filter settings for the next update. While tracking: learning gated by learn_threshold,
// raised to the confidence of a response at learn_relative_threshold x the running mean peak
// and PSR (LMCF's rule, Wang et al. CVPR 2017), capped so that a perfect history does not
// freeze the model. While re-detecting: no learning at all (learning_rate 0), the filter only
// searches around its last position.
void Pipeline::Impl::configureFilter(Track& t, bool learn) {
  float gate = static_cast<float>(params.learn_threshold);
  if (t.refs.count >= kRefWarmup && params.learn_relative_threshold > 0.0) {
    const float k = static_cast<float>(params.learn_relative_threshold);
    gate = std::max(gate, std::min(kMaxLearnGate, KcfTracker::confidenceFrom(k * t.refs.peak, k * t.refs.psr)));
  }
  if (std::abs(gate - t.gate.learn_gate) > 1e-3f || learn != t.gate.learning) {
    TrackerParams p = params;  // the filter's group only
    p.learn_threshold = gate;
    if (!learn) p.learning_rate = 0.0;
    t.kcf.setParams(p);
    t.gate.learn_gate = gate;
    t.gate.learning = learn;
  }
}

void Pipeline::Impl::updateRefs(Track& t, const KcfResult& r) {
  if (t.refs.count == 0) {
    t.refs.peak = r.peak;
    t.refs.psr = r.psr;
  } else {
    const float a = t.refs.count < kRefWarmup ? 1.0f / static_cast<float>(t.refs.count + 1) : kRefSmoothing;
    t.refs.peak += a * (r.peak - t.refs.peak);
    t.refs.psr += a * (r.psr - t.refs.psr);
  }
  ++t.refs.count;
}

float Pipeline::Impl::inFrameFraction(const cv::Rect2f& b) const {
  const cv::Rect2f f(0.0f, 0.0f, static_cast<float>(frame_size.width), static_cast<float>(frame_size.height));
  return b.area() > 0.0f ? (b & f).area() / b.area() : 0.0f;
}

// Frames dropped before this one (a camera driver or a nodelet queue behind a busy tracker):
// the filter searches around its last box, and a target that kept moving through the missing
// frames may have left the part of the window the filter answers well (the cosine window, and
// the background the model learned around the target, pull the peak back). The track's velocity
// over the time beyond one usual interval (capped as the re-detection's prediction is) gives a
// second search centre; the model is correlated at both (KcfTracker::evaluate, no state change)
// and the search starts at the one that answers better. Constant velocity alone is a poor guess
// under a moving camera (the image velocity of a small target is mostly the camera's jitter),
// hence the comparison. At the usual frame rate nothing is evaluated or moved.
void Pipeline::Impl::bridgeDroppedFrames(Track& t, const cv::Mat& frame) {
  const double missed = frame_interval.dropped();
  if (!(missed > 0.0) || !t.motion.have_velocity || t.status.state != TrackState::kTracking) return;
  cv::Point2f shift = t.motion.velocity * static_cast<float>(missed);
  const cv::Rect2f box = t.kcf.box();
  const float cap = kMaxPredictionBoxes * std::max(box.width, box.height);
  const float n = std::hypot(shift.x, shift.y);
  if (!std::isfinite(n) || n < 1.0f) return;  // under a pixel: nothing to bridge
  if (n > cap) shift *= cap / n;
  const cv::Rect2f moved = clampCentre(boxCentredAt(boxCentre(box) + shift, box.size()), frame_size);
  if (!usableBox(moved, frame_size) || !usableBox(box, frame_size)) return;
  if (t.kcf.evaluate(frame, moved).peak <= t.kcf.evaluate(frame, box).peak) return;
  t.kcf.shiftSearch(boxCentre(moved) - boxCentre(box));
}

// A peak on a box that no longer holds the contrasted object it started on is the filter
// following the background (target_contrast.h): the frame fails like a low peak, the track
// re-detects around where the object was last seen, and the mark stays until the filter
// restarts or an answer is accepted again.
bool Pipeline::Impl::lostObject(Track& t, const cv::Mat& frame, const cv::Rect2f& box) {
  // lost() tests this too; here it spares the measurement on a track that has nothing to lose.
  if (!TargetContrast::checkable(t.refs.contrast)) return false;
  if (!TargetContrast::lost(t.refs.contrast, contrast.read(frame, box))) return false;
  t.refs.lost_object = true;
  return true;
}

void Pipeline::Impl::step(Track& t, const cv::Mat& frame, double stamp) {
  ++t.status.age;
  bridgeDroppedFrames(t, frame);
  // The filter first, in both states (re-detecting: without learning).
  configureFilter(t, t.status.state == TrackState::kTracking);
  t.kcf.setSizeTrend(t.looming.sizeTrend());
  const KcfResult r = t.kcf.update(frame);
  t.result = r;
  // A box mostly outside the frame is an obstacle leaving the view: the filter's answer there
  // correlates mostly padding and background, so it does not count as tracking.
  const float needed = t.status.state == TrackState::kTracking ? goodPeak(t) : acceptPeak(t);
  const bool usable = usableBox(r.box, frame_size);
  // Checked whatever the peak: a low peak on a box that lost the object also marks the model.
  const bool lost_object = usable && lostObject(t, frame, r.box);
  if (r.peak >= needed && usable && inFrameFraction(r.box) >= kMinInFrame && !lost_object) {
    t.refs.lost_object = false;  // the model found the object again on its own
    updateRefs(t, r);
    t.looming.track(frame, stamp, r.box);
    acceptGood(t, r.box, stamp);
    return;
  }
  t.status.state = TrackState::kRedetecting;
  // Salient regions around the prediction (also on the frame where the peak fell).
  if (redetect(t, frame, stamp)) return;
  ++t.status.failures;
  t.status.box = predict(t, stamp);
  t.result.confidence = std::min(t.result.confidence, static_cast<float>(params.learn_threshold));
  t.result.model_updated = false;
  if (t.status.failures > params.max_redetect_failures) {
    t.status.state = TrackState::kLost;
    t.result.confidence = 0.0f;
  } else {
    t.status.state = TrackState::kRedetecting;
  }
}

}  // namespace core
}  // namespace obstacle_tracker
