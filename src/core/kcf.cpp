// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Kernelized correlation filter, written from Henriques, Caseiro, Martins, Batista, "High-Speed
// Tracking with Kernelized Correlation Filters", TPAMI 37(3), 2015 (Gaussian kernel correlation,
// eq. 31; training, eq. 17; detection, eq. 22), with multi-channel fHOG + grey features
// (fhog.h), a fixed template size, a search over a few scales (as SAMF, Li & Zhu, ECCV-W 2014)
// and a confidence from the peak and the peak-to-sidelobe ratio (Bolme et al., CVPR 2010).
// This file: the tracking step (detection over the searched scales, refinement, learning) and the
// public API; the filter's parts are in kcf_filter.cpp and kcf_scale.cpp (kcf_impl.h).
#include "obstacle_tracker/core/kcf.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "kcf_impl.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/frame_check.h"

namespace obstacle_tracker {
namespace core {

using namespace kcf_detail;  // NOLINT(build/namespaces): the filter's own constants and helpers

namespace {

void checkBox(const cv::Mat& frame, const cv::Rect2f& box, const char* who) {
  if (!finiteBox(box)) throw std::invalid_argument(std::string(who) + ": box is not finite");
  if (!(box.width >= 1.0f) || !(box.height >= 1.0f)) {
    throw std::invalid_argument(std::string(who) + ": box must be at least 1x1 pixel");
  }
  const cv::Rect2f frame_rect(0.0f, 0.0f, static_cast<float>(frame.cols),
                              static_cast<float>(frame.rows));
  if ((box & frame_rect).area() <= 0.0f) {
    throw std::invalid_argument(std::string(who) + ": box does not overlap the frame");
  }
  // The filter window (box x (1 + padding)) is resampled with int pixel arithmetic: a box
  // billions of pixels wide overflowed it (test_robust_pipeline). A target can be larger
  // than the frame when very close, but not kMaxBoxToFrame times larger.
  constexpr float kMaxBoxToFrame = 16.0f;
  if (box.width > kMaxBoxToFrame * frame.cols || box.height > kMaxBoxToFrame * frame.rows) {
    throw std::invalid_argument(std::string(who) + ": box is more than 16 times the frame's size");
  }
}

}  // namespace

KcfTracker::KcfTracker(const TrackerParams& params) : impl_(new Impl(params)) {}

KcfTracker::~KcfTracker() { delete impl_; }

KcfTracker::KcfTracker(KcfTracker&& other) noexcept : impl_(other.impl_) { other.impl_ = nullptr; }

KcfTracker& KcfTracker::operator=(KcfTracker&& other) noexcept {
  if (this != &other) {
    delete impl_;
    impl_ = other.impl_;
    other.impl_ = nullptr;
  }
  return *this;
}

namespace {
void checkImpl(const void* impl) {
  if (impl == nullptr) throw std::logic_error("KcfTracker: used after being moved from");
}
}  // namespace

void KcfTracker::setParams(const TrackerParams& params) {
  if (impl_ == nullptr) {
    impl_ = new Impl(params);
    return;
  }
  impl_->setParams(params);
}

const TrackerParams& KcfTracker::params() const {
  checkImpl(impl_);
  return impl_->params;
}

void KcfTracker::init(const cv::Mat& frame, const cv::Rect2f& box) {
  checkImpl(impl_);
  requireFrame(frame, "KcfTracker::init");
  checkBox(frame, box, "KcfTracker::init");
  impl_->initialized = false;
  impl_->cached_valid = false;
  impl_->scale_votes = 0;
  impl_->buildGeometry(frame, box);
  impl_->train(frame, 1.0f);
  impl_->calibrateScales(frame);
  if (impl_->use_scale_filter) impl_->buildScaleFilter(frame);
  impl_->initialized = true;
}

namespace {

// One tracking step: detection over the searched scales, refinement, and (when allowed and the
// confidence reaches learn_threshold) learning. Leaves the refined features in m.zf for learn().
KcfResult trackStep(KcfTracker::Impl& m, const cv::Mat& frame, bool allow_learning) {
  const TrackerParams& p = m.params;

  // Detect at each scale; keep the best (non-unit scales slightly penalised).
  int best = 0;
  float best_score = -1e30f;
  std::array<cv::Point, kcf_detail::kMaxScaleCount> peak_locs;  // count <= kMaxScaleCount (params.h)
  const int count = static_cast<int>(m.scales.size());
  for (int i = 0; i < count; ++i) {
    const float s = m.scales[i];
    m.respond(frame, m.center, cv::Size2f(m.window.width * s, m.window.height * s), m.resp[i]);
    double mx;
    cv::minMaxLoc(m.resp[i], nullptr, &mx, nullptr, &peak_locs[i]);
    const float score = static_cast<float>(mx) * m.scale_calib[i] *
                        (std::abs(s - 1.0f) < 1e-6f ? 1.0f : static_cast<float>(p.scale_penalty));
    if (score > best_score) {
      best_score = score;
      best = i;
    }
  }
  if (count > 1) best = m.confirmScale(best);
  const cv::Point best_loc = peak_locs[best];
  const cv::Mat& r = m.resp[best];
  const float s = m.scales[best];
  KcfResult result;
  result.peak = r.at<float>(best_loc);
  result.psr = m.psrOf(r, best_loc, result.peak);
  result.confidence = confidenceOf(result.peak, result.psr);

  const cv::Point2f d = m.subCellPeak(r, best_loc);
  const cv::Size2f ws(m.window.width * s, m.window.height * s);
  m.center.x += d.x * m.cell * ws.width / m.tw;
  m.center.y += d.y * m.cell * ws.height / m.th;
  // Keep the centre on the frame so the window always sees it.
  m.center.x = std::min(std::max(m.center.x, 0.0f), static_cast<float>(frame.cols));
  m.center.y = std::min(std::max(m.center.y, 0.0f), static_cast<float>(frame.rows));

  // Scale, bounded so a drifting filter cannot blow the box up or shrink it to nothing, and kept
  // when the response is not trusted (an occluder or clutter must not resize the box).
  const float applied = m.applyScale(result.confidence >= p.learn_threshold ? s : 1.0f);
  result.scale_change = applied;

  // Refinement: features at the new centre (needed for training anyway) are correlated with the
  // model once more and the small residual offset is added. This removes most of the bias of the
  // cosine window towards zero motion (about 5 % of the shift) for the price of one kernel
  // correlation; the training sample is then off by the residual only (a few hundredths of a cell).
  const float zz = m.featuresSpectrum(frame, m.center, m.window, m.zf);
  m.gaussianCorrelation(m.model_xf, m.model_xx, m.zf, zz);
  m.kernelResponse(m.resp[0]);
  cv::Point loc;
  cv::minMaxLoc(m.resp[0], nullptr, nullptr, nullptr, &loc);
  const cv::Point2f residual = m.subCellPeak(m.resp[0], loc);
  if (std::abs(residual.x) <= 1.0f && std::abs(residual.y) <= 1.0f) {
    m.center.x += residual.x * m.cell * m.window.width / m.tw;
    m.center.y += residual.y * m.cell * m.window.height / m.th;
  }
  result.box = m.boxAt(m.center, m.target);

  m.cached_zz = zz;
  m.cached_valid = true;
  const bool learn =
      allow_learning && result.confidence >= p.learn_threshold && p.learning_rate > 0.0;
  if (learn) m.trainOnSpectrum(zz, static_cast<float>(p.learning_rate));

  // DSST scale filter at the new centre (only when the response is trusted).
  if (m.use_scale_filter && result.confidence >= p.learn_threshold) {
    const float f = m.applyScale(m.detectScale(frame));
    result.scale_change = f;
    result.box = m.boxAt(m.center, m.target);
    if (learn) m.trainScale(frame, kScaleLearningRate);
  }
  result.model_updated = learn;
  return result;
}

}  // namespace

KcfResult KcfTracker::update(const cv::Mat& frame) {
  checkImpl(impl_);
  requireFrame(frame, "KcfTracker::update");
  if (!impl_->initialized) throw std::logic_error("KcfTracker::update: not initialised");
  return trackStep(*impl_, frame, true);
}

void KcfTracker::shiftSearch(const cv::Point2f& offset) {
  checkImpl(impl_);
  if (!impl_->initialized) throw std::logic_error("KcfTracker::shiftSearch: not initialised");
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y)) return;
  impl_->center += offset;  // kept on the frame by the next step (trackStep clamps the centre)
}

void KcfTracker::setSizeTrend(int trend) {
  checkImpl(impl_);
  if (trend < -1 || trend > 1) throw std::invalid_argument("KcfTracker::setSizeTrend: trend must be -1, 0 or +1");
  impl_->size_trend = trend;
  impl_->have_size_trend = true;
}

KcfResult KcfTracker::detect(const cv::Mat& frame) {
  checkImpl(impl_);
  requireFrame(frame, "KcfTracker::detect");
  if (!impl_->initialized) throw std::logic_error("KcfTracker::detect: not initialised");
  return trackStep(*impl_, frame, false);
}

void KcfTracker::learn(const cv::Mat& frame) {
  checkImpl(impl_);
  requireFrame(frame, "KcfTracker::learn");
  if (!impl_->initialized) throw std::logic_error("KcfTracker::learn: not initialised");
  Impl& m = *impl_;
  const float eta = static_cast<float>(m.params.learning_rate);
  if (eta <= 0.0f) return;
  if (m.cached_valid) {
    m.trainOnSpectrum(m.cached_zz, eta);
  } else {
    m.train(frame, eta);
  }
  m.cached_valid = false;
  if (m.use_scale_filter) m.trainScale(frame, kScaleLearningRate);
}

KcfResult KcfTracker::evaluate(const cv::Mat& frame, const cv::Rect2f& candidate) {
  checkImpl(impl_);
  requireFrame(frame, "KcfTracker::evaluate");
  checkBox(frame, candidate, "KcfTracker::evaluate");
  if (!impl_->initialized) throw std::logic_error("KcfTracker::evaluate: not initialised");
  Impl& m = *impl_;
  const float s = std::sqrt(candidate.area() / m.target.area());
  const cv::Size2f ws(m.window.width * s, m.window.height * s);
  const cv::Point2f c = boxCentre(candidate);
  cv::Mat& r = m.resp[0];
  m.respond(frame, c, ws, r);
  double mx;
  cv::Point loc;
  cv::minMaxLoc(r, nullptr, &mx, nullptr, &loc);
  KcfResult result;
  result.peak = static_cast<float>(mx);
  result.psr = m.psrOf(r, loc, result.peak);
  result.confidence = confidenceOf(result.peak, result.psr);
  const cv::Point2f d = m.subCellPeak(r, loc);
  result.box = cv::Rect2f(candidate.x + d.x * m.cell * ws.width / m.tw,
                          candidate.y + d.y * m.cell * ws.height / m.th, candidate.width,
                          candidate.height);
  result.scale_change = s;
  result.model_updated = false;
  return result;
}

bool KcfTracker::initialized() const { return impl_ != nullptr && impl_->initialized; }

cv::Rect2f KcfTracker::box() const {
  if (!initialized()) return cv::Rect2f();
  return impl_->boxAt(impl_->center, impl_->target);
}

float KcfTracker::confidenceFrom(float peak, float psr) { return confidenceOf(peak, psr); }

cv::Size KcfTracker::templateCells() const {
  if (!initialized()) return cv::Size();
  return cv::Size(impl_->cols, impl_->rows);
}
}  // namespace core
}  // namespace obstacle_tracker
