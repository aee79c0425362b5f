// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// KcfTracker::Impl, shared by kcf.cpp (the tracking step and the public API), kcf_filter.cpp
// (geometry, features, kernel correlation, training, response) and kcf_scale.cpp (scale search
// calibration and the DSST scale filter). Private to the core.
//
// Kernelized correlation filter, written from Henriques, Caseiro, Martins, Batista, "High-Speed
// Tracking with Kernelized Correlation Filters", TPAMI 37(3), 2015 (Gaussian kernel correlation,
// eq. 31; training, eq. 17; detection, eq. 22), with multi-channel fHOG + grey features
// (fhog.h), a fixed template size, a search over a few scales (as SAMF, Li & Zhu, ECCV-W 2014)
// and a confidence from the peak and the peak-to-sidelobe ratio (Bolme et al., CVPR 2010).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/fft.h"
#include "obstacle_tracker/core/fhog.h"
#include "obstacle_tracker/core/kcf.h"
#include "obstacle_tracker/core/patch_sampler.h"

namespace obstacle_tracker {
namespace core {
namespace kcf_detail {

constexpr int kChannels = FhogExtractor::kChannels;
constexpr int kPsrExclusion = 5;  // sidelobe excludes the 11x11 cells around the peak (MOSSE)
constexpr int kMinCells = 8;        // smallest side of the cell grid
constexpr float kMaxWindowAspect = 2.0f;  // longer / shorter side of the filter window, at most
constexpr float kSmallTarget = 32.0f;     // sqrt(w * h) below which the window is square
constexpr float kMinTargetSide = 4.0f;    // scale search never shrinks a side below this (px)
constexpr float kMaxPsr = 100.0f;
constexpr float kScaleModelArea = 512.0f;  // DSST's scale model size (32 x 16 px)
constexpr float kScaleLambda = 0.01f;      // DSST's regulariser
constexpr int kMaxScaleCount = 33;         // params.h's upper bound on scale_count
constexpr float kScaleCalibration = 0.5f;  // share (in log) of the scale asymmetry corrected
constexpr float kScaleLearningRate = 0.025f;  // DSST's scale-model rate (learning_rate is for KCF)

inline float clamp01(float v) { return std::min(1.0f, std::max(0.0f, v)); }

inline bool finiteBox(const cv::Rect2f& b) {
  return std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.width) &&
         std::isfinite(b.height);
}

// Interleaved complex (CV_32FC2) element-wise helpers on buffers of the same size.
// acc += a .* conj(b), over `count` complex values.
inline void accumulateConjProduct(const float* a, const float* b, float* acc, int count) {
  for (int i = 0; i < 2 * count; i += 2) {
    const float ar = a[i], ai = a[i + 1], br = b[i], bi = b[i + 1];
    acc[i] += ar * br + ai * bi;
    acc[i + 1] += ai * br - ar * bi;
  }
}

// out = a .* b, over `count` complex values (not cv::mulSpectrums, whose arm64 build fuses the
// multiply and the add: fft.h).
inline void multiplySpectra(const float* a, const float* b, float* out, int count) {
  for (int i = 0; i < 2 * count; i += 2) {
    const float ar = a[i], ai = a[i + 1], br = b[i], bi = b[i + 1];
    out[i] = ar * br - ai * bi;
    out[i + 1] = ar * bi + ai * br;
  }
}

// The confidence mapping (documented in kcf.h): geometric mean of a peak term and a PSR term.
inline float confidenceOf(float peak, float psr) {
  const float c_peak = clamp01(peak / KcfTracker::kConfidencePeakFull);
  const float c_psr = clamp01((psr - KcfTracker::kConfidencePsrZero) /
                              (KcfTracker::kConfidencePsrFull - KcfTracker::kConfidencePsrZero));
  return std::sqrt(c_peak * c_psr);
}

}  // namespace kcf_detail

struct KcfTracker::Impl {
  TrackerParams params;
  bool initialized = false;

  // Geometry, fixed at init.
  int cell = 4;
  int cols = 0, rows = 0;  // cells of the template
  int tw = 0, th = 0;      // template pixels (cols * cell, rows * cell)
  cv::Point2f center;
  cv::Size2f target;       // current target size, frame pixels
  cv::Size2f window;       // current window size, frame pixels (window / target is fixed)
  cv::Size2f min_target, max_target;
  std::vector<float> scales;
  std::vector<float> scale_calib;  // per-scale factor equalising the template's own asymmetry

  // Buffers, made once per template size.
  FhogExtractor fhog;
  cv::Mat patch;           // template-size patch
  PatchSampler sampler;
  cv::Mat feat;            // (C * rows) x cols, CV_32F, windowed features
  cv::Mat cos_window;      // rows x cols
  cv::Mat yf;              // label spectrum, rows x cols CV_32FC2
  cv::Mat model_xf;        // (C * rows) x cols CV_32FC2
  cv::Mat model_alphaf;    // rows x cols CV_32FC2
  float model_xx = 0.0f;   // ||x_model||^2
  cv::Mat zf;              // (C * rows) x cols CV_32FC2, features of the sample being tested
  cv::Mat corr_f, corr, k, kf, resp_f;
  std::vector<cv::Mat> resp;  // one response per scale
  cv::Mat new_alphaf;
  // Features of the last tracking step at the tracked box, kept for learn().
  bool cached_valid = false;
  int scale_votes = 0;  // confirmScale(): frames in a row a larger (> 0) or smaller (< 0) scale won
  bool have_size_trend = false;  // setSizeTrend() was called
  int size_trend = 0;            // its last trend: +1 growing, -1 shrinking, 0 none
  float cached_zz = 0.0f;

  // DSST scale filter (Danelljan et al., BMVC 2014): one column of fHOG features per scale.
  bool use_scale_filter = false;
  int scale_n = 1;                 // scales of the scale filter (S)
  int scale_dim = 0;               // feature length per scale (D)
  int sm_w = 0, sm_h = 0;          // scale model patch size, px
  std::vector<float> scale_window; // 1-D Hann over the scales
  std::vector<float> dsst_factors; // a^(n - (S-1)/2)
  cv::Mat scale_patch, scale_feat;
  cv::Mat scale_x;                 // D x S, CV_32F
  cv::Mat scale_xf;                // D x S, CV_32FC2 (DFT of each row)
  cv::Mat scale_num;               // D x S, CV_32FC2: conj(F) * G, interpolated
  cv::Mat scale_den;               // 1 x S, CV_32F: sum_d |F_d|^2, interpolated
  cv::Mat scale_new_den;
  cv::Mat scale_yf;                // 1 x S, CV_32FC2
  cv::Mat scale_resp_f, scale_resp;
  RealFft2d scale_fft;             // 1 x S: each row's spectrum, and the response's inverse

  // The template's transforms (fft.h: the same bits on every machine, unlike cv::dft).
  RealFft2d fft;

  explicit Impl(const TrackerParams& p) { setParams(p); }

  // kcf_filter.cpp
  void forward(const cv::Mat& src, cv::Mat& dst);
  void inverse(const cv::Mat& src, cv::Mat& dst);
  void setParams(const TrackerParams& p);
  void extractPatch(const cv::Mat& frame, cv::Point2f c, cv::Size2f ws);
  float featuresSpectrum(const cv::Mat& frame, cv::Point2f c, cv::Size2f ws, cv::Mat& out_f);
  void gaussianCorrelation(const cv::Mat& xf, float xx, const cv::Mat& zf_in, float zz);
  void buildGeometry(const cv::Mat& frame, const cv::Rect2f& box);
  void train(const cv::Mat& frame, float eta);
  void trainOnSpectrum(float xx, float eta);
  void respond(const cv::Mat& frame, cv::Point2f c, cv::Size2f ws, cv::Mat& out);
  void kernelResponse(cv::Mat& out);
  cv::Point2f subCellPeak(const cv::Mat& r, cv::Point p) const;
  float psrOf(const cv::Mat& r, cv::Point p, float peak) const;
  float applyScale(float f);
  int confirmScale(int best);
  cv::Rect2f boxAt(cv::Point2f c, cv::Size2f s) const;

  // kcf_scale.cpp
  void scaleSamples(const cv::Mat& frame, cv::Point2f c, cv::Size2f t);
  void trainScale(const cv::Mat& frame, float eta);
  float detectScale(const cv::Mat& frame);
  void calibrateScales(const cv::Mat& frame);
  void buildScaleFilter(const cv::Mat& frame);
};

}  // namespace core
}  // namespace obstacle_tracker
