// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// sensor_msgs/Image -> the core's frame (CV_8UC1 grey or CV_8UC3 BGR). Every encoding a camera
// driver or a bag commonly carries is converted here, before the core sees the frame:
//   mono8, 8UC1                        -> CV_8UC1 as is
//   mono16, 16UC1 (thermal)            -> CV_8UC1 by a robust percentile stretch (below)
//   bgr8, 8UC3 / rgb8 / bgra8, 8UC4 / rgba8 -> CV_8UC3 BGR (channel swap, alpha dropped)
//   bgr16, rgb16, bgra16, rgba16       -> CV_8UC3 BGR, percentile stretch
//   bayer_{rggb,bggr,gbrg,grbg}8       -> CV_8UC3 BGR (cv::cvtColor demosaicing)
//   bayer_*16                          -> demosaiced at 16 bit, then percentile stretch
//   yuv422 (UYVY), yuv422_yuy2 (YUYV)  -> CV_8UC3 BGR
// Anything else (32FC3, 16SC1, a misspelt name, ...) throws UnsupportedEncoding; a message whose
// size does not match its width/height/step throws MalformedImage. Nothing here reads outside
// the message's data.
//
// 16-bit stretch: thermal cameras send 14-16 bit counts that occupy a narrow band of the range,
// so a fixed >> 8 gives an almost flat image. The band [p_low, p_high] between two percentiles
// of this frame's histogram is mapped linearly onto [0, 255] (values outside saturate), which
// ignores a few hot or dead pixels. Per frame, no temporal smoothing.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <sensor_msgs/Image.h>

namespace obstacle_tracker {
namespace bridge {

struct UnsupportedEncoding : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct MalformedImage : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// True for the encodings listed above.
bool isSupportedEncoding(const std::string& encoding);
std::vector<std::string> supportedEncodings();

// Maps [low, high] percentiles (0..100) of a 16-bit image (any channel count) onto 8 bits.
// Keeps its 65536-bin histogram between calls (no allocation per frame).
class PercentileStretch {
 public:
  PercentileStretch(double low_percentile = 1.0, double high_percentile = 99.0);
  void setPercentiles(double low_percentile, double high_percentile);
  // src: CV_16U with any channel count; dst: CV_8U with the same channel count.
  void apply(const cv::Mat& src, cv::Mat& dst);
  // The input values mapped to 0 and 255 by the last apply().
  std::uint16_t lastLow() const { return last_low_; }
  std::uint16_t lastHigh() const { return last_high_; }

 private:
  double low_percentile_;
  double high_percentile_;
  std::vector<std::uint32_t> histogram_;
  std::uint16_t last_low_ = 0;
  std::uint16_t last_high_ = 0;
};

// Converts one image message. The returned Mat is one of this object's buffers (valid until the
// next call; reused, so no allocation per frame once the size is stable).
class FrameConverter {
 public:
  FrameConverter() = default;
  PercentileStretch& stretch() { return stretch_; }
  const cv::Mat& convert(const sensor_msgs::Image& msg);

 private:
  PercentileStretch stretch_;
  cv::Mat swapped_;   // byte-swapped copy of big-endian 16-bit data
  cv::Mat converted_;  // demosaiced / colour-converted frame (8 or 16 bit)
  cv::Mat out_;
};

}  // namespace bridge
}  // namespace obstacle_tracker
