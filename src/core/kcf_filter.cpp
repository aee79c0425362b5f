// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// KcfTracker::Impl (kcf_impl.h): the filter's geometry, features (fHOG + grey, cosine window),
// Gaussian kernel correlation (KCF eq. 31), training (eq. 17), response (eq. 22), sub-cell peak
// and PSR.
#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "kcf_impl.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/portable_math.h"

namespace obstacle_tracker {
namespace core {

using namespace kcf_detail;  // NOLINT(build/namespaces): the filter's own constants and helpers

void KcfTracker::Impl::forward(const cv::Mat& src, cv::Mat& dst) { fft.forward(src, dst); }

void KcfTracker::Impl::inverse(const cv::Mat& src, cv::Mat& dst) { fft.inverse(src, dst); }

// Same clamping as core::validate (NaN -> default, out of range -> nearest bound), written
// against the parameter list directly so it allocates nothing: the pipeline may change
// thresholds every frame.
void KcfTracker::Impl::setParams(const TrackerParams& p) {
  params = p;
  clampGroup(params);
}

// Frame window (centre c, size ws) -> template patch (tw x th) (patch_sampler.h).
void KcfTracker::Impl::extractPatch(const cv::Mat& frame, cv::Point2f c, cv::Size2f ws) {
  sampler.sample(frame, c, ws, tw, th, patch);
}

// Features of the window -> zf (spectra), returns ||z||^2.
float KcfTracker::Impl::featuresSpectrum(const cv::Mat& frame, cv::Point2f c, cv::Size2f ws, cv::Mat& out_f) {
  cached_valid = false;
  extractPatch(frame, c, ws);
  fhog.compute(patch, cell, feat);
  out_f.create(kChannels * rows, cols, CV_32FC2);
  double energy = 0.0;
  for (int ch = 0; ch < kChannels; ++ch) {
    cv::Mat plane = feat.rowRange(ch * rows, (ch + 1) * rows);
    cv::multiply(plane, cos_window, plane);
    energy += sumOfSquares(plane);  // not Mat::dot: CPU-dependent order (portable_math.h)
    cv::Mat dst = out_f.rowRange(ch * rows, (ch + 1) * rows);
    forward(plane, dst);
  }
  return static_cast<float>(energy);
}

// Gaussian kernel correlation of the model x with z (Henriques 2015, eq. 31), normalised by
// N = rows * cols * C so that the kernel width does not depend on the template size.
// Result: kf = F(k^{xz}).
void KcfTracker::Impl::gaussianCorrelation(const cv::Mat& xf, float xx, const cv::Mat& zf_in, float zz) {
  corr_f.create(rows, cols, CV_32FC2);
  const int n = rows * cols;
  std::fill(corr_f.ptr<float>(), corr_f.ptr<float>() + 2 * n, 0.0f);  // (setTo allocates)
  for (int ch = 0; ch < kChannels; ++ch) {
    accumulateConjProduct(zf_in.ptr<float>(ch * rows), xf.ptr<float>(ch * rows),
                          corr_f.ptr<float>(), n);
  }
  inverse(corr_f, corr);
  const float sigma = static_cast<float>(params.kcf_kernel_sigma);
  const float scale = -1.0f / (sigma * sigma * static_cast<float>(n * kChannels));
  k.create(rows, cols, CV_32F);
  const float* cp = corr.ptr<float>();
  float* kp = k.ptr<float>();
  for (int i = 0; i < n; ++i) {
    const float d = std::max(0.0f, xx + zz - 2.0f * cp[i]);
    kp[i] = d * scale;
  }
  expInPlace(kp, n);  // not cv::exp, whose last bit depends on the CPU (portable_math.h)
  forward(k, kf);
}

void KcfTracker::Impl::buildGeometry(const cv::Mat& frame, const cv::Rect2f& box) {
  cell = params.kcf_cell_size;
  const float pad = 1.0f + static_cast<float>(params.kcf_padding);
  const float min_win = static_cast<float>(params.kcf_min_window);
  float ww = std::max(box.width * pad, min_win);
  float wh = std::max(box.height * pad, min_win);
  // Keep the window's aspect within 1:kMaxWindowAspect so a thin target still has context
  // (and enough cells) along its short side.
  // Small, compact targets (aspect <= 2) get a square window: their motion is large against
  // their short side. Thin small targets (a crossing aircraft) keep the aspect limit: a square
  // window stalled the filter on them in the generated multi and out_of_view scenes.
  const float box_aspect = std::max(box.width, box.height) / std::max(1e-3f, std::min(box.width, box.height));
  const float max_aspect =
      (std::sqrt(box.width * box.height) < kSmallTarget && box_aspect <= 2.0f) ? 1.0f : kMaxWindowAspect;
  ww = std::max(ww, wh / max_aspect);
  wh = std::max(wh, ww / max_aspect);
  const float longer = std::max(ww, wh);
  const int long_cells =
      cv::getOptimalDFTSize(std::max(kMinCells, static_cast<int>(std::lround(
                                                    static_cast<double>(params.kcf_template_size) / cell))));
  const int short_cells = cv::getOptimalDFTSize(std::max(
      kMinCells, static_cast<int>(std::lround(long_cells * std::min(ww, wh) / longer))));
  cols = ww >= wh ? long_cells : short_cells;
  rows = ww >= wh ? short_cells : long_cells;
  tw = cols * cell;
  th = rows * cell;
  center = boxCentre(box);
  target = box.size();
  window = cv::Size2f(ww, wh);
  min_target = cv::Size2f(std::min(box.width, kMinTargetSide), std::min(box.height, kMinTargetSide));
  max_target = cv::Size2f(std::max(box.width, static_cast<float>(frame.cols)),
                          std::max(box.height, static_cast<float>(frame.rows)));

  cv::Mat hy, hx;
  cv::createHanningWindow(cos_window, cv::Size(cols, rows), CV_32F);
  // createHanningWindow puts zeros on the border; fine for a correlation filter.

  // Label: Gaussian on the cyclic distance from (0, 0) (Henriques 2015, sec. 5.1), sigma from
  // the target size in cells.
  const float target_cells_w = target.width * (static_cast<float>(tw) / window.width) / cell;
  const float target_cells_h = target.height * (static_cast<float>(th) / window.height) / cell;
  const float sigma = static_cast<float>(params.kcf_output_sigma_factor) *
                      std::sqrt(target_cells_w * target_cells_h);
  cv::Mat y(rows, cols, CV_32F);
  for (int r = 0; r < rows; ++r) {
    const int dr = std::min(r, rows - r);
    for (int c = 0; c < cols; ++c) {
      const int dc = std::min(c, cols - c);
      y.at<float>(r, c) = std::exp(-0.5f * static_cast<float>(dr * dr + dc * dc) / (sigma * sigma));
    }
  }
  fft.configure(rows, cols);
  forward(y, yf);
  corr_f.create(rows, cols, CV_32FC2);
  corr.create(rows, cols, CV_32F);
  k.create(rows, cols, CV_32F);
  kf.create(rows, cols, CV_32FC2);
  resp_f.create(rows, cols, CV_32FC2);

  use_scale_filter = params.kcf_scale_filter;
  const int count = use_scale_filter ? 1 : std::max(1, params.scale_count);
  scales.resize(count);
  scale_calib.assign(count, 1.0f);
  for (int i = 0; i < count; ++i) {
    scales[i] = static_cast<float>(std::pow(params.scale_step, i - (count - 1) / 2.0));
  }
  sampler.reserve(tw, th, frame.type(), frame.cols);
  resp.resize(count);
  for (auto& r : resp) r.create(rows, cols, CV_32F);
  model_xf.create(kChannels * rows, cols, CV_32FC2);
  zf.create(kChannels * rows, cols, CV_32FC2);
  model_alphaf.create(rows, cols, CV_32FC2);
  new_alphaf.create(rows, cols, CV_32FC2);
}

// Trains on the window at the current centre (Henriques 2015, eq. 17) and interpolates the model
// with rate eta (1 = replace).
void KcfTracker::Impl::train(const cv::Mat& frame, float eta) {
  const float xx = featuresSpectrum(frame, center, window, zf);
  trainOnSpectrum(xx, eta);
}

// Same, on the features already in zf (||z||^2 = xx).
void KcfTracker::Impl::trainOnSpectrum(float xx, float eta) {
  gaussianCorrelation(zf, xx, zf, xx);
  // alpha^ = y^ / (k^xx + lambda)
  const float lambda = static_cast<float>(params.kcf_lambda);
  const int n = rows * cols;
  const float* yp = yf.ptr<float>();
  const float* kp = kf.ptr<float>();
  float* ap = new_alphaf.ptr<float>();
  for (int i = 0; i < 2 * n; i += 2) {
    const float br = kp[i] + lambda, bi = kp[i + 1];
    const float inv = 1.0f / (br * br + bi * bi);
    ap[i] = (yp[i] * br + yp[i + 1] * bi) * inv;
    ap[i + 1] = (yp[i + 1] * br - yp[i] * bi) * inv;
  }
  if (eta >= 1.0f) {
    zf.copyTo(model_xf);
    new_alphaf.copyTo(model_alphaf);
  } else {
    // Not cv::addWeighted: its result depends on the CPU (portable_math.h).
    blendInPlace(model_xf, zf, eta);
    blendInPlace(model_alphaf, new_alphaf, eta);
  }
  // ||x_model||^2 by Parseval (unnormalised forward DFT).
  // Not cv::norm: its summation order is the SIMD width's, which differs on ARM (portable_math.h).
  model_xx = static_cast<float>(sumOfSquares(model_xf) / static_cast<double>(n));
}

// Response of the model on the window (c, ws) into out (Henriques 2015, eq. 22).
void KcfTracker::Impl::respond(const cv::Mat& frame, cv::Point2f c, cv::Size2f ws, cv::Mat& out) {
  const float zz = featuresSpectrum(frame, c, ws, zf);
  gaussianCorrelation(model_xf, model_xx, zf, zz);
  kernelResponse(out);
}

// The response for the kernel spectrum kf: F^-1(kf .* alpha^) (eq. 22 after the correlation).
void KcfTracker::Impl::kernelResponse(cv::Mat& out) {
  resp_f.create(rows, cols, CV_32FC2);
  multiplySpectra(kf.ptr<float>(), model_alphaf.ptr<float>(), resp_f.ptr<float>(), rows * cols);
  inverse(resp_f, out);
}

// Sub-cell peak position by a parabola through log values (exact for a Gaussian peak), plain
// parabola when a neighbour is not positive. Returns the peak's cyclic displacement in cells.
cv::Point2f KcfTracker::Impl::subCellPeak(const cv::Mat& r, cv::Point p) const {
  auto at = [&](int y, int x) {
    return r.at<float>((y + rows) % rows, (x + cols) % cols);
  };
  auto offset = [](float l, float c, float rr) {
    if (l > 0.0f && c > 0.0f && rr > 0.0f) {
      const float ll = std::log(l), lc = std::log(c), lr = std::log(rr);
      const float den = ll - 2.0f * lc + lr;
      if (den < 0.0f) return std::max(-0.5f, std::min(0.5f, 0.5f * (ll - lr) / den));
    }
    const float den = l - 2.0f * c + rr;
    if (den < 0.0f) return std::max(-0.5f, std::min(0.5f, 0.5f * (l - rr) / den));
    return 0.0f;
  };
  const float c0 = at(p.y, p.x);
  float dx = static_cast<float>(p.x) + offset(at(p.y, p.x - 1), c0, at(p.y, p.x + 1));
  float dy = static_cast<float>(p.y) + offset(at(p.y - 1, p.x), c0, at(p.y + 1, p.x));
  if (dx > cols * 0.5f) dx -= static_cast<float>(cols);
  if (dy > rows * 0.5f) dy -= static_cast<float>(rows);
  return cv::Point2f(dx, dy);
}

// PSR (Bolme et al. 2010): (peak - mean) / std of the response outside the 11x11 cells around
// the peak (cyclic).
float KcfTracker::Impl::psrOf(const cv::Mat& r, cv::Point p, float peak) const {
  // 11 x 11 as in MOSSE when the grid has at least 20 cells a side, narrower on small grids so
  // a sidelobe remains.
  const int excl = std::min(kPsrExclusion, std::min(rows, cols) / 4);
  double sum = 0.0, sum2 = 0.0;
  int count = 0;
  for (int y = 0; y < rows; ++y) {
    int dy = std::abs(y - p.y);
    dy = std::min(dy, rows - dy);
    const float* rp = r.ptr<float>(y);
    for (int x = 0; x < cols; ++x) {
      int dx = std::abs(x - p.x);
      dx = std::min(dx, cols - dx);
      if (dy <= excl && dx <= excl) continue;
      sum += rp[x];
      sum2 += static_cast<double>(rp[x]) * rp[x];
      ++count;
    }
  }
  if (count < 2) return 0.0f;
  const double mean = sum / count;
  const double var = std::max(0.0, sum2 / count - mean * mean);
  const double sd = std::sqrt(var);
  if (sd < 1e-12) return peak > mean ? kMaxPsr : 0.0f;
  return static_cast<float>(std::min<double>(kMaxPsr, (peak - mean) / sd));
}

// Scales target and window by f, bounded so that a drifting filter cannot blow the box up or
// shrink it to nothing; returns the factor applied.
float KcfTracker::Impl::applyScale(float f) {
  f = std::min(f, max_target.width / target.width);
  f = std::min(f, max_target.height / target.height);
  f = std::max(f, min_target.width / target.width);
  f = std::max(f, min_target.height / target.height);
  target = cv::Size2f(target.width * f, target.height * f);
  window = cv::Size2f(window.width * f, window.height * f);
  return f;
}

cv::Rect2f KcfTracker::Impl::boxAt(cv::Point2f c, cv::Size2f s) const {
  return boxCentredAt(c, s);
}

}  // namespace core
}  // namespace obstacle_tracker
