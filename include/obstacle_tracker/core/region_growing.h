// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// 8-connected region growing, breadth first: the loop the auto-initialiser's candidate regions
// (auto_init_candidates.cpp) and the extent grower's object (extent_grower.cpp) share. The
// callers differ in what joins a region and how a pixel is marked as taken (a label image that
// later seeds look up; clearing a scratch image), so those two are the caller's functions.
// cv::floodFill would grow the same regions but allocates its work buffer on every call, and the
// auto-initialiser needs the region's pixels and labels that outlive the call.
#pragma once

#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

// Grows from the seeds in `queue` (pixel indices y * cols + x, each already marked as taken).
// Each pixel taken from the queue, in order, is first handed to visit(x, y); when that returns
// false the growth stops and growRegion8 returns false. Then each of its 8 neighbours (rows
// dy = -1, 0, 1, within a row dx = -1, 0, 1) inside `clip` for which claim(x, y) returns true is
// appended; claim accepts a pixel that belongs to the region and marks it as taken, so that no
// pixel is appended twice. On return `queue` holds the pixels reached, in the order reached.
// No allocation once queue's capacity holds the region.
template <typename Claim, typename Visit>
bool growRegion8(std::vector<int>& queue, int cols, const cv::Rect& clip, Claim&& claim, Visit&& visit) {
  const int x_lo = clip.x, x_hi = clip.x + clip.width - 1;
  const int y_lo = clip.y, y_hi = clip.y + clip.height - 1;
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int y = queue[q] / cols, x = queue[q] % cols;
    if (!visit(x, y)) return false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < x_lo || nx > x_hi || ny < y_lo || ny > y_hi || !claim(nx, ny)) continue;
        queue.push_back(ny * cols + nx);
      }
  }
  return true;
}

}  // namespace core
}  // namespace obstacle_tracker
