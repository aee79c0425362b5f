// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Synthetic test frames for the ROS tests: a bright disc on a sky gradient, drifting slowly, and
// the matching sensor_msgs (Image, CameraInfo). No data files needed.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>

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

inline sensor_msgs::Image toImageMsg(const cv::Mat& bgr, const std::string& frame_id, double stamp,
                                     std::uint32_t seq) {
  sensor_msgs::Image msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp.fromSec(stamp);
  msg.header.seq = seq;
  msg.height = bgr.rows;
  msg.width = bgr.cols;
  msg.encoding = sensor_msgs::image_encodings::BGR8;
  msg.is_bigendian = 0;
  msg.step = static_cast<std::uint32_t>(bgr.cols * bgr.elemSize());
  msg.data.resize(static_cast<std::size_t>(msg.step) * bgr.rows);
  for (int r = 0; r < bgr.rows; ++r) {
    std::memcpy(&msg.data[static_cast<std::size_t>(r) * msg.step], bgr.ptr(r), msg.step);
  }
  return msg;
}

// Pinhole camera with a 60 degree horizontal field of view, no distortion.
inline sensor_msgs::CameraInfo cameraInfo(const sensor_msgs::Image& image) {
  sensor_msgs::CameraInfo info;
  info.header = image.header;
  info.width = image.width;
  info.height = image.height;
  const double f = 0.5 * image.width / std::tan(30.0 * M_PI / 180.0);
  const double cx = 0.5 * image.width - 0.5, cy = 0.5 * image.height - 0.5;
  info.distortion_model = "plumb_bob";
  info.D = {0.0, 0.0, 0.0, 0.0, 0.0};
  info.K = {f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {f, 0.0, cx, 0.0, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

}  // namespace testing
}  // namespace obstacle_tracker
