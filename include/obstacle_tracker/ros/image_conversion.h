// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// sensor_msgs/Image -> the core's frame (CV_8UC1 grey or CV_8UC3 BGR). Every encoding a camera
// driver or a bag commonly carries is converted here, before the core sees the frame:
//   mono8, 8UC1                        -> CV_8UC1 as is
//   mono16, 16UC1 (thermal)            -> CV_8UC1 by core::IntensityStretch (percentiles)
//   bgr8, 8UC3 / rgb8 / bgra8, 8UC4 / rgba8 -> CV_8UC3 BGR (channel swap, alpha dropped)
//   bgr16, rgb16, bgra16, rgba16       -> CV_8UC3 BGR, percentile stretch
//   bayer_{rggb,bggr,gbrg,grbg}8       -> CV_8UC3 BGR (demosaiced)
//   bayer_*16                          -> demosaiced at 16 bit, then percentile stretch
//   yuv422 (UYVY), yuv422_yuy2 (YUYV)  -> CV_8UC3 BGR
// The colour conversions are cv_bridge's (cv_bridge::cvtColor), but for yuv422_yuy2, which it
// does not know; the 8UCn / 16UC1 names are taken as grey, BGR and BGRA. 16-bit data in either
// byte order (is_bigendian) is read correctly.
// Anything else (32FC3, 16SC1, a misspelt name, ...) throws UnsupportedEncoding; a message whose
// data is not exactly step x height bytes, whose step is shorter than a row or (16-bit) odd, or
// that is empty or has a side above 65536 throws MalformedImage. Nothing here reads outside the
// message's data.
//
// 16-bit frames go through core::IntensityStretch (core/intensity_stretch.h), the rule and the
// defaults the tools use too: percentiles mapped onto [0, 255], smoothed over frames.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <sensor_msgs/Image.h>

#include "obstacle_tracker/core/intensity_stretch.h"

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

// Converts one image message. The returned Mat is one of this object's buffers, never the
// message's bytes (valid until the next call). mono8, 8UC1, bgr8 and 8UC3 are copied, and mono16,
// 16UC1 and bgr16 stretched, into buffers reused from frame to frame (no allocation once the size
// is stable); the other encodings go through cv_bridge::cvtColor, which allocates its result on
// every call.
class FrameConverter {
 public:
  FrameConverter() = default;
  core::IntensityStretch& stretch() { return stretch_; }
  const cv::Mat& convert(const sensor_msgs::Image& msg);

 private:
  core::IntensityStretch stretch_;
  cv::Mat swapped_;    // 16-bit data turned into the host's byte order
  cv::Mat converted_;  // demosaiced / colour-converted frame (8 or 16 bit)
  cv::Mat out_;        // the copied or stretched frame
};

}  // namespace bridge
}  // namespace obstacle_tracker
