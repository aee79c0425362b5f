// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Pipeline::Impl (pipeline_impl.h): tracks among themselves. Auto-initialisation while there is
// room, verification of auto-started tracks (and their challengers), merges and splits.
#include <algorithm>
#include <cmath>

#include "pipeline_impl.h"

namespace obstacle_tracker {
namespace core {

using namespace pipeline_detail;  // NOLINT(build/namespaces): the pipeline's own constants

namespace {

// Two boxes on the same thing: IoU above max_iou, or either holds the other's centre.
bool sameThing(const cv::Rect2f& a, const cv::Rect2f& b, float max_iou) {
  return boxIou(a, b) > max_iou || a.contains(boxCentre(b)) || b.contains(boxCentre(a));
}

}  // namespace

bool Pipeline::Impl::overlapsTrack(const cv::Rect2f& b, float max_iou) const {
  for (const auto& t : tracks) {
    if (t->status.state != TrackState::kLost && sameThing(b, t->status.box, max_iou)) return true;
  }
  return false;
}

int Pipeline::Impl::activeTracks() const {
  int n = 0;
  for (const auto& t : tracks) n += t->status.state != TrackState::kLost && !t->status.probation ? 1 : 0;
  return n;
}

void Pipeline::Impl::mergeTracks() {
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    for (std::size_t j = i + 1; j < tracks.size();) {
      const Track::Status& a = tracks[i]->status;
      const Track::Status& b = tracks[j]->status;
      if (a.state != TrackState::kLost && b.state != TrackState::kLost && boxIou(a.box, b.box) > params.merge_iou) {
        // Keep the one in the better state, then the older one.
        const bool keep_a = a.probation != b.probation                     ? b.probation
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
// ln sqrt(area) while its pixels grow steadily, away from the frame's edge. A track re-acquired on
// contrast alone (pipeline_tracking.cpp, contrastedCandidate) is verified the same way.
// While a track is unverified the AutoInitializer keeps running, and a candidate it confirms
// elsewhere becomes a challenger: tracked and verified the same way, but not reported. A
// challenger that passes replaces a track still unverified after auto_init_verify_frames
// (settleChallenge). A verified track is never replaced; an unverified one is replaced only by
// a challenger that has proved itself a mover, so an obstacle on a collision course, which
// neither moves nor grows much at first, is not given up for a candidate that has not proved
// more (an auto-started obstacle that hovers in a still view never verifies and would give way
// to a mover). A track started on persistence alone (provisional: no cue confirmed it) gives
// way at once to any candidate a cue confirms. While a track is unverified the AutoInitializer
// costs what it costs while searching (and allocates as it does: the feature tracks of
// background_motion.h).
void Pipeline::Impl::verify(Track& t) {
  if (t.verification.verified || t.verification.start_pending || t.status.state == TrackState::kLost) return;
  if (params.auto_init_verify_frames <= 0 || params.auto_init_min_motion <= 0.0) {
    t.verification.verified = true;  // switched off since the track started
    return;
  }
  ++t.verification.watched;
  // On the camera's on-screen display: never an obstacle, however it seems to move.
  if (autoinit.overlayShare(t.status.box) >= AutoInitializer::kOverlayShare) return;
  const cv::Point2d bg_d = autoinit.backgroundMotion() - t.verification.start_background;
  const cv::Point2f bg(static_cast<float>(bg_d.x), static_cast<float>(bg_d.y));
  const cv::Point2f in_image = boxCentre(t.status.box) - t.verification.start_centre;
  const float image_motion = std::hypot(in_image.x, in_image.y);
  const float bg_motion = std::hypot(bg.x, bg.y);
  const float own_motion = std::hypot(in_image.x - bg.x, in_image.y - bg.y);
  t.verification.max_image_motion = std::max(t.verification.max_image_motion, image_motion);
  // Twice the confirmation's distance, whatever the size (the filter's box does not fluctuate
  // with the segmentation as a candidate's region does), plus a share of the background's own
  // displacement: the global estimate lags a fast pan (by about half on antiuav_ir_04's pan over
  // sky and a tree line) and a near object moves unlike the distant background (parallax), so
  // a scene object seems to move against the background in proportion to the pan.
  // (auto_init_min_motion and kVerifyMinImageMotion are pixels of the front end's working frame.)
  const float px = static_cast<float>(autoinit.framePixelsPerWorkingPixel());
  const float need = 2.0f * px * static_cast<float>(params.auto_init_min_motion) + kVerifyPanShare * bg_motion;
  // Moved against the background, and in the image too, or (a target the camera keeps in view)
  // at least a little in the image with pixels that change: an overlay is pixel-locked.
  // A box on a piece of a line (a contrail behind the aircraft, a wire) cannot show motion along
  // the line (the aperture problem): the filter slides along it as the view drifts. Judged on
  // the mean over the watched frames: one frame's coherence of a faint trail dips under any bar.
  t.verification.coherence_sum += autoinit.lineCoherence(t.status.box);
  ++t.verification.coherence_checks;
  const bool line_like = t.verification.coherence_sum >= kVerifyMaxLineCoherence * t.verification.coherence_checks;
  const bool moved = own_motion >= need && !line_like &&
                     (image_motion >= need || (t.verification.max_image_motion >= px * kVerifyMinImageMotion &&
                                               autoinit.stillShare(t.status.box) < kVerifyStillShare));
  const float growth = 0.5f * std::log(std::max(1.0f, t.status.box.area())) - t.verification.start_log_size;
  // Growth is evidence only where it measures the object coming closer: while its own pixels
  // grow steadily (the looming estimator's size trend; the box's net change also holds the
  // re-sizes of re-detections, which jump), and away from the frame's edge, where the box may
  // hold only the visible part of a structure that enters the view as the camera turns
  // (boxNearFrameEdge).
  const bool grew = params.auto_init_min_growth > 0.0 && growth >= static_cast<float>(params.auto_init_min_growth) &&
                    t.looming.sizeTrend() > 0 && !boxNearFrameEdge(t.status.box, frame_size);
  if (moved || grew) t.verification.verified = true;
}

// The unverified track (not a challenger) watched longest past auto_init_verify_frames, or none.
Pipeline::Impl::Track* Pipeline::Impl::replaceableTrack() {
  Track* best = nullptr;
  for (auto& t : tracks) {
    if (t->verification.verified || t->status.probation || t->status.state == TrackState::kLost ||
        t->verification.watched < params.auto_init_verify_frames) {
      continue;
    }
    if (best == nullptr || t->verification.watched > best->verification.watched) best = t.get();
  }
  return best;
}

bool Pipeline::Impl::anyUnverified() const {
  for (const auto& t : tracks) {
    if (!t->verification.verified && !t->status.probation && t->status.state != TrackState::kLost) return true;
  }
  return false;
}

Pipeline::Impl::Track* Pipeline::Impl::challenger() {
  for (auto& t : tracks) {
    if (t->status.probation) return t.get();
  }
  return nullptr;
}

void Pipeline::Impl::removeTrack(const Track* victim) {
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
void Pipeline::Impl::settleChallenge() {
  Track* c = challenger();
  if (c == nullptr) return;
  if (c->status.state == TrackState::kLost || (!c->verification.verified && c->verification.watched > 2 * params.auto_init_verify_frames)) {
    removeTrack(c);
    return;
  }
  if (activeTracks() < params.max_obstacles) {
    c->status.probation = false;  // the slot became free
    return;
  }
  if (!c->verification.verified) return;
  if (Track* stale = replaceableTrack()) {
    removeTrack(stale);
    c = challenger();
    c->status.probation = false;
  }
}

void Pipeline::Impl::search(const cv::Mat& frame, double stamp) {
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
  for (auto& t : tracks) {
    placeVerificationStart(*t);
    verify(*t);
  }
  settleChallenge();
  for (const auto& r : found) {
    if (!usableBox(r.box, frame_size)) continue;
    if (overlapsTrack(r.box, kSpawnMaxIou)) {
      confirmProvisional(r.box);
      continue;
    }
    if (activeTracks() >= params.max_obstacles) {
      if (Track* p = provisionalTrack()) removeTrack(p);
    }
    if (activeTracks() < params.max_obstacles) {
      newAutoTrack(frame, stamp, r.box);
    } else if (anyUnverified() && challenger() == nullptr) {
      newAutoTrack(frame, stamp, r.box).status.probation = true;
    }
  }
  if (found.empty()) setAsideMotionlessTrack(frame);
  // Nothing confirmed and a free slot: the most persistent candidate, provisionally (the paper
  // starts on one frame's most salient region; persistence over 2 x auto_init_frames frames is
  // the multi-frame version of that rule). A target the camera follows, or one that hovers,
  // shows no motion cue and would otherwise get no box at all. It is reported unconfirmed
  // (confidence < 0.5) until verify() passes, so only with the verification on.
  SalientRegion r;
  if (params.auto_init_verify_frames > 0 && found.empty() && provisionalTrack() == nullptr &&
      activeTracks() < params.max_obstacles && autoinit.persistentRegion(frame, &r) && usableBox(r.box, frame_size) &&
      !overlapsTrack(r.box, kSpawnMaxIou)) {
    newAutoTrack(frame, stamp, r.box).verification.provisional = true;
  }
}

// An auto-started track that has not moved in the image (kVerifyMinImageMotion) in
// auto_init_verify_frames checks without being verified gives the next most persistent candidate
// its chance: a hot pixel, a lighthouse or a buoy is often more salient than a distant target and,
// under a still camera, nothing else tells it from a target that hovers. A track that moves in the
// image keeps its place (a target the camera follows verifies late), and so does one with no other
// candidate to try; the auto-initialiser brings the set-aside candidates back once all have had
// their chance (AutoInitializer::setAsidePersistent).
// The auto-initialiser's choice this frame was made before the mark, so the swap comes one
// detection frame later. The track is removed only when the persistence start in search() will
// take the next candidate's place (no other provisional track, the candidate not tracked yet).
void Pipeline::Impl::setAsideMotionlessTrack(const cv::Mat& frame) {
  if (challenger() != nullptr) return;  // a challenger that proves itself replaces it anyway
  Track* stale = replaceableTrack();
  if (stale == nullptr ||
      stale->verification.max_image_motion >= autoinit.framePixelsPerWorkingPixel() * kVerifyMinImageMotion)
    return;
  autoinit.setAsidePersistent(stale->status.box);
  SalientRegion next;
  const Track* provisional = provisionalTrack();
  if (autoinit.persistentRegion(frame, &next) && usableBox(next.box, frame_size) &&
      !overlapsTrack(next.box, kSpawnMaxIou) &&  // covers the stale track too: it is never lost
      (provisional == nullptr || provisional == stale)) {
    removeTrack(stale);
  }
}

// The provisional track (started on persistence alone, still unverified, not a challenger), or none.
Pipeline::Impl::Track* Pipeline::Impl::provisionalTrack() {
  for (auto& t : tracks) {
    if (t->verification.provisional && !t->verification.verified && !t->status.probation &&
        t->status.state != TrackState::kLost) {
      return t.get();
    }
  }
  return nullptr;
}

// A confirmed candidate on a provisional track: the track now stands on a cue.
void Pipeline::Impl::confirmProvisional(const cv::Rect2f& box) {
  for (auto& t : tracks) {
    if (t->verification.provisional && sameThing(box, t->status.box, kSpawnMaxIou)) t->verification.provisional = false;
  }
}

void Pipeline::Impl::spawnSplits(const cv::Mat& frame, double stamp) {
  for (const auto& b : spawn) {
    if (activeTracks() >= params.max_obstacles) break;
    if (!usableBox(b, frame_size) || overlapsTrack(b, kSpawnMaxIou)) continue;
    newTrack(frame, stamp, b);
  }
  spawn.clear();
}

}  // namespace core
}  // namespace obstacle_tracker
