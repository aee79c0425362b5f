// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The closed detection-tracking loop of Bharati et al. (T-IV 2018), extended to several obstacles
// and looming: frame bookkeeping, starting tracks, the frame's order of work (run) and the report.
// Design and per-frame states: pipeline_impl.h.
#include "obstacle_tracker/core/pipeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "obstacle_tracker/core/frame_check.h"
#include "obstacle_tracker/core/warmup.h"
#include "pipeline_impl.h"

namespace obstacle_tracker {
namespace core {

using namespace pipeline_detail;  // NOLINT(build/namespaces): the pipeline's own constants

namespace {

// A new track's answer on its first frame: the training sample itself (full peak and PSR).
KcfResult firstAnswer(const cv::Rect2f& box) {
  KcfResult r;
  r.box = box;
  r.peak = 1.0f;
  r.psr = KcfTracker::kConfidencePsrFull;
  r.confidence = 1.0f;
  r.model_updated = true;
  return r;
}

}  // namespace

void Pipeline::Impl::resetAll() {
  while (!tracks.empty()) {
    pool.push_back(std::move(tracks.back()));
    tracks.pop_back();
  }
  autoinit.reset();
  autoinit_fresh = true;
  out.clear();
  last_stamp = -std::numeric_limits<double>::infinity();
  frame_interval.reset();
  frame_index = 0;
}

void Pipeline::Impl::applyPending() {
  if (!have_pending) return;
  params = pending;
  have_pending = false;
  saliency.setParams(params);
  autoinit.setParams(params);
  for (auto& t : tracks) {
    t->kcf.setParams(params);
    t->gate.learn_gate = -1.0f;  // the filter has the plain params now: configureFilter sets its gate again
    t->looming.setParams(params.looming_rate_noise, params.looming_from_pixels);
  }
  for (auto& t : pool) t->kcf.setParams(params);
  // The surplus of a smaller max_obstacles goes from the back; a challenger is not one of the
  // max_obstacles tracks and stays.
  int kept = 0;
  for (const auto& t : tracks) kept += t->status.probation ? 0 : 1;
  for (std::size_t i = tracks.size(); i-- > 0 && kept > params.max_obstacles;) {
    if (tracks[i]->status.probation) continue;
    pool.push_back(std::move(tracks[i]));
    tracks.erase(tracks.begin() + static_cast<long>(i));
    --kept;
  }
}

// Frame bookkeeping shared by process() and startTrack().
void Pipeline::Impl::beginFrame(const cv::Mat& frame, double stamp, const char* who) {
  requireFrame(frame, who);
  if (!std::isfinite(stamp)) throw std::invalid_argument(std::string(who) + ": stamp is not finite");
  applyPending();
  if (stamp < last_stamp || (frame_size.area() > 0 && frame.size() != frame_size)) resetAll();
  frame_size = frame.size();
  last_stamp = stamp;
  frame_interval.add(stamp);
  ++frame_index;
  // Tracks reported lost last frame are gone now.
  for (std::size_t i = 0; i < tracks.size();) {
    if (tracks[i]->status.state == TrackState::kLost) {
      pool.push_back(std::move(tracks[i]));
      tracks.erase(tracks.begin() + static_cast<long>(i));
    } else {
      ++i;
    }
  }
}

// given: the box is the caller's (ground truth, an operator's); otherwise a detected region, its
// sides known to the segmentation's error (redetectedSize()).
Pipeline::Impl::Track& Pipeline::Impl::newTrack(const cv::Mat& frame, double stamp, const cv::Rect2f& box, bool given) {
  std::unique_ptr<Track> t;
  if (!pool.empty()) {
    t = std::move(pool.back());
    pool.pop_back();
    t->kcf.setParams(params);
    t->looming.setParams(params.looming_rate_noise, params.looming_from_pixels);
  } else {
    t = std::make_unique<Track>(params, params);  // the filter's and the loop's groups
  }
  t->kcf.init(frame, box);
  t->status = Track::Status{next_id++, TrackState::kTracking, box};
  t->motion = Track::Motion{box, stamp};
  t->motion.size_var = given ? cv::Vec2f(kGivenBoxSigma * kGivenBoxSigma, kGivenBoxSigma * kGivenBoxSigma)
                             : extentVariance(box.size());
  t->motion.size_stamp = stamp;
  t->result = firstAnswer(box);
  t->gate = Track::FilterGate();
  t->looming.start(frame, stamp, box);
  t->refs = Track::References{contrast.read(frame, box)};
  t->verification = Track::Verification();
  tracks.push_back(std::move(t));
  return *tracks.back();
}

// A track started by auto-initialisation: watched until it moves like an obstacle.
Pipeline::Impl::Track& Pipeline::Impl::newAutoTrack(const cv::Mat& frame, double stamp, const cv::Rect2f& box) {
  Track& t = newTrack(frame, stamp, box);
  beginVerification(t, box);
  return t;
}

// The track on box is not an obstacle until verify() has seen it move (or grow) like one; with
// the verification switched off it is at once.
void Pipeline::Impl::beginVerification(Track& t, const cv::Rect2f& box) {
  t.verification = Track::Verification();
  if (!verificationOn()) return;
  t.verification.verified = false;
  setVerificationStart(t, box);
}

// Where verify() measures the track's motion and growth from: box, and the background's motion
// so far.
void Pipeline::Impl::setVerificationStart(Track& t, const cv::Rect2f& box) {
  t.verification.start_centre = boxCentre(box);
  t.verification.start_background = autoinit.backgroundMotion();
  t.verification.start_log_size = 0.5f * std::log(std::max(1.0f, box.area()));
}

// A track re-acquired on contrast alone (step()): unverified again. Its start is placed at the
// next auto-initialisation frame (placeVerificationStart), where the background's motion up to
// that frame is known. A track that was already unverified keeps its count of checks and its
// provisional mark (re-acquisition must not reset its turn to give way), only its start moves,
// the box having jumped.
void Pipeline::Impl::restartVerification(Track& t) {
  if (t.verification.verified) {
    t.verification = Track::Verification();
    t.verification.verified = false;
  }
  t.verification.start_pending = true;
}

void Pipeline::Impl::placeVerificationStart(Track& t) {
  if (!t.verification.start_pending) return;
  t.verification.start_pending = false;
  setVerificationStart(t, t.status.box);
}

void Pipeline::Impl::report() {
  // Best first (state, then age), stable. An insertion sort over the few tracks: std::stable_sort
  // takes a temporary buffer from the heap on every call (test_pipeline_memory).
  const auto before = [](const Track& a, const Track& b) {
    const int ra = stateRank(a.status.state), rb = stateRank(b.status.state);
    if (ra != rb) return ra < rb;
    return a.status.age > b.status.age;
  };
  for (std::size_t i = 1; i < tracks.size(); ++i) {
    for (std::size_t j = i; j > 0 && before(*tracks[j], *tracks[j - 1]); --j) std::swap(tracks[j], tracks[j - 1]);
  }
  out.clear();
  for (const auto& t : tracks) {
    if (t->status.probation) continue;
    Obstacle o;
    o.id = t->status.id;
    o.box = t->status.box;
    o.confidence = std::min(1.0f, std::max(0.0f, t->result.confidence));
    o.confirmed = t->verification.verified;
    if (!o.confirmed) o.confidence = std::min(o.confidence, kUnconfirmedConfidenceCap);
    o.peak = t->result.peak;
    o.psr = t->result.psr;
    o.state = t->status.state;
    o.expansion_rate = t->looming.expansionRate();
    o.expansion_rate_sigma = t->looming.expansionRateSigma();
    o.time_to_contact = t->looming.timeToContact();
    o.time_to_contact_sigma = t->looming.timeToContactSigma();
    o.age = t->status.age;
    o.model_updated = t->result.model_updated;
    out.push_back(o);
  }
}

const std::vector<Obstacle>& Pipeline::Impl::run(const cv::Mat& frame, double stamp, const cv::Rect2f* start_box) {
  spawn.clear();
  for (auto& t : tracks) step(*t, frame, stamp);
  if (start_box != nullptr) {
    // Make room: the given box wins over the weakest track.
    while (activeTracks() >= params.max_obstacles && !tracks.empty()) {
      report();  // sorts best first
      pool.push_back(std::move(tracks.back()));
      tracks.pop_back();
    }
    newTrack(frame, stamp, *start_box, /*given=*/true);
  }
  spawnSplits(frame, stamp);
  if (params.max_obstacles > 1) mergeTracks();
  search(frame, stamp);
  report();
  return out;
}


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
  requireFrame(frame, "Pipeline::startTrack");
  if (!usableBox(box, frame.size())) {
    throw std::invalid_argument("Pipeline::startTrack: the box must be finite, at least 1x1 px and overlap the frame");
  }
  impl_->beginFrame(frame, stamp, "Pipeline::startTrack");
  return impl_->run(frame, stamp, &box);
}

void Pipeline::reset() { impl_->resetAll(); }

void Pipeline::prepare(cv::Size size, int type) {
  requireFrame(cv::Mat(1, 1, type), "Pipeline::prepare");
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
