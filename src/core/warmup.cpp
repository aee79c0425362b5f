// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/warmup.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace obstacle_tracker {
namespace core {

namespace {

constexpr int kWarmupFrames = 4;  // searching, start, tracking twice (scale search included)

}  // namespace

WarmupClip makeWarmupClip(cv::Size size, int type) {
  if (size.width < kWarmupMinSide || size.height < kWarmupMinSide) {
    throw std::invalid_argument("makeWarmupClip: size " + std::to_string(size.width) + "x" +
                                std::to_string(size.height) + " has a side below " + std::to_string(kWarmupMinSide));
  }
  if (type != CV_8UC1 && type != CV_8UC3) throw std::invalid_argument("makeWarmupClip: type must be CV_8UC1 or CV_8UC3");
  // A vertical gradient with fixed-seed noise (a sky), and a dark blob of a tenth of the short
  // side that moves a little each frame: a salient object for the saliency and the filter.
  cv::Mat sky(size, CV_8UC1);
  for (int r = 0; r < size.height; ++r) sky.row(r).setTo(cv::Scalar(150 + 60 * r / size.height));
  cv::Mat noise(size, CV_8UC1);
  cv::RNG rng(12345);
  rng.fill(noise, cv::RNG::NORMAL, 0, 6);
  cv::add(sky, noise, sky);
  const float side = std::max(6.0f, std::min(size.width, size.height) / 10.0f);
  WarmupClip clip;
  for (int i = 0; i < kWarmupFrames; ++i) {
    cv::Mat frame = sky.clone();
    const cv::Point2f centre(size.width * 0.5f + 2.0f * i, size.height * 0.5f + 1.0f * i);
    cv::ellipse(frame, cv::Point(cvRound(centre.x), cvRound(centre.y)),
                cv::Size(cvRound(side / 2), cvRound(side / 3)), 0.0, 0.0, 360.0, cv::Scalar(40), cv::FILLED);
    if (type == CV_8UC3) cv::cvtColor(frame, frame, cv::COLOR_GRAY2BGR);
    if (i == 0) clip.box = cv::Rect2f(centre.x - side / 2, centre.y - side / 3, side, 2 * side / 3);
    clip.frames.push_back(frame);
  }
  return clip;
}

}  // namespace core
}  // namespace obstacle_tracker
