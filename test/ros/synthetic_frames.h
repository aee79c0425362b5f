// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Synthetic test frames for the ROS tests: a bright disc on a sky gradient, drifting slowly, the
// matching sensor_msgs (Image, CameraInfo), and how the tests compare a converted frame with the
// expected one. No data files needed.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>

#include "obstacle_tracker/ros/camera_geometry.h"

namespace obstacle_tracker {
namespace testing {

// Disc centre at frame i (pixels): steady drift (about 2.5 px per frame at 320 px wide), back and
// forth every 80 frames, so a tracker can follow and auto-initialisation sees it move.
inline cv::Point2f discCentre(int i, int width, int height) {
  const int phase = i % 160;
  const float s = phase < 80 ? phase : 160 - phase;  // 0..80..0
  return cv::Point2f(0.2f * width + 0.0078f * width * s, 0.4f * height + 0.002f * height * s);
}

inline float discRadius(int width, int height) { return 0.05f * std::min(width, height); }

// BGR sky: medium blue at the top turning paler towards the horizon; a bright, warm-white disc
// (a sunlit aircraft-like blob) that stands out in colour and brightness.
inline cv::Mat skyFrame(int i, int width = 320, int height = 240) {
  cv::Mat frame(height, width, CV_8UC3);
  for (int r = 0; r < height; ++r) {
    const double t = static_cast<double>(r) / (height - 1);
    const cv::Vec3b colour(static_cast<uchar>(170 + 40 * t), static_cast<uchar>(100 + 60 * t),
                           static_cast<uchar>(40 + 70 * t));
    frame.row(r).setTo(cv::Scalar(colour[0], colour[1], colour[2]));
  }
  cv::circle(frame, discCentre(i, width, height), static_cast<int>(discRadius(width, height)),
             cv::Scalar(200, 245, 255), cv::FILLED, cv::LINE_AA);
  return frame;
}

// A message holding m's pixels under `encoding` (m's own type), packed rows; 16-bit values in
// big-endian byte order when big_endian.
inline sensor_msgs::Image imageMessage(const cv::Mat& m, const std::string& encoding, bool big_endian = false) {
  sensor_msgs::Image msg;
  msg.height = m.rows;
  msg.width = m.cols;
  msg.encoding = encoding;
  msg.is_bigendian = big_endian;
  msg.step = static_cast<std::uint32_t>(m.cols * m.elemSize());
  msg.data.resize(static_cast<std::size_t>(msg.step) * m.rows);
  for (int r = 0; r < m.rows; ++r) {
    std::memcpy(&msg.data[static_cast<std::size_t>(r) * msg.step], m.ptr(r), msg.step);
  }
  if (big_endian && m.depth() == CV_16U) {
    for (std::size_t i = 0; i + 1 < msg.data.size(); i += 2) std::swap(msg.data[i], msg.data[i + 1]);
  }
  return msg;
}

inline sensor_msgs::Image toImageMsg(const cv::Mat& bgr, const std::string& frame_id, double stamp,
                                     std::uint32_t seq) {
  sensor_msgs::Image msg = imageMessage(bgr, sensor_msgs::image_encodings::BGR8);
  msg.header.frame_id = frame_id;
  msg.header.stamp.fromSec(stamp);
  msg.header.seq = seq;
  return msg;
}

// The largest absolute difference between two frames' pixels (0: identical).
inline double maxAbsDiff(const cv::Mat& a, const cv::Mat& b) { return cv::norm(a, b, cv::NORM_INF); }

// Pinhole camera with a 60 degree horizontal field of view, no distortion.
inline sensor_msgs::CameraInfo cameraInfo(const sensor_msgs::Image& image) {
  const double f = 0.5 * image.width / std::tan(30.0 * M_PI / 180.0);
  sensor_msgs::CameraInfo info =
      bridge::pinholeCameraInfo(static_cast<int>(image.width), static_cast<int>(image.height), f);
  info.header = image.header;
  return info;
}

}  // namespace testing
}  // namespace obstacle_tracker
