// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// ExtentGrower (extent_grower.h): from the bright core that Otsu leaves of a small or blurred
// object to the object's visible extent, by region growing from the core on the contrast against
// the local background (robust statistics of the window's outer ring: median background level,
// MAD noise). The level is relative to the core's own contrast, as the edge of a blurred blob is
// where its profile has fallen to a small share of its height.
#include "obstacle_tracker/core/extent_grower.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/grey_histogram.h"
#include "obstacle_tracker/core/region_growing.h"

namespace obstacle_tracker {
namespace core {

namespace {

constexpr float kMinMargin = 6.0f;   // px of window around the core at least
constexpr int kRing = 2;             // px: the window's outer ring gives background and noise
constexpr double kNoiseSigmas = 3.0; // object pixels stand this many noise sigmas out
constexpr int kMinLevel = 2;         // grey levels: the object's contrast is at least this
constexpr float kMaxGrowth = 4.0f;   // the grown box covers at most this x the core's area
constexpr double kCorePercentile = 0.9;

bool inRing(int x, int y, int w, int h) { return x < kRing || y < kRing || x >= w - kRing || y >= h - kRing; }

}  // namespace

cv::Rect2f ExtentGrower::grow(const cv::Mat& frame, const cv::Rect2f& core, double share) {
  if (!(share > 0.0) || frame.empty() || (frame.type() != CV_8UC1 && frame.type() != CV_8UC3)) return core;
  if (!boxHasPixels(core)) return core;
  // Window and core in pixels, clipped to the frame.
  const float margin = std::max(kMinMargin, std::max(core.width, core.height));
  const cv::Rect window = grownPixelRect(core, margin, frame.size());
  const cv::Rect core_px = grownPixelRect(core, 0.0f, frame.size());
  const int wx0 = window.x, wy0 = window.y;
  const int w = window.width, h = window.height;
  if (w < 2 * kRing + 3 || h < 2 * kRing + 3) return core;
  const int cx0 = std::max(kRing, core_px.x - wx0);
  const int cy0 = std::max(kRing, core_px.y - wy0);
  const int cx1 = std::min(w - kRing, core_px.br().x - wx0);
  const int cy1 = std::min(h - kRing, core_px.br().y - wy0);
  if (cx1 <= cx0 || cy1 <= cy0) return core;

  const cv::Mat win = frame(cv::Rect(wx0, wy0, w, h));
  const int channels = frame.channels();

  // Background level per channel: median of the ring.
  std::array<int, 3> bg{0, 0, 0};
  int ring_count = 0;
  {
    std::array<GreyHistogram, 3> hist{};
    for (int y = 0; y < h; ++y) {
      const uchar* row = win.ptr<uchar>(y);
      for (int x = 0; x < w; ++x) {
        if (!inRing(x, y, w, h)) {
          x = w - kRing - 1;  // jump over the inside of the row
          continue;
        }
        for (int ch = 0; ch < channels; ++ch) ++hist[static_cast<std::size_t>(ch)][row[x * channels + ch]];
        ++ring_count;
      }
    }
    for (int ch = 0; ch < channels; ++ch) {
      const auto c = static_cast<std::size_t>(ch);
      bg[c] = histogramQuantile(hist[c], ring_count, 0.5);
    }
  }

  // Contrast image, its noise on the ring and its level in the core.
  cv::Mat c = contrast_arena_.get(h, w, CV_8U);
  GreyHistogram ring_hist{}, core_hist{};
  for (int y = 0; y < h; ++y) {
    const uchar* row = win.ptr<uchar>(y);
    uchar* out = c.ptr<uchar>(y);
    for (int x = 0; x < w; ++x) {
      int v = 0;
      for (int ch = 0; ch < channels; ++ch) {
        v = std::max(v, std::abs(static_cast<int>(row[x * channels + ch]) - bg[static_cast<std::size_t>(ch)]));
      }
      out[x] = static_cast<uchar>(v);
      if (inRing(x, y, w, h)) ++ring_hist[static_cast<std::size_t>(v)];
      else if (x >= cx0 && x < cx1 && y >= cy0 && y < cy1) ++core_hist[static_cast<std::size_t>(v)];
    }
  }
  const double noise = kMadToSigma * histogramQuantile(ring_hist, ring_count, 0.5);
  const int peak = histogramQuantile(core_hist, (cx1 - cx0) * (cy1 - cy0), kCorePercentile);
  const double level = std::max({share * peak, kNoiseSigmas * noise, static_cast<double>(kMinLevel)});
  if (peak <= level) return core;  // the core does not stand out of the background
  const int threshold = static_cast<int>(std::floor(level));  // object: c > threshold

  cv::Rect object;
  if (!growRegion(c, cv::Rect(cv::Point(cx0, cy0), cv::Point(cx1, cy1)), threshold, object)) return core;
  // The union of the core box and the object's box.
  const float ox0 = std::min(core.x, static_cast<float>(wx0 + object.x));
  const float oy0 = std::min(core.y, static_cast<float>(wy0 + object.y));
  const float ox1 = std::max(core.x + core.width, static_cast<float>(wx0 + object.x + object.width));
  const float oy1 = std::max(core.y + core.height, static_cast<float>(wy0 + object.y + object.height));
  const cv::Rect2f grown(ox0, oy0, ox1 - ox0, oy1 - oy0);
  if (grown.area() > kMaxGrowth * core.area()) return core;
  return grown;
}

// Region growing in the contrast image `c` from the core's pixels above `threshold`; visited pixels
// are set to 0. The queue holds each window pixel at most once. False when the core has no such
// pixel or the region reaches the window's edge (joined to the surroundings); else `bounds` is the
// region's box in window pixels.
bool ExtentGrower::growRegion(cv::Mat& c, const cv::Rect& core, int threshold, cv::Rect& bounds) {
  const int w = c.cols, h = c.rows;
  const int cx0 = core.x, cy0 = core.y, cx1 = core.x + core.width, cy1 = core.y + core.height;
  if (queue_.capacity() < static_cast<std::size_t>(w) * h) queue_.reserve(static_cast<std::size_t>(w) * h);
  queue_.clear();
  for (int y = cy0; y < cy1; ++y) {
    uchar* row = c.ptr<uchar>(y);
    for (int x = cx0; x < cx1; ++x) {
      if (row[x] > threshold) {
        row[x] = 0;
        queue_.push_back(y * w + x);
      }
    }
  }
  if (queue_.empty()) return false;
  int minx = w, miny = h, maxx = -1, maxy = -1;
  auto claim = [&](int x, int y) {
    uchar& v = c.ptr<uchar>(y)[x];
    if (v <= threshold) return false;
    v = 0;
    return true;
  };
  auto visit = [&](int x, int y) {
    minx = std::min(minx, x);
    maxx = std::max(maxx, x);
    miny = std::min(miny, y);
    maxy = std::max(maxy, y);
    return x != 0 && y != 0 && x != w - 1 && y != h - 1;  // false: joined to the surroundings
  };
  if (!growRegion8(queue_, w, cv::Rect(0, 0, w, h), claim, visit)) return false;
  bounds = cv::Rect(cv::Point(minx, miny), cv::Point(maxx + 1, maxy + 1));
  return true;
}

}  // namespace core
}  // namespace obstacle_tracker
