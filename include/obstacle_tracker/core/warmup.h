// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// A few synthetic frames that take every per-frame path of the pipeline once (whole-frame
// saliency and auto-initialisation while searching, a filter started on a box, tracking with the
// scale search), so that Pipeline::prepare can make its buffers, OpenCV's lazily built tables
// and thread pool, and the pages behind them before the first camera frame counts.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

struct WarmupClip {
  std::vector<cv::Mat> frames;  // of the asked size and type, a textured sky with a moving blob
  cv::Rect2f box;               // the blob in frames[0]
};

// Smallest side of a warm-up clip: smaller frames are processed in no time anyway.
constexpr int kWarmupMinSide = 16;

// size at least kWarmupMinSide on both sides; type CV_8UC1 or CV_8UC3 (throws
// std::invalid_argument otherwise).
WarmupClip makeWarmupClip(cv::Size size, int type);

}  // namespace core
}  // namespace obstacle_tracker
