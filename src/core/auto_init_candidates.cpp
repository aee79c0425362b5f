// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// AutoInitializer::Impl (auto_init_impl.h), steps 2-3: the candidate map P (local contrast x MBD
// saliency) and its candidates (cell maxima grown into regions, filtered).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

#include "auto_init_impl.h"
#include "obstacle_tracker/core/region_growing.h"

namespace obstacle_tracker {
namespace core {

using namespace auto_init_detail;  // NOLINT(build/namespaces): the auto-initialiser's own constants

// Candidate map P (CV_8U, the working size of step 0).
cv::Mat AutoInitializer::Impl::candidateMap(const cv::Mat& grey) {
  const int rows = grey.rows, cols = grey.cols;
  const bool halve = rows >= 64 && cols >= 64;
  cv::Mat half = grey;
  if (halve) {
    half = half_arena.get(rows / 2, cols / 2, CV_8U);
    cv::resize(grey(cv::Rect(0, 0, half.cols * 2, half.rows * 2)), half, half.size(), 0, 0, cv::INTER_AREA);
  }
  cv::Mat sal = sal_arena.get(half.rows, half.cols, CV_8U);
  SaliencyParams mp = params;
  mp.saliency_backgroundness = false;
  mp.saliency_postprocess = false;
  mp.saliency_median = 0;
  mbd.compute(half, mp, sal);
  cv::Mat p = prob_arena.get(rows, cols, CV_8U);
  cv::Mat sal_full = sal;
  if (halve) {
    sal_full = up_arena.get(rows, cols, CV_8U);
    cv::resize(sal, sal_full(cv::Rect(0, 0, sal.cols * 2, sal.rows * 2)), cv::Size(sal.cols * 2, sal.rows * 2), 0, 0,
               cv::INTER_NEAREST);
    // An odd last row / column copies its neighbour.
    if (cols > sal.cols * 2) sal_full.col(cols - 2).copyTo(sal_full.col(cols - 1));
    if (rows > sal.rows * 2) sal_full.row(rows - 2).copyTo(sal_full.row(rows - 1));
  }
  if (params.auto_init_local_contrast) {
    cv::Mat small_mean = blur_arena.get(rows, cols, CV_8U);
    cv::Mat large_mean = box_arena.get(rows, cols, CV_8U);
    cv::Mat contrast = contrast_arena.get(rows, cols, CV_8U);
    cv::blur(grey, small_mean, cv::Size(3, 3));
    cv::blur(grey, large_mean, cv::Size(21, 21));
    cv::absdiff(small_mean, large_mean, contrast);
    contrast_map = contrast;
    // P = min(255, 2 contrast) x S / 255: contrast is stretched x2 (saturating) because small
    // targets rarely reach 128 levels of local contrast and the product must not vanish in
    // 8 bits.
    cv::add(contrast, contrast, contrast);
    cv::multiply(contrast, sal_full, p, 1.0 / 255.0);
  } else {
    sal_full.copyTo(p);
    contrast_map.release();  // no contrast map: no isolated candidates, no stale one either
  }
  return p;
}

// Candidates of one frame: peaks of P and isolated peaks of the local contrast, grown into
// regions, filtered; best first (keepBest).
void AutoInitializer::Impl::findCandidates(const cv::Mat& p) {
  cellPeaks(p);
  isolatedPeaks(p);
  const int rows = p.rows, cols = p.cols;
  // Grow each peak into its region (>= kGrowShare x the peak), drop duplicates and filtered regions.
  if (stamp.size() != static_cast<size_t>(rows) * cols) {
    stamp.assign(static_cast<size_t>(rows) * cols, 0);
    stamp_value = 0;
  }
  const double max_area = params.max_object_area_fraction * rows * cols;
  size_t kept = 0;
  if (stamp_value > INT32_MAX - 1024) {
    std::fill(stamp.begin(), stamp.end(), 0);
    stamp_value = 0;
  }
  for (size_t i = 0; i < candidates.size(); ++i) {
    Candidate c = candidates[i];
    const cv::Point seed(static_cast<int>(c.centre.x), static_cast<int>(c.centre.y));
    // A pixel of the region of a stronger candidate already kept: the same object. (A seed in
    // the region of a stronger peak that was filtered out is still grown: that region may be a
    // border-glued structure the target touches at 0.3 x its peak.)
    const int seed_stamp = stamp[static_cast<size_t>(seed.y) * cols + seed.x];
    bool same = false;
    // (Still candidates do not count: a target passing over an overlay is not the overlay.)
    for (size_t j = 0; j < kept && !same; ++j) same = candidates[j].stamp == seed_stamp && !candidates[j].still;
    if (same) continue;
    growRegion(c.from_contrast ? contrast_map : p, seed, c);
    if (keepCandidate(c, cols, max_area)) candidates[kept++] = c;
  }
  keepBest(kept);
}

// Of the `kept` first candidates: the best auto_init_candidates peaks of P (ties: larger mean),
// then the kIsolatedCandidates most isolated of the contrast source. Still candidates after the
// others in each group, so that they never take a moving one's place.
void AutoInitializer::Impl::keepBest(size_t kept) {
  candidates.resize(kept);
  // Grown in order, the peaks of P before the isolated ones (cellPeaks, then isolatedPeaks).
  const auto contrast_start = std::find_if(candidates.begin(), candidates.end(),
                                           [](const Candidate& c) { return c.from_contrast; });
  // Ties in growth order (the stamps rise with it): std::sort with that last key orders as a
  // stable sort would, without the stable sort's temporary buffer.
  std::sort(candidates.begin(), contrast_start, [](const Candidate& a, const Candidate& b) {
    if (a.still != b.still) return b.still;
    if (a.peak != b.peak) return a.peak > b.peak;
    return a.mean != b.mean ? a.mean > b.mean : a.stamp < b.stamp;
  });
  std::sort(contrast_start, candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.still != b.still) return b.still;
    return a.isolation != b.isolation ? a.isolation > b.isolation : a.stamp < b.stamp;
  });
  const auto from_p = static_cast<int>(contrast_start - candidates.begin());
  const int keep_p = std::min(from_p, params.auto_init_candidates);
  const int keep_isolated = std::min(static_cast<int>(candidates.size()) - from_p, kIsolatedCandidates);
  // Move the kept isolated ones up behind the kept peaks of P (no allocation: a rotate in place).
  std::rotate(candidates.begin() + keep_p, contrast_start, contrast_start + keep_isolated);
  candidates.resize(static_cast<size_t>(keep_p + keep_isolated));
}

// The 8-connected region of `p` (P, or the contrast map for an isolated candidate) >=
// kGrowShare x the candidate's peak around `seed` (within
// kGrowRadius), stamped with a new stamp value: the candidate's box, area, mean and centre, and
// the growth cue's size measure. Leaves the region's pixels in `queue`.
void AutoInitializer::Impl::growRegion(const cv::Mat& p, cv::Point seed, Candidate& c) {
  const int rows = p.rows, cols = p.cols;
  ++stamp_value;
  c.stamp = stamp_value;
  const int thr = std::max(1, static_cast<int>(std::ceil(kGrowShare * c.peak)));
  const int x_lo = std::max(0, seed.x - kGrowRadius), x_hi = std::min(cols - 1, seed.x + kGrowRadius);
  const int y_lo = std::max(0, seed.y - kGrowRadius), y_hi = std::min(rows - 1, seed.y + kGrowRadius);
  queue.clear();
  queue.push_back(seed.y * cols + seed.x);
  stamp[static_cast<size_t>(seed.y) * cols + seed.x] = stamp_value;
  int x0 = seed.x, x1 = seed.x, y0 = seed.y, y1 = seed.y;
  double sum = 0.0;
  auto claim = [&](int x, int y) {
    const size_t k = static_cast<size_t>(y) * cols + x;
    if (stamp[k] == stamp_value || p.at<uchar>(y, x) < thr) return false;
    stamp[k] = stamp_value;
    return true;
  };
  auto visit = [&](int x, int y) {
    sum += p.at<uchar>(y, x);
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
    return true;
  };
  growRegion8(queue, cols, cv::Rect(cv::Point(x_lo, y_lo), cv::Point(x_hi + 1, y_hi + 1)), claim, visit);
  {
    // Size measure for the growth cue: pixels of `p` >= kSizeShare x the peak in a window
    // around the grown core (thin parts of a silhouette, e.g. wings, stay under the core's
    // 0.3 x peak but above this).
    const int r = 2 * std::max(x1 - x0 + 1, y1 - y0 + 1) + 4;
    const int thr_s = std::max(1, static_cast<int>(std::ceil(kSizeShare * c.peak)));
    const int sx0 = std::max(0, (x0 + x1) / 2 - r), sx1 = std::min(cols - 1, (x0 + x1) / 2 + r);
    const int sy0 = std::max(0, (y0 + y1) / 2 - r), sy1 = std::min(rows - 1, (y0 + y1) / 2 + r);
    int count = 0;
    for (int y = sy0; y <= sy1; ++y) {
      const uchar* row = p.ptr<uchar>(y);
      for (int x = sx0; x <= sx1; ++x) count += row[x] >= thr_s;
    }
    c.size_px = count;
  }
  c.area = static_cast<int>(queue.size());
  c.mean = static_cast<float>(sum / c.area);
  c.box = cv::Rect(cv::Point(x0, y0), cv::Point(x1 + 1, y1 + 1));
  c.centre = cv::Point2f(0.5f * (x0 + x1 + 1), 0.5f * (y0 + y1 + 1));
  c.touches_border = x0 == 0 || y0 == 0 || x1 == cols - 1 || y1 == rows - 1;
  c.truncated = x0 == seed.x - kGrowRadius || x1 == seed.x + kGrowRadius || y0 == seed.y - kGrowRadius ||
                y1 == seed.y + kGrowRadius;
}

// The filters a grown candidate (its region's pixels in `queue`) must pass; sets c.still.
bool AutoInitializer::Impl::keepCandidate(Candidate& c, int cols, double max_area) {
  if (c.touches_border && params.reject_border_regions) return false;
  // Size: the grown core of a target of a few pixels (or of a thin silhouette) is smaller than
  // the target, so the object pixels (size_px) count too.
  if (std::max(c.box.area(), c.size_px) < params.min_object_area || c.area > max_area) return false;
  // The contrast source measures isolation for objects of up to two cells (ringClutter): a region
  // grown longer than that is a line or an edge whose end stood out, not a small object.
  if (c.from_contrast && std::max(c.box.width, c.box.height) > 2 * kCell) return false;
  // A thin region that reached kGrowRadius from its seed is a piece of a band longer than any
  // candidate (a horizon, a shore, the warm strip along a thermal frame's bottom): the pieces
  // of it seeded along its length take turns as its peak, and their track then "moves" along
  // the band. A large object, cut at the radius too, is not thin.
  if (c.truncated && std::max(c.box.width, c.box.height) >= kBandElongation * std::min(c.box.width, c.box.height))
    return false;
  // Most of its pixels locked to the image: part of the on-screen display (overlay_mask.h).
  if (overlayShare(queue, cols) >= AutoInitializer::kOverlayShare) return false;
  if (params.auto_init_reject_static && frame_index > 0) {
    // Share of the box's pixels, or of the region's own pixels, unchanged for kStillFrames
    // frames: an overlay (or a static scene under a still camera). A moving target changes
    // most of its box and of its pixels every frame; an overlay line crossing a textured
    // background keeps its own pixels but not its box.
    const int still_px = stillPixels(c.box);
    int still_region = 0;
    for (const int q : queue) still_region += still.ptr<uchar>(q / cols)[q % cols] >= kStillFrames;
    // Kept, flagged: an obstacle on a collision course keeps its bearing and changes only at
    // its rim, so it looks still too; it can be confirmed by growth, never by motion.
    // (The growth cue lives in the motion test: with auto_init_min_motion 0 there is no
    // cue to hold them back, so they are dropped.)
    c.still = still_px >= kStillShare * c.box.area() || still_region >= kStillShare * c.area;
    if (c.still && (params.auto_init_min_growth <= 0.0 || params.auto_init_min_motion <= 0.0)) return false;
  }
  return true;
}

}  // namespace core
}  // namespace obstacle_tracker
