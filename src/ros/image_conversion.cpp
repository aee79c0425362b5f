// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The checks are ours: they run before a byte of the message is read and name the problem. The
// sizes come from sensor_msgs::image_encodings, the pixel types from cv_bridge::getCvType and the
// colour conversions (channel order, alpha, Bayer demosaicing, yuv422) from cv_bridge::cvtColor.
// Two cases stay here, both measured with Debian's cv_bridge 1.16.2 and sensor_msgs 1.13.1:
//   - yuv422_yuy2: neither knows the name (image_encodings::numChannels throws "Unknown encoding",
//     cv_bridge "Unrecognized image encoding"), so its size and its cv::cvtColor code are ours.
//   - 16-bit data whose byte order is not the host's: cv_bridge does swap the bytes, but hands the
//     result back as CV_8UC2 / CV_8UC6 / CV_8UC8 instead of CV_16UC1 / 3 / 4, and converting such
//     a message to another encoding either throws inside cv::cvtColor (a 6-channel "BGR" image, a
//     2-channel Bayer mosaic) or keeps the wrong type (bgr16 to bgr8 gives CV_8UC6). The swap
//     below is the only pixel loop left.
#include "obstacle_tracker/ros/image_conversion.h"

#include <cstdint>
#include <iterator>
#include <sstream>
#include <utility>

#include <boost/endian/conversion.hpp>
#include <boost/make_shared.hpp>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/image_encodings.h>

namespace obstacle_tracker {
namespace bridge {
namespace enc = sensor_msgs::image_encodings;

namespace {

const char* const kYuy2 = "yuv422_yuy2";

// The encodings accepted, in the order the nodelet lists them.
const char* const kAccepted[] = {
    "mono8",        "8UC1",         "mono16",       "16UC1",        "bgr8",        "8UC3",
    "rgb8",         "bgra8",        "8UC4",         "rgba8",        "bgr16",       "rgb16",
    "bgra16",       "rgba16",       "bayer_rggb8",  "bayer_bggr8",  "bayer_gbrg8", "bayer_grbg8",
    "bayer_rggb16", "bayer_bggr16", "bayer_gbrg16", "bayer_grbg16", "yuv422",      kYuy2,
};

// The generic names carry no colour order and cv_bridge refuses to colour-convert them; the
// drivers that send them mean grey, BGR and BGRA, so they are converted as those.
const std::pair<const char*, const char*> kGenericAs[] = {
    {"8UC1", "mono8"}, {"8UC3", "bgr8"}, {"8UC4", "bgra8"}, {"16UC1", "mono16"}};

bool accepted(const std::string& encoding) {
  for (const char* name : kAccepted) {
    if (encoding == name) return true;
  }
  return false;
}

struct Layout {
  std::string encoding;  // cv_bridge's name for the message's pixels
  int channels;
  int sample_bytes;  // 1 or 2
  bool yuy2;
};

// `encoding` must be accepted(). yuv422_yuy2 is unknown to image_encodings (see the top).
Layout layoutOf(const std::string& encoding) {
  if (encoding == kYuy2) return {encoding, 2, 1, true};
  std::string name = encoding;
  for (const auto& generic : kGenericAs) {
    if (encoding == generic.first) name = generic.second;
  }
  return {name, enc::numChannels(name), enc::bitDepth(name) / 8, false};
}

// What the core gets: grey stays grey, everything else becomes BGR; 16-bit frames stay 16-bit
// until core::IntensityStretch.
const std::string& targetOf(const Layout& layout) {
  const bool grey = enc::isMono(layout.encoding);
  if (layout.sample_bytes == 2) return grey ? enc::MONO16 : enc::BGR16;
  return grey ? enc::MONO8 : enc::BGR8;
}

// Throws MalformedImage unless the message's data holds exactly step x height bytes and a row of
// `layout` pixels fits in a step. cv_bridge checks this too, but in 32-bit arithmetic (a
// 65536 x 65536 image with no data passes it) and with a message that names none of the fields.
void validate(const sensor_msgs::Image& msg, const Layout& layout) {
  const std::uint64_t row_bytes =
      static_cast<std::uint64_t>(layout.channels) * layout.sample_bytes * msg.width;
  const std::uint64_t needed = static_cast<std::uint64_t>(msg.step) * msg.height;
  std::ostringstream problem;
  if (msg.width == 0 || msg.height == 0) {
    problem << "empty image (" << msg.width << "x" << msg.height << ")";
  } else if (msg.width > (1u << 16) || msg.height > (1u << 16)) {
    problem << "image too large (" << msg.width << "x" << msg.height << ")";
  } else if (msg.step < row_bytes) {
    problem << "step " << msg.step << " is shorter than a row of " << msg.width << " '"
            << msg.encoding << "' pixels (" << row_bytes << " bytes)";
  } else if (msg.data.size() < needed) {
    problem << "data holds " << msg.data.size() << " bytes, step x height needs " << needed;
  } else if (msg.data.size() > needed) {
    problem << "data holds " << msg.data.size() << " bytes, more than step x height (" << needed
            << ")";
  } else if (layout.sample_bytes == 2 && msg.step % 2 != 0) {
    problem << "step " << msg.step << " is not a whole number of 16-bit samples";
  } else if (layout.channels == 2 && msg.width % 2 != 0) {
    problem << "yuv422 needs an even width, got " << msg.width;
  }
  if (!problem.str().empty()) {
    throw MalformedImage("malformed '" + msg.encoding + "' image: " + problem.str());
  }
}

// Reverses the bytes of every 16-bit value of `raw` into `out` (reallocated only when the size or
// type changes).
void swapBytes16(const cv::Mat& raw, cv::Mat& out) {
  out.create(raw.size(), raw.type());
  const int values = raw.cols * raw.channels();
  for (int r = 0; r < raw.rows; ++r) {
    const std::uint16_t* in = raw.ptr<std::uint16_t>(r);
    std::uint16_t* dst = out.ptr<std::uint16_t>(r);
    for (int i = 0; i < values; ++i) dst[i] = boost::endian::endian_reverse(in[i]);
  }
}

// The message's pixels in the host's byte order: a view of the message's bytes, or `swapped`. The
// view is what cv_bridge::toCvShare gives, built here from cv_bridge's type because toCvShare
// allocates a CvImage and copies the header on every call, and sends every message flagged
// big-endian through toCvCopy: a copy of an 8-bit image (whose flag means nothing) and the mistyped
// 16-bit result described at the top of this file.
cv::Mat pixels(const sensor_msgs::Image& msg, const Layout& layout, cv::Mat& swapped) {
  const int type = layout.yuy2 ? CV_8UC2 : cv_bridge::getCvType(layout.encoding);
  const cv::Mat view(static_cast<int>(msg.height), static_cast<int>(msg.width), type,
                     const_cast<std::uint8_t*>(msg.data.data()), msg.step);
  const bool big_endian_host = boost::endian::order::native == boost::endian::order::big;
  if (layout.sample_bytes == 1 || (msg.is_bigendian != 0) == big_endian_host) return view;
  swapBytes16(view, swapped);
  return swapped;
}

}  // namespace

bool isSupportedEncoding(const std::string& encoding) { return accepted(encoding); }

std::vector<std::string> supportedEncodings() {
  return std::vector<std::string>(std::begin(kAccepted), std::end(kAccepted));
}

const cv::Mat& FrameConverter::convert(const sensor_msgs::Image& msg) {
  if (!accepted(msg.encoding)) {
    throw UnsupportedEncoding("unsupported image encoding '" + msg.encoding + "'");
  }
  const Layout layout = layoutOf(msg.encoding);
  validate(msg, layout);
  const cv::Mat in = pixels(msg, layout, swapped_);
  const std::string& target = targetOf(layout);

  const cv::Mat* frame = &in;
  if (layout.yuy2) {
    cv::cvtColor(in, converted_, cv::COLOR_YUV2BGR_YUYV);
    frame = &converted_;
  } else if (layout.encoding != target) {
    // cv_bridge has no destination argument: each conversion allocates its result.
    const cv_bridge::CvImageConstPtr source =
        boost::make_shared<cv_bridge::CvImage>(std_msgs::Header(), layout.encoding, in);
    converted_ = cv_bridge::cvtColor(source, target)->image;
    frame = &converted_;
  }
  if (frame->depth() == CV_16U) {
    stretch_.apply(*frame, out_);
    return out_;
  }
  if (frame == &in) {
    // Copy into our own buffer (reused, no allocation in the steady state) so that nothing
    // downstream can keep a pointer into a message that is about to be freed.
    in.copyTo(out_);
    return out_;
  }
  return converted_;
}

}  // namespace bridge
}  // namespace obstacle_tracker
