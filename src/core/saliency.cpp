// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Saliency detector (Bharati et al., T-IV 2018, Algorithm 1 and the re-detection step):
//   1. shrink the frame (or search window) so its longer side is at most saliency_max_side;
//   2. MBD saliency map by FastMBD (Zhang et al., ICCV 2015) on Lab (colour) or grey (thermal),
//      optionally plus MB+'s backgroundness map and smoothing / contrast stretch;
//   3. Otsu threshold of the 8-bit map (cv::threshold THRESH_OTSU is the paper's eqs. 6-11);
//   4. 8-connected regions with area, box, mean saliency, border contact; filtered by
//      min_object_area, max_object_area_fraction and reject_border_regions; ranked.
//
// Ranking score: the region's saliency mass, area (full-frame px^2) x mean saliency in [0, 1].
// Between regions of similar saliency this is the paper's "largest region"; it keeps a large but
// faint patch from outranking a compact bright one. saliency_rank_by_area = true gives the
// paper's rule exactly (score = area). In windowed re-detection the mass is
// multiplied by exp(-d^2 / (2 s^2)), d the distance of the region's box centre from the window
// centre (the last position) and s half the window's longer side, so that of two similar
// candidates the one nearer the last position wins.
#include "obstacle_tracker/core/saliency.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/frame_check.h"
#include "obstacle_tracker/core/mbd.h"
#include "obstacle_tracker/core/segmentation.h"

namespace obstacle_tracker {
namespace core {

cv::Mat MatArena::get(int rows, int cols, int type) {
  const size_t bytes = static_cast<size_t>(rows) * cols * CV_ELEM_SIZE(type);
  if (memory_.size() < bytes) memory_.resize(bytes);
  return cv::Mat(rows, cols, type, memory_.data());
}



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

struct SaliencyDetector::Impl {
  SaliencyParams params;
  MatArena small_arena, mid_arena, map_arena;
  MbdSaliency mbd;
  RegionExtractor extractor;
  std::vector<SalientRegion> regions;
  cv::Mat map;
  cv::Rect map_region;

  Impl() { regions.reserve(256); }

  void run(const cv::Mat& frame, const cv::Rect& roi, bool windowed) {
    const cv::Mat src = frame(roi);
    const int longer = std::max(roi.width, roi.height);
    cv::Mat img = src;
    if (longer > params.saliency_max_side) {
      const double s = static_cast<double>(params.saliency_max_side) / longer;
      const int w = std::max(1, static_cast<int>(std::lround(roi.width * s)));
      const int h = std::max(1, static_cast<int>(std::lround(roi.height * s)));
      img = small_arena.get(h, w, frame.type());
      // Area averaging is the right filter for shrinking, but OpenCV's INTER_AREA is fast only
      // for integer factors: average by the largest integer factor f first, then finish with a
      // bilinear step of less than 2x.
      int f = static_cast<int>(1.0 / s);
      while (f >= 2 && (roi.width / f < w || roi.height / f < h)) --f;  // mid image >= target
      if (f >= 2) {
        cv::Mat mid = mid_arena.get(roi.height / f, roi.width / f, frame.type());
        cv::resize(src(cv::Rect(0, 0, mid.cols * f, mid.rows * f)), mid, mid.size(), 0, 0, cv::INTER_AREA);
        cv::resize(mid, img, img.size(), 0, 0, cv::INTER_LINEAR);
      } else {
        cv::resize(src, img, img.size(), 0, 0, cv::INTER_AREA);
      }
    }
    map = map_arena.get(img.rows, img.cols, CV_8U);
    mbd.compute(img, params, map);
    map_region = roi;
    RegionExtractor::Geometry g;
    g.offset = cv::Point2f(static_cast<float>(roi.x), static_cast<float>(roi.y));
    g.sx = static_cast<float>(roi.width) / img.cols;
    g.sy = static_cast<float>(roi.height) / img.rows;
    g.frame_area = static_cast<double>(frame.rows) * frame.cols;
    g.centre_prior = windowed;
    extractor.extract(map, g, params, regions);
  }
};

namespace {
// OpenCV builds its 8-bit Lab lookup tables on the first BGR2Lab call (about 130 ms here). Doing
// it when a detector is made keeps that stall out of the frame on which the first track starts
// (a camera-rate nodelet with queue size 1 would drop the frames behind it).
void warmUpLabTables() {
  static const bool done = [] {
    cv::Mat bgr(1, 1, CV_8UC3, cv::Scalar(0, 0, 0)), lab;
    cv::cvtColor(bgr, lab, cv::COLOR_BGR2Lab);
    return true;
  }();
  (void)done;
}
}  // namespace

SaliencyDetector::SaliencyDetector(const SaliencyParams& params) : impl_(new Impl) {
  warmUpLabTables();
  setParams(params);
}
SaliencyDetector::~SaliencyDetector() { delete impl_; }

void SaliencyDetector::setParams(const SaliencyParams& params) {
  impl_->params = params;
  clampGroup(impl_->params);
}

const std::vector<SalientRegion>& SaliencyDetector::detect(const cv::Mat& frame) {
  requireFrame(frame, "SaliencyDetector::detect");
  impl_->run(frame, cv::Rect(0, 0, frame.cols, frame.rows), false);
  return impl_->regions;
}

const std::vector<SalientRegion>& SaliencyDetector::detectInWindow(const cv::Mat& frame,
                                                                   const cv::Rect2f& last_box) {
  requireFrame(frame, "SaliencyDetector::detectInWindow");
  const cv::Rect win = searchWindow(frame.size(), last_box, impl_->params.search_window_scale);
  if (win.width < 3 || win.height < 3) {
    impl_->regions.clear();
    return impl_->regions;
  }
  impl_->run(frame, win, true);
  return impl_->regions;
}

cv::Rect SaliencyDetector::searchWindow(const cv::Size& frame_size, const cv::Rect2f& box, double scale) {
  constexpr float kMinSide = 32.0f;
  if (!std::isfinite(box.x) || !std::isfinite(box.y) || !std::isfinite(box.width) ||
      !std::isfinite(box.height) || !std::isfinite(scale) || box.width <= 0 || box.height <= 0 ||
      frame_size.width <= 0 || frame_size.height <= 0)
    return cv::Rect();
  const cv::Rect2f frame_rect(0.0f, 0.0f, static_cast<float>(frame_size.width),
                              static_cast<float>(frame_size.height));
  if ((box & frame_rect).area() <= 0.0f) return cv::Rect();
  const float s = static_cast<float>(std::max(1.0, scale));
  const float w = std::max(kMinSide, box.width * s), h = std::max(kMinSide, box.height * s);
  const cv::Point2f c = boxCentre(box);
  const float cx = c.x, cy = c.y;
  const int x0 = static_cast<int>(std::floor(cx - 0.5f * w)), y0 = static_cast<int>(std::floor(cy - 0.5f * h));
  const int x1 = static_cast<int>(std::ceil(cx + 0.5f * w)), y1 = static_cast<int>(std::ceil(cy + 0.5f * h));
  return cv::Rect(cv::Point(x0, y0), cv::Point(x1, y1)) & cv::Rect(0, 0, frame_size.width, frame_size.height);
}

const cv::Mat& SaliencyDetector::saliencyMap() const { return impl_->map; }
cv::Rect SaliencyDetector::mapRegion() const { return impl_->map_region; }

}  // namespace core
}  // namespace obstacle_tracker
