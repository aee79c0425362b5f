// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// KcfTracker::Impl (kcf_impl.h): the scale search's calibration and the DSST 1-D scale filter
// (Danelljan et al., BMVC 2014).
#include <algorithm>
#include <cmath>
#include <string_view>

#include <opencv2/imgproc.hpp>

#include "kcf_impl.h"
#include "obstacle_tracker/core/portable_math.h"

namespace obstacle_tracker {
namespace core {

using namespace kcf_detail;  // NOLINT(build/namespaces): the filter's own constants and helpers

// Scale samples at centre c around target size t: column n holds the windowed fHOG features of
// the box t * a^(n - (S-1)/2), resized to the scale model size (DSST, sec. 3).
void KcfTracker::Impl::scaleSamples(const cv::Mat& frame, cv::Point2f c, cv::Size2f t) {
  for (int n = 0; n < scale_n; ++n) {
    const float f = dsst_factors[n];
    sampler.sample(frame, c, cv::Size2f(t.width * f, t.height * f), sm_w, sm_h, scale_patch);
    fhog.compute(scale_patch, cell, scale_feat);
    const float* src = scale_feat.ptr<float>();
    const float w = scale_window[n];
    for (int d = 0; d < scale_dim; ++d) scale_x.at<float>(d, n) = src[d] * w;
  }
  scale_fft.forwardEachRow(scale_x, scale_xf);
}

// Trains the scale filter on samples at the current centre and size (rate eta; 1 = replace).
void KcfTracker::Impl::trainScale(const cv::Mat& frame, float eta) {
  scaleSamples(frame, center, target);
  const float* g = scale_yf.ptr<float>();
  float* den = scale_new_den.ptr<float>();
  std::fill(den, den + scale_n, 0.0f);
  for (int d = 0; d < scale_dim; ++d) {
    const float* xf = scale_xf.ptr<float>(d);
    float* num = scale_num.ptr<float>(d);
    for (int n = 0; n < scale_n; ++n) {
      const float xr = xf[2 * n], xi = xf[2 * n + 1];
      // G * conj(F)
      const float nr = g[2 * n] * xr + g[2 * n + 1] * xi;
      const float ni = g[2 * n + 1] * xr - g[2 * n] * xi;
      num[2 * n] = eta >= 1.0f ? nr : (1.0f - eta) * num[2 * n] + eta * nr;
      num[2 * n + 1] = eta >= 1.0f ? ni : (1.0f - eta) * num[2 * n + 1] + eta * ni;
      den[n] += xr * xr + xi * xi;
    }
  }
  float* model_den = scale_den.ptr<float>();
  for (int n = 0; n < scale_n; ++n) {
    model_den[n] = eta >= 1.0f ? den[n] : (1.0f - eta) * model_den[n] + eta * den[n];
  }
}

// Scale factor (relative to the current size) that the scale filter finds at the centre.
float KcfTracker::Impl::detectScale(const cv::Mat& frame) {
  scaleSamples(frame, center, target);
  float* rf = scale_resp_f.ptr<float>();
  std::fill(rf, rf + 2 * scale_n, 0.0f);
  for (int d = 0; d < scale_dim; ++d) {
    const float* zf_row = scale_xf.ptr<float>(d);
    const float* num = scale_num.ptr<float>(d);
    for (int n = 0; n < scale_n; ++n) {
      rf[2 * n] += num[2 * n] * zf_row[2 * n] - num[2 * n + 1] * zf_row[2 * n + 1];
      rf[2 * n + 1] += num[2 * n] * zf_row[2 * n + 1] + num[2 * n + 1] * zf_row[2 * n];
    }
  }
  const float* den = scale_den.ptr<float>();
  for (int n = 0; n < scale_n; ++n) {
    const float inv = 1.0f / (den[n] + kScaleLambda);
    rf[2 * n] *= inv;
    rf[2 * n + 1] *= inv;
  }
  scale_fft.inverse(scale_resp_f, scale_resp);
  const float* r = scale_resp.ptr<float>();
  int best = 0;
  for (int n = 1; n < scale_n; ++n) {
    if (r[n] > r[best]) best = n;
  }
  // Sub-scale peak (parabola), not past the sampled range.
  float pos = static_cast<float>(best);
  if (best > 0 && best < scale_n - 1) {
    const float den2 = r[best - 1] - 2.0f * r[best] + r[best + 1];
    if (den2 < 0.0f) pos += std::max(-0.5f, std::min(0.5f, 0.5f * (r[best - 1] - r[best + 1]) / den2));
  }
  return static_cast<float>(std::pow(params.scale_step, pos - (scale_n - 1) * 0.5f));
}

// Scale self-calibration: on the frame it was trained on, the model's peak at the scale
// s^-k and at s^k should be equal (the true scale is 1); they are not (a tighter window of a
// thin silhouette on sky answers higher), and left alone that asymmetry makes the three-scale
// search shrink a constant-size target (to half its size over 100 frames on the generated
// crossing scenes). The factors
//   c_k = (sqrt(peak(s^-k) * peak(s^k)) / peak(s^k))^kScaleCalibration
// take half of that asymmetry away (the unit scale keeps 1) and are applied to every later
// frame's peaks before the choice. Half, not all: the full correction keeps the generated
// scenes' sizes as well but loses a tall pedestrian (the Woman clip) and a camera jerk
// (docs/measurements.md, "Scale self-calibration").
void KcfTracker::Impl::calibrateScales(const cv::Mat& frame) {
  const int count = static_cast<int>(scales.size());
  std::fill(scale_calib.begin(), scale_calib.end(), 1.0f);
  if (count < 3 || count > kMaxScaleCount) return;
  std::array<float, kMaxScaleCount> peaks{};  // no allocation: init runs on re-detections too
  for (int i = 0; i < count; ++i) {
    if (2 * i == count - 1) continue;  // the unit scale is not needed
    const float sc = scales[i];
    respond(frame, center, cv::Size2f(window.width * sc, window.height * sc), resp[i]);
    double mx;
    cv::minMaxLoc(resp[i], nullptr, &mx);
    peaks[i] = static_cast<float>(mx);
  }
  for (int k = 1; 2 * k < count + 1; ++k) {
    const int lo = (count - 1) / 2 - k, hi = (count - 1) / 2 + k;
    if (lo < 0 || hi >= count || !(peaks[lo] > 0.0f) || !(peaks[hi] > 0.0f)) continue;
    const float g = std::sqrt(peaks[lo] * peaks[hi]);
    scale_calib[lo] = std::pow(g / peaks[lo], kScaleCalibration);
    scale_calib[hi] = std::pow(g / peaks[hi], kScaleCalibration);
  }
}

// The per-scale arrays (kMaxScaleCount) hold every scale_count the parameter list allows.
#define OT_CHECK_SCALE_COUNT_BOUND_(type, name, def, lo, hi, unit, doc)                       \
  static_assert(std::string_view(#name) != "scale_count" || (hi) == kMaxScaleCount,          \
                "kMaxScaleCount must equal scale_count's upper bound in params.h");
OT_TRACKER_PARAMS(OT_CHECK_SCALE_COUNT_BOUND_)
#undef OT_CHECK_SCALE_COUNT_BOUND_

// The searched scale to use this frame. A step in the direction of the size trend measured
// outside the filter (setSizeTrend) is taken at once; any other step only once the same side has
// won scale_confirm_frames frames in a row, the unit scale is used until then. A single frame's
// win is weak evidence: with the model
// averaged over frames whose background moved, the smaller window's sample, with less of that
// background, answers a few percent above the unit scale on many frames of a constant-size
// target, and steps taken on those wins, never undone, shrank the box to the most contrasted part
// (a crossing aircraft's tail fin). The size trend (the sum of the last frames' pixel expansions
// inside the box, LoomingEstimator::sizeTrend, counted only when their mean is beyond two standard
// errors of their scatter) tells a real size change within a few frames, so growth is not delayed
// by the confirmation (docs/measurements.md).
int KcfTracker::Impl::confirmScale(int best) {
  const int unit = (static_cast<int>(scales.size()) - 1) / 2;
  const int side = best > unit ? 1 : (best < unit ? -1 : 0);
  if (side == 0 || !have_size_trend || side == size_trend) {
    scale_votes = 0;
    return best;
  }
  scale_votes = scale_votes * side > 0 ? scale_votes + side : side;
  if (std::abs(scale_votes) >= params.scale_confirm_frames) {
    scale_votes = 0;
    return best;
  }
  return unit;
}

void KcfTracker::Impl::buildScaleFilter(const cv::Mat& frame) {
  scale_n = std::max(1, params.scale_count);
  if (scale_n % 2 == 0) ++scale_n;  // odd, so the unit scale is sampled
  // Scale model: the target (no padding) resized to at most kScaleModelArea pixels, at least
  // two cells a side.
  const float area = target.area();
  const float k = area > kScaleModelArea ? std::sqrt(kScaleModelArea / area) : 1.0f;
  sm_w = std::max(2 * cell, static_cast<int>(std::lround(target.width * k)));
  sm_h = std::max(2 * cell, static_cast<int>(std::lround(target.height * k)));
  sm_w = std::min(sm_w, std::max(tw, 2 * cell));
  sm_h = std::min(sm_h, std::max(th, 2 * cell));
  scale_dim = kChannels * (sm_w / cell) * (sm_h / cell);
  dsst_factors.resize(scale_n);
  scale_window.resize(scale_n);
  for (int n = 0; n < scale_n; ++n) {
    dsst_factors[n] = static_cast<float>(std::pow(params.scale_step, n - (scale_n - 1) / 2.0));
    scale_window[n] =
        scale_n == 1 ? 1.0f
                     : static_cast<float>(0.5 - 0.5 * std::cos(2.0 * M_PI * (n + 1) / (scale_n + 1)));
  }
  scale_x.create(scale_dim, scale_n, CV_32F);
  scale_xf.create(scale_dim, scale_n, CV_32FC2);
  scale_num.create(scale_dim, scale_n, CV_32FC2);
  scale_den.create(1, scale_n, CV_32F);
  scale_new_den.create(1, scale_n, CV_32F);
  scale_resp_f.create(1, scale_n, CV_32FC2);
  scale_resp.create(1, scale_n, CV_32F);
  // Label: Gaussian over the scale index, peak at the centre, sigma = sqrt(S) / 4 (DSST).
  const float sigma = std::sqrt(static_cast<float>(scale_n)) * 0.25f;
  cv::Mat ys(1, scale_n, CV_32F);
  for (int n = 0; n < scale_n; ++n) {
    const float d = static_cast<float>(n) - (scale_n - 1) * 0.5f;
    ys.at<float>(0, n) = std::exp(-0.5f * d * d / (sigma * sigma));
  }
  scale_fft.configure(1, scale_n);
  scale_fft.forwardEachRow(ys, scale_yf);
  sampler.reserve(sm_w, sm_h, frame.type(), frame.cols);
  trainScale(frame, 1.0f);
}

}  // namespace core
}  // namespace obstacle_tracker
