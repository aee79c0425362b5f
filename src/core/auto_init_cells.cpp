// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// AutoInitializer::Impl (auto_init_impl.h), step 3a: where the candidates start. Cell-level peaks
// of the candidate map P, and isolated peaks of the local contrast map (the second source).
#include <algorithm>
#include <array>
#include <cstdlib>
#include <functional>

#include <opencv2/core.hpp>

#include "auto_init_impl.h"

namespace obstacle_tracker {
namespace core {

using namespace auto_init_detail;  // NOLINT(build/namespaces): the auto-initialiser's own constants

// Maximum of each kCell x kCell cell of a CV_8U map (row-major, ceil(cols / kCell) per row).
void AutoInitializer::Impl::cellMaxima(const cv::Mat& m, std::vector<float>& cells) {
  const int rows = m.rows, cols = m.cols;
  const int gw = (cols + kCell - 1) / kCell, gh = (rows + kCell - 1) / kCell;
  cells.assign(static_cast<size_t>(gw) * gh, -1.0f);
  for (int r = 0; r < rows; ++r) {
    const uchar* o = m.ptr<uchar>(r);
    float* cm = &cells[static_cast<size_t>(r / kCell) * gw];
    for (int gx = 0; gx < gw; ++gx) {
      const int x0 = gx * kCell, x1 = std::min(cols, x0 + kCell);
      uchar v = 0;
      for (int x = x0; x < x1; ++x) v = std::max(v, o[x]);  // vectorisable max
      cm[gx] = std::max(cm[gx], static_cast<float>(v));
    }
  }
}

// No neighbour of the cell (8-connected) has a larger maximum.
bool AutoInitializer::Impl::isCellMaximum(const std::vector<float>& cells, int gx, int gy, int gw, int gh) {
  const float v = cells[static_cast<size_t>(gy) * gw + gx];
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = gx + dx, ny = gy + dy;
      if ((dx || dy) && nx >= 0 && ny >= 0 && nx < gw && ny < gh && cells[static_cast<size_t>(ny) * gw + nx] > v)
        return false;
    }
  return true;
}

// Where in the cell its maximum `v` is (first in raster order).
cv::Point2f AutoInitializer::Impl::cellArgmax(const cv::Mat& m, int gx, int gy, float v) {
  const int x0 = gx * kCell, y0 = gy * kCell;
  const int x1 = std::min(m.cols, x0 + kCell), y1 = std::min(m.rows, y0 + kCell);
  for (int y = y0; y < y1; ++y) {
    const uchar* o = m.ptr<uchar>(y);
    for (int x = x0; x < x1; ++x)
      if (o[x] == static_cast<uchar>(v)) return {static_cast<float>(x), static_cast<float>(y)};
  }
  return {static_cast<float>(x0), static_cast<float>(y0)};
}

// Peaks of P that are maxima of their kCell x kCell cell and its 8 neighbours (at least 8 and a
// tenth of the frame's best), strongest first, at most kPoolFactor x auto_init_candidates.
void AutoInitializer::Impl::cellPeaks(const cv::Mat& p) {
  candidates.clear();
  const int gw = (p.cols + kCell - 1) / kCell, gh = (p.rows + kCell - 1) / kCell;
  cellMaxima(p, cell_max);
  float global_max = 0.0f;
  for (float v : cell_max) global_max = std::max(global_max, v);
  const float floor_value = std::max(kMinPeakLevel, kMinPeakShare * static_cast<float>(static_cast<int>(global_max)));
  for (int gy = 0; gy < gh; ++gy)
    for (int gx = 0; gx < gw; ++gx) {
      const float v = cell_max[static_cast<size_t>(gy) * gw + gx];
      if (v < floor_value || !isCellMaximum(cell_max, gx, gy, gw, gh)) continue;
      Candidate c;
      c.peak = c.strength = v;
      c.centre = cellArgmax(p, gx, gy, v);
      candidates.push_back(c);
    }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.peak > b.peak; });
  const size_t pool = static_cast<size_t>(kPoolFactor * params.auto_init_candidates);
  if (candidates.size() > pool) candidates.resize(pool);
}

// Clutter around cell (gx, gy): the kClutterRank-th largest maximum of the (up to 16) cells at
// Chebyshev distance 2, the ring just outside an object of up to two cells. An object alone on
// sky has a quiet ring; a tree line, a roof edge or a texture has at least kClutterRank loud
// cells in it, while one straight line through the cell crosses the ring in two or three.
float AutoInitializer::Impl::ringClutter(const std::vector<float>& cells, int gx, int gy, int gw, int gh) {
  std::array<float, 16> ring{};
  int n = 0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      const int nx = gx + dx, ny = gy + dy;
      if (std::max(std::abs(dx), std::abs(dy)) != 2 || nx < 0 || ny < 0 || nx >= gw || ny >= gh) continue;
      ring[static_cast<size_t>(n++)] = cells[static_cast<size_t>(ny) * gw + nx];
    }
  if (n < kClutterRank) return 0.0f;
  std::nth_element(ring.begin(), ring.begin() + (kClutterRank - 1), ring.begin() + n, std::greater<float>());
  return ring[kClutterRank - 1];
}

// The second source: cells of the local contrast map that stand out of the clutter around them
// (isolation = cell maximum / max(kClutterFloor, ringClutter) >= kMinIsolation), most isolated
// first, at most kPoolFactor x kIsolatedCandidates, appended to the candidates. P multiplies the
// local contrast by MBD saliency normalised to the frame's most salient object, so a small bird
// or drone on plain sky beside a bright structure gets a few grey levels of P, under the peaks'
// floor, while its contrast is several times that of the sky around it. This is the cell-level
// form of the local contrast measure of infrared small-target detection (Chen et al., "A Local
// Contrast Method for Small Infrared Target Detection", IEEE TGRS 2014).
void AutoInitializer::Impl::isolatedPeaks(const cv::Mat& p) {
  isolated.clear();
  if (contrast_map.empty()) return;
  const int gw = (contrast_map.cols + kCell - 1) / kCell, gh = (contrast_map.rows + kCell - 1) / kCell;
  isolated.reserve(static_cast<size_t>(gw) * gh);  // allocates once per working size
  cellMaxima(contrast_map, cell_contrast);
  for (int gy = 0; gy < gh; ++gy)
    for (int gx = 0; gx < gw; ++gx) {
      const float v = cell_contrast[static_cast<size_t>(gy) * gw + gx];
      if (v < kMinIsolation * kClutterFloor || !isCellMaximum(cell_contrast, gx, gy, gw, gh)) continue;
      const float isolation = v / std::max(kClutterFloor, ringClutter(cell_contrast, gx, gy, gw, gh));
      if (isolation < kMinIsolation) continue;
      Candidate c;
      c.peak = v;
      c.isolation = isolation;
      c.from_contrast = true;
      c.centre = cellArgmax(contrast_map, gx, gy, v);
      c.strength = p.at<uchar>(cvRound(c.centre.y), cvRound(c.centre.x));
      // A peak on a still pixel goes to the back of the pool: many fixed specks (lamps, stars,
      // dead pixels) must not push a moving one out before keepCandidate sees which is still.
      c.still = params.auto_init_reject_static && frame_index > 0 && still.size() == contrast_map.size() &&
                still.at<uchar>(cvRound(c.centre.y), cvRound(c.centre.x)) >= kStillFrames;
      isolated.push_back(c);
    }
  const size_t pool = std::min(isolated.size(), static_cast<size_t>(kPoolFactor * kIsolatedCandidates));
  std::partial_sort(isolated.begin(), isolated.begin() + static_cast<std::ptrdiff_t>(pool), isolated.end(),
                    [](const Candidate& a, const Candidate& b) {
                      return a.still != b.still ? b.still : a.isolation > b.isolation;
                    });
  candidates.insert(candidates.end(), isolated.begin(), isolated.begin() + static_cast<std::ptrdiff_t>(pool));
}

}  // namespace core
}  // namespace obstacle_tracker
