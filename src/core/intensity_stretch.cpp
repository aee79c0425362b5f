// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// IntensityStretch: the 16-bit / float to 8-bit rule described in intensity_stretch.h.
#include "obstacle_tracker/core/intensity_stretch.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace obstacle_tracker {
namespace core {

namespace {

constexpr int kHistogramBins = 65536;
// The float path samples about this many values per frame, whatever the frame size.
constexpr std::size_t kSampleTarget = 65536;

// The value at percentile `pct` of the samples (nearest rank); reorders them.
double samplePercentile(std::vector<float>& samples, double pct) {
  const std::size_t idx = std::min(
      samples.size() - 1, static_cast<std::size_t>(pct / 100.0 * (samples.size() - 1) + 0.5));
  std::nth_element(samples.begin(), samples.begin() + static_cast<long>(idx), samples.end());
  return static_cast<double>(samples[idx]);
}

}  // namespace

IntensityStretch::IntensityStretch(double low_percentile, double high_percentile,
                                   double smoothing) {
  setPercentiles(low_percentile, high_percentile);
  setSmoothing(smoothing);
}

void IntensityStretch::setPercentiles(double low_percentile, double high_percentile) {
  if (!(low_percentile >= 0.0 && high_percentile <= 100.0 && low_percentile < high_percentile)) {
    std::ostringstream msg;
    msg << "stretch percentiles must satisfy 0 <= low < high <= 100, got " << low_percentile
        << " and " << high_percentile;
    throw std::invalid_argument(msg.str());
  }
  low_percentile_ = low_percentile;
  high_percentile_ = high_percentile;
}

void IntensityStretch::setSmoothing(double smoothing) {
  if (!(smoothing > 0.0 && smoothing <= 1.0)) {
    std::ostringstream msg;
    msg << "stretch smoothing must be in (0, 1], got " << smoothing;
    throw std::invalid_argument(msg.str());
  }
  smoothing_ = smoothing;
}

void IntensityStretch::reset() {
  have_range_ = false;
  depth_ = -1;
  smooth_low_ = smooth_high_ = 0.0;
  low_ = 0.0;
  high_ = 255.0;
}

void IntensityStretch::apply(const cv::Mat& src, cv::Mat& dst) {
  if (src.empty() || src.depth() == CV_8U) {
    throw std::invalid_argument("IntensityStretch::apply expects a non-empty frame deeper than 8 bits");
  }
  if (src.depth() != depth_) {
    reset();
    depth_ = src.depth();
  }
  const int type8 = CV_MAKETYPE(CV_8U, src.channels());
  if (src.depth() == CV_16U) {
    double lo = 0.0, hi = 0.0;
    histogramRange(src, &lo, &hi);
    // Counts are integers: a span of one count keeps a flat frame at 0 without dividing by zero.
    updateRange(lo, hi, 1.0);
    const double alpha = 255.0 / (high_ - low_);
    src.convertTo(dst, type8, alpha, -low_ * alpha);  // saturating
    return;
  }
  double lo = 0.0, hi = 0.0;
  bool found = false, non_finite = false;
  const cv::Mat& values = sampledRange(src, &lo, &hi, &found, &non_finite);
  if (found) {
    // convertTo computes in float: below about 1e-5 of the values' magnitude, the span would be
    // lost in rounding and a flat frame would come out as noise between 0 and 255.
    updateRange(lo, hi, 1e-4 * std::max({1.0, std::fabs(lo), std::fabs(hi)}));
  } else if (!have_range_) {
    updateRange(0.0, 0.0, 1e-4);  // no finite value yet: everything maps to 0 or 255
  }
  if (non_finite) {
    // float_ is ours here (sampledRange copied into it). NaN and -inf go to the value mapped to
    // 0 and +inf to the one mapped to 255 (converting an infinity to an integer is undefined).
    const int cols = float_.cols * float_.channels();
    const float low = static_cast<float>(low_), high = static_cast<float>(high_);
    for (int r = 0; r < float_.rows; ++r) {
      float* p = float_.ptr<float>(r);
      for (int c = 0; c < cols; ++c) {
        if (!std::isfinite(p[c])) p[c] = p[c] > 0.0f ? high : low;
      }
    }
  }
  const double alpha = 255.0 / (high_ - low_);
  values.convertTo(dst, type8, alpha, -low_ * alpha);  // saturating
}

void IntensityStretch::histogramRange(const cv::Mat& src, double* lo, double* hi) {
  histogram_.assign(kHistogramBins, 0u);  // keeps its capacity: allocates on the first call only
  const int values_per_row = src.cols * src.channels();
  for (int r = 0; r < src.rows; ++r) {
    const std::uint16_t* row = src.ptr<std::uint16_t>(r);
    for (int i = 0; i < values_per_row; ++i) ++histogram_[row[i]];
  }
  const double total = static_cast<double>(values_per_row) * src.rows;
  const double low_count = total * low_percentile_ / 100.0;
  const double high_count = total * high_percentile_ / 100.0;
  int low = -1, high = kHistogramBins - 1;
  double cumulative = 0.0;
  for (int v = 0; v < kHistogramBins; ++v) {
    cumulative += histogram_[v];
    if (low < 0 && cumulative > low_count) low = v;
    if (cumulative >= high_count && histogram_[v] > 0) {
      high = v;
      break;
    }
  }
  *lo = std::max(low, 0);
  *hi = high;
}

const cv::Mat& IntensityStretch::sampledRange(const cv::Mat& src, double* lo, double* hi,
                                              bool* found, bool* non_finite) {
  const cv::Mat* values = &src;
  if (src.depth() != CV_32F) {
    src.convertTo(float_, CV_MAKETYPE(CV_32F, src.channels()));
    values = &float_;
  }
  samples_.clear();
  const std::size_t n = values->total() * values->channels();
  const std::size_t step = std::max<std::size_t>(1, n / kSampleTarget);
  const int cols = values->cols * values->channels();
  std::size_t k = 0;
  *non_finite = false;
  for (int r = 0; r < values->rows; ++r) {
    const float* p = values->ptr<float>(r);
    for (int c = 0; c < cols; ++c, ++k) {
      if (!std::isfinite(p[c])) {
        *non_finite = true;
      } else if (k % step == 0) {
        samples_.push_back(p[c]);
      }
    }
  }
  *found = !samples_.empty();
  if (*found) {
    *lo = samplePercentile(samples_, low_percentile_);
    *hi = samplePercentile(samples_, high_percentile_);
  }
  if (*non_finite && values == &src) {
    src.copyTo(float_);  // the caller's frame is never written
    values = &float_;
  }
  return *values;
}

void IntensityStretch::updateRange(double lo, double hi, double min_span) {
  if (have_range_ && smoothing_ < 1.0) {
    // In this form a range that does not change stays exactly where it is.
    smooth_low_ += smoothing_ * (lo - smooth_low_);
    smooth_high_ += smoothing_ * (hi - smooth_high_);
  } else {
    smooth_low_ = lo;
    smooth_high_ = hi;
    have_range_ = true;
  }
  low_ = smooth_low_;
  high_ = std::max(smooth_high_, smooth_low_ + min_span);
}

}  // namespace core
}  // namespace obstacle_tracker
