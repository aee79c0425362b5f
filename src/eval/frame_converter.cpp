// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// FrameConverter: any decoded frame to the 8-bit 1- or 3-channel frames the core accepts; the
// rules are in sequence.h.
#include "obstacle_tracker/eval/sequence.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace obstacle_tracker {
namespace eval {

namespace {

// A robust [low, high] range from a histogram of integer values 0..65535.
void histogramRange(const std::vector<int>& hist, double total, double lo_pct, double hi_pct,
                    double* lo, double* hi) {
  const double lo_count = total * lo_pct / 100.0;
  const double hi_count = total * hi_pct / 100.0;
  double acc = 0.0;
  int l = -1, h = -1;
  for (int v = 0; v < static_cast<int>(hist.size()); ++v) {
    acc += hist[v];
    if (l < 0 && acc > lo_count) l = v;
    if (h < 0 && acc >= hi_count) {
      h = v;
      break;
    }
  }
  if (l < 0) l = 0;
  if (h < 0) h = static_cast<int>(hist.size()) - 1;
  *lo = l;
  *hi = h;
}

// The value at percentile `pct` of the samples (nearest rank); reorders them.
double samplePercentile(std::vector<float>& samples, double pct) {
  const std::size_t idx = std::min(
      samples.size() - 1, static_cast<std::size_t>(pct / 100.0 * (samples.size() - 1) + 0.5));
  std::nth_element(samples.begin(), samples.begin() + static_cast<long>(idx), samples.end());
  return static_cast<double>(samples[idx]);
}

}  // namespace

FrameConverter::FrameConverter(double low_percent, double high_percent, double smoothing)
    : low_percent_(std::clamp(low_percent, 0.0, 100.0)),
      high_percent_(std::clamp(high_percent, 0.0, 100.0)),
      smoothing_(std::clamp(smoothing, 1e-6, 1.0)) {
  if (high_percent_ <= low_percent_) {
    throw std::invalid_argument("FrameConverter: high_percent must exceed low_percent");
  }
}

void FrameConverter::reset() {
  have_range_ = false;
  low_ = 0.0;
  high_ = 255.0;
}

const cv::Mat& FrameConverter::convert(const cv::Mat& in) {
  if (in.empty()) throw std::invalid_argument("FrameConverter: empty frame");
  const int ch = in.channels();
  if (ch < 1 || ch > 4) {
    throw std::invalid_argument("FrameConverter: unsupported channel count " + std::to_string(ch));
  }
  const int depth = in.depth();
  if (depth == CV_8U && (ch == 1 || ch == 3)) {
    out_ = in;
    return out_;
  }

  // Bring the channel layout to 1 or 3 first (at the input depth).
  const cv::Mat* src = &in;
  if (ch == 4) {
    cv::cvtColor(in, work_, cv::COLOR_BGRA2BGR);
    src = &work_;
  } else if (ch == 2) {
    cv::extractChannel(in, work_, 0);
    src = &work_;
  }
  if (depth == CV_8U) {
    if (src == &work_) {
      out_ = work_;  // already converted into our buffer
    } else {
      src->copyTo(out_);
    }
    return out_;
  }

  double lo = 0.0, hi = 0.0;
  if (depth == CV_16U) {
    histogramRange16(*src, &lo, &hi);
  } else {
    src = &floatWithSampledRange(in, *src, &lo, &hi);
  }
  stretchToOutput(*src, lo, hi);
  return out_;
}

void FrameConverter::histogramRange16(const cv::Mat& src, double* lo, double* hi) {
  histogram_.assign(65536, 0);
  const int cols = src.cols * src.channels();
  for (int r = 0; r < src.rows; ++r) {
    const auto* p = src.ptr<std::uint16_t>(r);
    for (int c = 0; c < cols; ++c) ++histogram_[p[c]];
  }
  histogramRange(histogram_, static_cast<double>(src.total()) * src.channels(), low_percent_,
                 high_percent_, lo, hi);
}

const cv::Mat& FrameConverter::floatWithSampledRange(const cv::Mat& in, const cv::Mat& src,
                                                     double* lo, double* hi) {
  if (src.depth() == CV_32F) {
    float_ = src;  // shallow; cloned below before any change
  } else {
    src.convertTo(float_, CV_MAKETYPE(CV_32F, src.channels()));
  }
  // A strided sample keeps the percentile cost bounded on large frames.
  samples_.clear();
  const std::size_t n = float_.total() * float_.channels();
  const std::size_t step = std::max<std::size_t>(1, n / 65536);
  const int cols = float_.cols * float_.channels();
  std::size_t k = 0;
  bool non_finite = false;
  for (int r = 0; r < float_.rows; ++r) {
    const float* p = float_.ptr<float>(r);
    for (int c = 0; c < cols; ++c, ++k) {
      if (!std::isfinite(p[c])) {
        non_finite = true;
      } else if (k % step == 0) {
        samples_.push_back(p[c]);
      }
    }
  }
  if (!samples_.empty()) {
    *lo = samplePercentile(samples_, low_percent_);
    *hi = samplePercentile(samples_, high_percent_);
  }
  if (non_finite) {
    // NaN -> the low end; +-inf saturate in the conversion to 8 bits.
    if (float_.data == in.data || float_.data == work_.data) float_ = float_.clone();
    cv::patchNaNs(float_, *lo);
  }
  return float_;
}

void FrameConverter::stretchToOutput(const cv::Mat& src, double lo, double hi) {
  if (have_range_) {
    low_ = (1.0 - smoothing_) * low_ + smoothing_ * lo;
    high_ = (1.0 - smoothing_) * high_ + smoothing_ * hi;
  } else {
    low_ = lo;
    high_ = hi;
    have_range_ = true;
  }
  const double span = std::max(high_ - low_, 1e-6);
  const double alpha = 255.0 / span;
  src.convertTo(out_, CV_MAKETYPE(CV_8U, src.channels()), alpha, -low_ * alpha);  // saturates
}

cv::Mat toCoreFrame(const cv::Mat& in) {
  FrameConverter conv;
  cv::Mat out = conv.convert(in);
  return out.data == in.data ? out : out.clone();
}

}  // namespace eval
}  // namespace obstacle_tracker
