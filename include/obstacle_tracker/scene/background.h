// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Static scenery for generated flight scenes, rendered once per scene into a panorama larger
// than the frame (the camera then only shifts a window over it): a sky gradient, fractal
// (multi-octave value-noise) clouds lit from above, the sun with glare and a lens streak, distant
// hills, a tree line, buildings and a lattice mast on the horizon, textured ground with haze.
// Colour (CV_8UC3, BGR) or thermal-like counts (CV_16UC1: cold sky, warm ground).
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace scene {

struct BackgroundSpec {
  cv::Size size{640, 480};          // panorama size, pixels
  float frame_height = 480.0f;      // the camera frame's height: sets the scale of features
  float horizon_y = 400.0f;         // panorama row of the horizon (beyond the bottom: no ground)
  float cloud_cover = 0.35f;        // 0 (clear) .. 1 (overcast)
  float cloud_scale = 1.0f;         // multiplies the cloud cell size
  cv::Point2f sun{-200.0f, -200.0f};  // panorama coordinates (may be outside)
  float glare = 0.3f;               // 0 .. 1
  float trees = 0.6f;               // 0 .. 1: share of the horizon with a tree line
  float buildings = 0.3f;           // 0 .. 1
  bool mast = false;                // a lattice telecom mast on the horizon
  int palette = 0;                  // 0 clear blue, 1 hazy, 2 late afternoon
  std::uint64_t seed = 1;
};

// Renders the panorama (CV_8UC3 or CV_16UC1 when mono16).
void renderBackground(const BackgroundSpec& spec, bool mono16, cv::Mat& out);

// A dense cloud for occlusion scenarios: alpha (CV_32FC1, 0..1, fully opaque core of about
// half the size) and premultiplied colour (CV_32FC3 BGR 0..255, or CV_32FC1 thermal counts).
void renderCloudSprite(cv::Size size, std::uint64_t seed, bool mono16, cv::Mat& premultiplied, cv::Mat& alpha);

}  // namespace scene
}  // namespace obstacle_tracker
