// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// RegionExtractor (region_extractor.h): Otsu threshold of an 8-bit saliency map, 8-connected
// regions, their statistics, filtering and ranking (steps 3 and 4 of the saliency detector,
// saliency.cpp).
//
// Ranking score: the region's saliency mass, area (full-frame px^2) x mean saliency in [0, 1].
// Between regions of similar saliency this is the paper's "largest region"; it keeps a large but
// faint patch from outranking a compact bright one. saliency_rank_by_area = true gives the
// paper's rule exactly (score = area). In windowed re-detection the mass is
// multiplied by exp(-d^2 / (2 s^2)), d the distance of the region's box centre from the window
// centre (the last position) and s half the window's longer side, so that of two similar
// candidates the one nearer the last position wins.
#include "obstacle_tracker/core/region_extractor.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace obstacle_tracker {
namespace core {

namespace {

// Root of label x, halving the path on the way.
inline int findRoot(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// Joins the sets of a and b; the smaller label stays the root. Returns the root.
inline int unite(std::vector<int>& parent, int a, int b) {
  a = findRoot(parent, a);
  b = findRoot(parent, b);
  if (a == b) return a;
  if (a < b) {
    parent[b] = a;
    return a;
  }
  parent[a] = b;
  return b;
}

}  // namespace

// First pass over binary_: provisional labels into labels_ and their equivalences in parent_;
// then parent_[provisional] = final label (1..n-1; 0 background). Returns n (with background).
int RegionExtractor::labelComponents() {
  const int rows = binary_.rows, cols = binary_.cols;
  parent_.clear();
  // At most one new label per 2x2 block; reserved once per largest map (no allocation after).
  parent_.reserve(static_cast<size_t>((rows + 1) / 2) * static_cast<size_t>((cols + 1) / 2) + 1);
  parent_.push_back(0);
  for (int r = 0; r < rows; ++r) {
    const uchar* b = binary_.ptr<uchar>(r);
    int* l = labels_.ptr<int>(r);
    const int* up = r > 0 ? labels_.ptr<int>(r - 1) : nullptr;
    for (int c = 0; c < cols; ++c) {
      if (b[c] == 0) {
        l[c] = 0;
        continue;
      }
      const int n = up != nullptr ? up[c] : 0;
      if (n != 0) {
        // N touches NW, NE and W (8-connected), so they are already in its set.
        l[c] = n;
        continue;
      }
      // W and NW touch each other; NE touches neither when N is background.
      int a = c > 0 ? l[c - 1] : 0;
      if (a == 0 && up != nullptr && c > 0) a = up[c - 1];
      const int ne = up != nullptr && c + 1 < cols ? up[c + 1] : 0;
      if (a != 0 && ne != 0) {
        l[c] = unite(parent_, a, ne);
      } else if (a != 0 || ne != 0) {
        l[c] = a != 0 ? a : ne;
      } else {
        l[c] = static_cast<int>(parent_.size());
        parent_.push_back(l[c]);
      }
    }
  }
  // A non-root's parent is a smaller label, already final when it is reached.
  int next = 1;
  for (size_t i = 1; i < parent_.size(); ++i) {
    const int p = parent_[i];
    parent_[i] = p == static_cast<int>(i) ? next++ : parent_[static_cast<size_t>(p)];
  }
  return next;
}

double RegionExtractor::extract(const cv::Mat& map, const Geometry& g, const SaliencyParams& params,
                                std::vector<SalientRegion>& regions) {
  regions.clear();
  const int rows = map.rows, cols = map.cols;
  binary_ = binary_arena_.get(rows, cols, CV_8U);
  labels_ = labels_arena_.get(rows, cols, CV_32S);
  const double t = cv::threshold(map, binary_, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  // 8-connected components in two raster passes (the classic union-find labelling, Rosenfeld &
  // Pfaltz 1966; Wu, Otoo & Suzuki 2009 for the neighbour shortcuts), then our statistics pass
  // with the saliency sum: the same components and statistics as connectedComponentsWithStats
  // (test_saliency compares them), without OpenCV's label table allocated on every call and no
  // stats matrix reallocated when the number of labels changes. Components are numbered in the
  // raster order of their first pixel.
  const int n = labelComponents();
  acc_.assign(static_cast<size_t>(n), Accumulator{0, INT_MAX, INT_MAX, -1, -1, 0});
  for (int r = 0; r < rows; ++r) {
    const int* l = labels_.ptr<int>(r);
    const uchar* s = map.ptr<uchar>(r);
    for (int c = 0; c < cols; ++c) {
      if (l[c] == 0) continue;
      Accumulator& a = acc_[parent_[l[c]]];
      ++a.area;
      a.sum += s[c];
      a.x0 = std::min(a.x0, c);
      a.x1 = std::max(a.x1, c);
      a.y0 = std::min(a.y0, r);
      a.y1 = std::max(a.y1, r);
    }
  }
  const double max_area = params.max_object_area_fraction * g.frame_area;
  const float cx = 0.5f * cols, cy = 0.5f * rows, sigma = 0.5f * std::max(cols, rows);
  for (int i = 1; i < n; ++i) {
    const Accumulator& a = acc_[i];
    if (a.area == 0) continue;
    SalientRegion reg;
    reg.area = static_cast<float>(a.area * g.sx * g.sy);
    reg.touches_border = a.x0 == 0 || a.y0 == 0 || a.x1 == cols - 1 || a.y1 == rows - 1;
    if (reg.area < params.min_object_area || reg.area > max_area) continue;
    if (reg.touches_border && params.reject_border_regions) continue;
    reg.box = cv::Rect2f(g.offset.x + a.x0 * g.sx, g.offset.y + a.y0 * g.sy, (a.x1 - a.x0 + 1) * g.sx,
                         (a.y1 - a.y0 + 1) * g.sy);
    reg.mean_saliency = static_cast<float>(a.sum / (255.0 * a.area));
    reg.score = params.saliency_rank_by_area ? reg.area : reg.area * reg.mean_saliency;
    if (g.centre_prior) {
      const float dx = 0.5f * (a.x0 + a.x1 + 1) - cx, dy = 0.5f * (a.y0 + a.y1 + 1) - cy;
      reg.score *= std::exp(-(dx * dx + dy * dy) / (2.0f * sigma * sigma));
    }
    regions.push_back(reg);
  }
  // Best score first; equal scores (equal saliency sums are common among small regions) in
  // raster order of their boxes, so that the order depends neither on the labelling algorithm
  // nor on std::sort's handling of ties.
  std::sort(regions.begin(), regions.end(), [](const SalientRegion& x, const SalientRegion& y) {
    if (x.score != y.score) return x.score > y.score;
    if (x.box.y != y.box.y) return x.box.y < y.box.y;
    if (x.box.x != y.box.x) return x.box.x < y.box.x;
    if (x.box.height != y.box.height) return x.box.height < y.box.height;
    return x.box.width < y.box.width;
  });
  return t;
}

}  // namespace core
}  // namespace obstacle_tracker
