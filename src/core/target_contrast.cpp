// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// TargetContrast (target_contrast.h): the object's contrast against robust statistics (median,
// MAD) of a ring around its box, as ExtentGrower (extent_grower.cpp) measures a core's surroundings.
#include "obstacle_tracker/core/target_contrast.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/grey_histogram.h"

namespace obstacle_tracker {
namespace core {

namespace {

constexpr int kMinRingPixels = 16;

// Calls visit(pixel) for the window's pixels outside `inside` on a grid of `step` from the
// window's corner; returns how many.
template <typename Visit>
int sampleRing(const cv::Mat& frame, const cv::Rect& window, const cv::Rect& inside, int step, Visit visit) {
  const int channels = frame.channels();
  int count = 0;
  for (int y = window.y; y < window.y + window.height; y += step) {
    const uchar* row = frame.ptr<uchar>(y);
    const bool box_row = y >= inside.y && y < inside.y + inside.height;
    for (int x = window.x; x < window.x + window.width; x += step) {
      if (box_row && x >= inside.x && x < inside.x + inside.width) {
        while (x + step < inside.x + inside.width) x += step;  // jump over the box
        continue;
      }
      visit(row + x * channels);
      ++count;
    }
  }
  return count;
}

}  // namespace

TargetContrast::Reading TargetContrast::read(const cv::Mat& frame, const cv::Rect2f& box) const {
  if (frame.empty() || (frame.type() != CV_8UC1 && frame.type() != CV_8UC3)) return Reading();
  if (!boxHasPixels(box)) return Reading();
  const float fw = static_cast<float>(frame.cols), fh = static_cast<float>(frame.rows);
  auto clampX = [&](float v) { return static_cast<int>(std::min(std::max(v, 0.0f), fw)); };
  auto clampY = [&](float v) { return static_cast<int>(std::min(std::max(v, 0.0f), fh)); };
  const float margin = std::max(kMinMargin, 0.5f * std::max(box.width, box.height));
  const cv::Rect window = grownPixelRect(box, margin, frame.size());
  const cv::Rect inside(cv::Point(clampX(std::round(box.x)), clampY(std::round(box.y))),
                        cv::Point(clampX(std::round(box.x + box.width)), clampY(std::round(box.y + box.height))));
  if (inside.area() <= 0) return Reading();
  // The ring is sampled on a grid of the window, the box on its own grid (an object thinner than
  // the ring's step must not fall between sampled rows).
  const int ring_step = std::max(1, (std::max(window.width, window.height) + kMaxSamples - 1) / kMaxSamples);
  const int box_step = std::max(1, (std::max(inside.width, inside.height) + kMaxBoxSamples - 1) / kMaxBoxSamples);
  const int channels = frame.channels();

  std::array<GreyHistogram, 3> ring_levels{};
  const int ring_count = sampleRing(frame, window, inside, ring_step, [&](const uchar* px) {
    for (int ch = 0; ch < channels; ++ch) ++ring_levels[static_cast<std::size_t>(ch)][px[ch]];
  });
  if (ring_count < kMinRingPixels) return Reading();
  std::array<int, 3> bg{0, 0, 0};
  for (int ch = 0; ch < channels; ++ch) {
    const auto c = static_cast<std::size_t>(ch);
    bg[c] = histogramQuantile(ring_levels[c], ring_count, 0.5);
  }
  auto contrastOf = [&](const uchar* px) {
    int v = 0;
    for (int ch = 0; ch < channels; ++ch) v = std::max(v, std::abs(static_cast<int>(px[ch]) - bg[static_cast<std::size_t>(ch)]));
    return static_cast<std::size_t>(v);
  };
  GreyHistogram ring_hist{}, box_hist{};
  sampleRing(frame, window, inside, ring_step, [&](const uchar* px) { ++ring_hist[contrastOf(px)]; });
  int box_count = 0;
  for (int y = inside.y; y < inside.y + inside.height; y += box_step) {
    const uchar* row = frame.ptr<uchar>(y);
    for (int x = inside.x; x < inside.x + inside.width; x += box_step, ++box_count) {
      ++box_hist[contrastOf(row + x * channels)];
    }
  }
  const double noise = std::max(1.0, kMadToSigma * histogramGroupedMedian(ring_hist, ring_count));
  const int rank = std::max(kSignalRank, box_count / kSignalShareInverse);
  const int ring_rank = std::max(kSignalRank, ring_count / kSignalShareInverse);
  Reading reading;
  reading.ratio = static_cast<float>(histogramRankFromTop(box_hist, rank) / noise);
  reading.noise = static_cast<float>(noise);
  reading.ring_ratio = static_cast<float>(histogramRankFromTop(ring_hist, ring_rank) / noise);
  return reading;
}

bool TargetContrast::checkable(const Reading& reference) {
  // A ring not read (a Reading built by hand) is taken as clutter: only a firm start counts.
  const float need = reference.ring_ratio >= 0.0f
                         ? std::min(kFirmReference, std::max(kMinReference, kStandOut * reference.ring_ratio))
                         : kFirmReference;
  return reference.ratio >= need;
}

bool TargetContrast::lost(const Reading& reference, const Reading& current) {
  if (!checkable(reference) || current.ratio == kUnknown) return false;
  if (current.noise > kMaxNoiseRise * reference.noise) return false;
  // Under the floor of the ring's noise now, or (the ring calmer than at the start) its signal
  // under the floor of the noise at the start. A faint start has a lower floor: half of what it
  // read, so that its own dips into the noise are not taken for a loss. A strong start (over
  // kFloor / kFadeShare) has a higher one, kFadeShare of what it read: a box that slid off a drone
  // 100 sigmas out of the sky and holds its edge, a few sigmas, has lost it.
  const float floor = std::max(std::min(kFloor, kFloorShare * reference.ratio), kFadeShare * reference.ratio);
  return current.ratio < floor || current.ratio * current.noise < floor * reference.noise;
}

}  // namespace core
}  // namespace obstacle_tracker
