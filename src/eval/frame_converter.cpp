// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// FrameConverter: any decoded frame to the 8-bit 1- or 3-channel frames the core accepts; the
// rules are in sequence.h, the stretch of deeper frames in core/intensity_stretch.h.
#include "obstacle_tracker/eval/sequence.h"

#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace obstacle_tracker {
namespace eval {

FrameConverter::FrameConverter(double low_percent, double high_percent, double smoothing)
    : stretch_(low_percent, high_percent, smoothing) {}

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
  // A buffer of its own: out_ may still share an earlier 8-bit frame of the caller's.
  stretch_.apply(*src, stretched_);
  return stretched_;
}

cv::Mat toCoreFrame(const cv::Mat& in) {
  FrameConverter conv;
  cv::Mat out = conv.convert(in);
  return out.data == in.data ? out : out.clone();
}

}  // namespace eval
}  // namespace obstacle_tracker
