// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The one rule that turns a 16-bit (thermal) or floating-point frame into the 8 bits the core
// tracks, shared by the nodelet (bridge::FrameConverter) and the tools (eval::FrameConverter), so
// that an offline score on 16-bit input describes what the nodelet does with the same frames.
//
// Thermal cameras send 14-16 bit counts that fill a narrow band of the range, so a fixed >> 8
// gives an almost flat image. The band between two percentiles of the frame's values (all
// channels together) is mapped linearly onto [0, 255]; values outside saturate, so a few hot or
// dead pixels do not flatten the picture.
//   CV_16U (any channel count): exact percentiles from a 65536-bin histogram of every value.
//   other depths but CV_8U (float, signed, 32-bit): percentiles (nearest rank) of a strided
//   sample of at most about 2^17 finite values; NaN and -inf map to 0, +inf to 255.
// Temporal smoothing: a thermal camera's automatic gain control re-levels the counts from frame to
// frame (and one bright object entering the view moves the high percentile), so a per-frame range
// makes the whole 8-bit picture flicker, which the tracker's appearance model takes for a change
// of the target. The range is therefore an exponential moving average over the frames stretched
// so far: `smoothing` is the weight of the newest frame (1 = per frame, no memory).
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

// The defaults of every user of the stretch (nodelet parameters mono16_low_percentile,
// mono16_high_percentile, mono16_smoothing; evaluate; track_sequence).
constexpr double kStretchLowPercentile = 0.5;
constexpr double kStretchHighPercentile = 99.95;
constexpr double kStretchSmoothing = 0.2;

class IntensityStretch {
 public:
  // Throws std::invalid_argument for settings setPercentiles / setSmoothing refuse.
  explicit IntensityStretch(double low_percentile = kStretchLowPercentile,
                            double high_percentile = kStretchHighPercentile,
                            double smoothing = kStretchSmoothing);

  // Percentiles in [0, 100]. Throws std::invalid_argument unless 0 <= low < high <= 100.
  void setPercentiles(double low_percentile, double high_percentile);
  // Weight of the newest frame's range, in (0, 1]. Throws std::invalid_argument otherwise.
  void setSmoothing(double smoothing);
  double lowPercentile() const { return low_percentile_; }
  double highPercentile() const { return high_percentile_; }
  double smoothing() const { return smoothing_; }

  // src: non-empty, any channel count, any depth but CV_8U (std::invalid_argument otherwise).
  // dst: CV_8U with src's channel count (reallocated only when its size or type changes). The
  // buffers are kept between calls: no allocation per frame once the frame size is stable.
  void apply(const cv::Mat& src, cv::Mat& dst);

  // Forgets the smoothed range (a new sequence, another camera); also done when the depth of the
  // input changes, whose values are in other units.
  void reset();

  // The input values mapped to 0 and to 255 by the last apply() (0 and 255 before the first).
  double lastLow() const { return low_; }
  double lastHigh() const { return high_; }

 private:
  // [lo, hi] of a CV_16U frame from the histogram of all its values.
  void histogramRange(const cv::Mat& src, double* lo, double* hi);
  // `src` as CV_32F (src itself or float_) with [lo, hi] from a sample of its finite values;
  // *found is false when it has none. *non_finite tells whether it holds NaN or inf.
  const cv::Mat& sampledRange(const cv::Mat& src, double* lo, double* hi, bool* found,
                              bool* non_finite);
  // Folds the newest frame's [lo, hi] into the applied range low_, high_.
  void updateRange(double lo, double hi, double min_span);

  double low_percentile_ = kStretchLowPercentile;
  double high_percentile_ = kStretchHighPercentile;
  double smoothing_ = kStretchSmoothing;
  bool have_range_ = false;
  int depth_ = -1;             // depth of the frames the range was measured on
  double smooth_low_ = 0.0;    // the moving average, before the minimum span is enforced
  double smooth_high_ = 0.0;
  double low_ = 0.0;           // applied range
  double high_ = 255.0;
  std::vector<std::uint32_t> histogram_;
  std::vector<float> samples_;
  cv::Mat float_;
};

}  // namespace core
}  // namespace obstacle_tracker
