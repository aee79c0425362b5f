// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/ros/image_conversion.h"

#include <cstring>
#include <sstream>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgproc.hpp>

namespace obstacle_tracker {
namespace bridge {
namespace {

constexpr int kNoConversion = -1;

struct EncodingInfo {
  const char* name;
  int depth;       // CV_8U or CV_16U
  int channels;    // in the message
  int to_bgr;      // cv::cvtColor code to BGR (or to grey for kNoConversion with 1 channel)
};

// Bayer names: ROS names the 2x2 pattern from the top-left pixel (rggb = R G / G B), OpenCV from
// the second row's second and third pixels, so ROS rggb is OpenCV's BayerBG (test_ros_conversion
// checks each pattern against a known colour).
const EncodingInfo kEncodings[] = {
    {"mono8", CV_8U, 1, kNoConversion},
    {"8UC1", CV_8U, 1, kNoConversion},
    {"mono16", CV_16U, 1, kNoConversion},
    {"16UC1", CV_16U, 1, kNoConversion},
    {"bgr8", CV_8U, 3, kNoConversion},
    {"8UC3", CV_8U, 3, kNoConversion},
    {"rgb8", CV_8U, 3, cv::COLOR_RGB2BGR},
    {"bgra8", CV_8U, 4, cv::COLOR_BGRA2BGR},
    {"8UC4", CV_8U, 4, cv::COLOR_BGRA2BGR},
    {"rgba8", CV_8U, 4, cv::COLOR_RGBA2BGR},
    {"bgr16", CV_16U, 3, kNoConversion},
    {"rgb16", CV_16U, 3, cv::COLOR_RGB2BGR},
    {"bgra16", CV_16U, 4, cv::COLOR_BGRA2BGR},
    {"rgba16", CV_16U, 4, cv::COLOR_RGBA2BGR},
    {"bayer_rggb8", CV_8U, 1, cv::COLOR_BayerBG2BGR},
    {"bayer_bggr8", CV_8U, 1, cv::COLOR_BayerRG2BGR},
    {"bayer_gbrg8", CV_8U, 1, cv::COLOR_BayerGR2BGR},
    {"bayer_grbg8", CV_8U, 1, cv::COLOR_BayerGB2BGR},
    {"bayer_rggb16", CV_16U, 1, cv::COLOR_BayerBG2BGR},
    {"bayer_bggr16", CV_16U, 1, cv::COLOR_BayerRG2BGR},
    {"bayer_gbrg16", CV_16U, 1, cv::COLOR_BayerGR2BGR},
    {"bayer_grbg16", CV_16U, 1, cv::COLOR_BayerGB2BGR},
    {"yuv422", CV_8U, 2, cv::COLOR_YUV2BGR_UYVY},
    {"yuv422_yuy2", CV_8U, 2, cv::COLOR_YUV2BGR_YUYV},
};

const EncodingInfo* findEncoding(const std::string& encoding) {
  for (const EncodingInfo& info : kEncodings) {
    if (encoding == info.name) return &info;
  }
  return nullptr;
}

bool hostIsBigEndian() {
  const std::uint16_t probe = 1;
  std::uint8_t first;
  std::memcpy(&first, &probe, 1);
  return first == 0;
}

}  // namespace

bool isSupportedEncoding(const std::string& encoding) { return findEncoding(encoding) != nullptr; }

std::vector<std::string> supportedEncodings() {
  std::vector<std::string> names;
  for (const EncodingInfo& info : kEncodings) names.emplace_back(info.name);
  return names;
}

const cv::Mat& FrameConverter::convert(const sensor_msgs::Image& msg) {
  const EncodingInfo* info = findEncoding(msg.encoding);
  if (info == nullptr) {
    throw UnsupportedEncoding("unsupported image encoding '" + msg.encoding + "'");
  }
  const std::uint64_t bytes_per_pixel =
      static_cast<std::uint64_t>(info->channels) * (info->depth == CV_16U ? 2 : 1);
  const std::uint64_t row_bytes = bytes_per_pixel * msg.width;
  std::ostringstream problem;
  if (msg.width == 0 || msg.height == 0) {
    problem << "empty image (" << msg.width << "x" << msg.height << ")";
  } else if (msg.width > (1u << 16) || msg.height > (1u << 16)) {
    problem << "image too large (" << msg.width << "x" << msg.height << ")";
  } else if (msg.step < row_bytes) {
    problem << "step " << msg.step << " is shorter than a row of " << msg.width << " '"
            << msg.encoding << "' pixels (" << row_bytes << " bytes)";
  } else if (msg.data.size() < static_cast<std::uint64_t>(msg.step) * msg.height) {
    problem << "data holds " << msg.data.size() << " bytes, step x height needs "
            << static_cast<std::uint64_t>(msg.step) * msg.height;
  } else if (info->to_bgr == cv::COLOR_YUV2BGR_UYVY || info->to_bgr == cv::COLOR_YUV2BGR_YUYV) {
    if (msg.width % 2 != 0) problem << "yuv422 needs an even width, got " << msg.width;
  }
  if (!problem.str().empty()) {
    throw MalformedImage("malformed '" + msg.encoding + "' image: " + problem.str());
  }

  cv::Mat view;
  const bool swap16 = info->depth == CV_16U && (msg.is_bigendian != 0) != hostIsBigEndian();
  if (swap16) {
    // Wrap the message's bytes and swap them into our buffer.
    const cv::Mat raw(static_cast<int>(msg.height), static_cast<int>(msg.width),
                      CV_MAKETYPE(CV_16U, info->channels),
                      const_cast<std::uint8_t*>(msg.data.data()), msg.step);
    swapped_.create(raw.size(), raw.type());
    const int values = raw.cols * raw.channels();
    for (int r = 0; r < raw.rows; ++r) {
      const std::uint8_t* in = raw.ptr<std::uint8_t>(r);
      std::uint16_t* out = swapped_.ptr<std::uint16_t>(r);
      for (int i = 0; i < values; ++i) {
        out[i] = static_cast<std::uint16_t>((in[2 * i] << 8) | in[2 * i + 1]);
      }
    }
    view = swapped_;
  } else {
    // cv_bridge wraps the message without copying (the message outlives this call).
    view = cv_bridge::toCvShare(msg, boost::shared_ptr<void const>())->image;
  }

  const cv::Mat* colour = &view;
  if (info->to_bgr != kNoConversion) {
    cv::cvtColor(view, converted_, info->to_bgr);
    colour = &converted_;
  }
  if (colour->depth() == CV_16U) {
    stretch_.apply(*colour, out_);
    return out_;
  }
  if (colour == &view) {
    // Copy into our own buffer (reused, no allocation in the steady state) so that nothing
    // downstream can keep a pointer into a message that is about to be freed.
    view.copyTo(out_);
    return out_;
  }
  return converted_;
}

}  // namespace bridge
}  // namespace obstacle_tracker
