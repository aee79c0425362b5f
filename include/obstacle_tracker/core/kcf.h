// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Kernelized correlation filter (Henriques et al., TPAMI 2015) on fHOG + grey features with a
// fixed template size, scale estimation and confidence (peak, PSR).
//
// The pipeline (pipeline_impl.h) relies on the members below and their meaning.
#pragma once

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/params.h"

namespace obstacle_tracker {
namespace core {

struct KcfResult {
  cv::Rect2f box;            // new box in frame pixels
  float peak = 0.0f;         // raw maximum of the response (the paper's confidence)
  float psr = 0.0f;          // peak-to-sidelobe ratio
  float confidence = 0.0f;   // [0, 1], mapping documented below (KcfTracker)
  float scale_change = 1.0f; // box size ratio against the previous frame
  bool model_updated = false;
};

// Confidence mapping (also in docs/algorithms.md, "Tracker (KCF)"):
//   c_peak = clamp((peak) / kConfidencePeakFull, 0, 1)
//   c_psr  = clamp((psr - kConfidencePsrZero) / (kConfidencePsrFull - kConfidencePsrZero), 0, 1)
//   confidence = sqrt(c_peak * c_psr)
// i.e. the geometric mean of the raw response peak (1 on the training sample itself) and the
// peak-to-sidelobe ratio, each scaled to [0, 1]. Either a flat response (low PSR) or a weak peak
// pulls the confidence down. The model learns only when confidence >=
// TrackerParams::learn_threshold; the pipeline re-detects when the raw peak <
// Params::peak_threshold (the paper's test).
//
// Bad input (empty frame, a type other than CV_8UC1/CV_8UC3, a box that is not finite, smaller
// than 1x1 px, outside the frame or more than 16 times the frame's width or height) throws
// std::invalid_argument; update/evaluate before init
// throw std::logic_error. Parameters are clamped into their ranges (core::validate).
class KcfTracker {
 public:
  struct Impl;

  // Calibrated on the 10 dev clips (docs/algorithms.md, "Tracker (KCF)"): frames tracked within 20 px have
  // peak >= 0.15 and PSR >= 12 in 95 % of cases (confidence >= 0.48); at the onset of a failure
  // peak ~0.05-0.13 and PSR ~5-11 (confidence <= 0.38).
  static constexpr float kConfidencePeakFull = 0.35f;
  static constexpr float kConfidencePsrZero = 5.0f;
  static constexpr float kConfidencePsrFull = 20.0f;

  explicit KcfTracker(const TrackerParams& params = TrackerParams());
  ~KcfTracker();
  KcfTracker(const KcfTracker&) = delete;
  KcfTracker& operator=(const KcfTracker&) = delete;
  KcfTracker(KcfTracker&&) noexcept;
  KcfTracker& operator=(KcfTracker&&) noexcept;

  // Takes effect at the next init (filter geometry) or update (rates, thresholds). Values are
  // clamped as core::validate does; no allocation, so it may be called every frame.
  void setParams(const TrackerParams& params);

  // Starts (or restarts) the filter on box. frame: CV_8UC1 or CV_8UC3 (BGR).
  void init(const cv::Mat& frame, const cv::Rect2f& box);

  // Detects in frame around the current box, then learns when confidence >= learn_threshold.
  KcfResult update(const cv::Mat& frame);

  // Moves the current box (the next detection's search centre) by offset px without touching
  // the model: the caller's motion prediction, e.g. over frames it never saw. Throws
  // std::logic_error before init; an offset that is not finite is ignored.
  void shiftSearch(const cv::Point2f& offset);

  // The object's size trend measured outside the filter (e.g. a looming estimate from the
  // object's own pixels, looming.h): +1 growing, -1 shrinking, 0 no significant change. Later
  // update()s take a scale step in the trend's direction at once; a step against it, or any step
  // while the trend is 0, must win scale_confirm_frames frames in a row. Until it is called (a
  // filter used on its own) every step is taken at once. Values other than -1, 0, +1 throw
  // std::invalid_argument.
  void setSizeTrend(int trend);

  // Correlates the current model at a candidate box without changing any state (to verify a
  // re-detection candidate against the model). The window is the model's, centred on the
  // candidate and scaled by sqrt(candidate area / current box area) (the model's aspect is kept);
  // the result's box has the candidate's size, moved to the response peak; scale_change is that
  // scale; model_updated is false.
  KcfResult evaluate(const cv::Mat& frame, const cv::Rect2f& candidate);

  // For callers that gate learning themselves (e.g. against running means of peak and PSR):
  // detect() is update() without learning (model_updated is false); learn() then trains on the
  // tracked box of the same frame (reusing detect()'s features, so it costs no extra extraction
  // when called right after detect()). learn() ignores learn_threshold.
  KcfResult detect(const cv::Mat& frame);
  void learn(const cv::Mat& frame);

  bool initialized() const;
  cv::Rect2f box() const;

  // The validated parameters in use.
  const TrackerParams& params() const;
  // The confidence mapping above.
  static float confidenceFrom(float peak, float psr);
  // Cells of the filter template (cols x rows); empty before init.
  cv::Size templateCells() const;

 private:
  Impl* impl_;
};

}  // namespace core
}  // namespace obstacle_tracker
