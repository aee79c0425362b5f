// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Multi-frame auto-initialisation (saliency.h, AutoInitializer). One frame's saliency picks the
// wrong object on real footage (on-screen text, sunlit ground, parked aircraft outrank the
// target), so candidates are followed over the first frames and confirmed by cues
// that one frame cannot give. Per frame, on the grey image:
//   1. background motion (background_motion.h: feature tracks and a robust similarity, phase
//      correlation over featureless sky) from the previous frame, summed at the frame centre:
//      where the background has moved to since the start; and the overlay mask (overlay_mask.h):
//      pixels that stay locked to the image while the background moves;
//   2. candidate map P = local contrast at native resolution (|3x3 mean - 21x21 mean|: keeps
//      targets of a few pixels that a 300 px saliency map loses) x MBD saliency at half
//      resolution (suppresses ground, trees and buildings connected to the frame border);
//      auto_init_local_contrast = false uses the MBD map alone;
//   3. candidates: peaks of P that are maxima of their 16x16 cell and its 8 neighbours, the best
//      auto_init_candidates of them; box = the 8-connected pixels >= 0.3 x the peak around it;
//      regions touching the frame border are dropped when reject_border_regions is set, and
//      regions with at least kOverlayShare of their pixels on the overlay mask always;
//   4. candidates are associated with the tracks of earlier frames (nearest predicted position
//      within a gate); a track is confirmed once seen auto_init_frames times (persistence, at
//      least 60 % of the frames since it appeared) and, when auto_init_min_motion > 0, once it
//      has moved that far against both the image (an overlay or a target the camera keeps still
//      stays put in the image) and the background (a static scene object moves exactly with the
//      background) and vacated its old place (the local contrast there, carried with the
//      background, has fallen under half of what it was: a peak wandering along a static lattice
//      or edge leaves the structure behind), or, when auto_init_min_growth > 0, once its object
//      pixels (P >= 0.1 x its peak around the core) have grown steadily by that much in
//      ln sqrt(pixels) over its history: an obstacle on a collision course keeps its bearing and
//      only grows. Still candidates (pixels unchanged for 3 frames) are kept for this cue only;
//   5. score of a confirmed track: mean peak of P x seen share x min(1, motion / (3 x
//      auto_init_min_motion)) (or growth / (3 x auto_init_min_growth)); with
//      auto_init_horizon_prior, a track below the horizon (the
//      strongest row-mean step of the shrunk frame) needs twice the frames and scores x 0.5;
//   6. the box of a confirmed track is refined by the saliency detector (FastMBD + Otsu) in a
//      window of 4 x the box (at least 32 px) at native resolution, when its best region
//      contains the track's centre, then grown to the object's visible extent (ExtentGrower,
//      extent_contrast: Otsu keeps the bright core of a blurred target of a few pixels).
// Each cue can be switched off by its parameter; init_table measures what each one brings.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/background_motion.h"
#include "obstacle_tracker/core/overlay_mask.h"
#include "obstacle_tracker/core/saliency.h"
#include "obstacle_tracker/core/segmentation.h"

namespace obstacle_tracker {
namespace core {

namespace {

constexpr int kCell = 16;           // candidate cell side (px)
constexpr int kGrowRadius = 64;     // largest half-side of a candidate box (px)
constexpr int kMaxMissed = 3;       // frames a track may go unseen before it is dropped
constexpr size_t kMaxTracks = 96;
constexpr int kPoolFactor = 4;      // peaks grown per frame, x auto_init_candidates
constexpr int kStillFrames = 3;     // frames a pixel must be unchanged to count as still
constexpr int kStillLevel = 3;      // grey levels of change still counted as unchanged
constexpr float kStillShare = 0.85f;
constexpr float kGrowShare = 0.3f;
constexpr double kRefineWindowScale = 4.0;  // window around a confirmed candidate for its box
constexpr float kRefineMaxGrowth = 16.0f;   // a refined box may cover at most 16 x the candidate's
constexpr float kMaxAspect = 4.5f;      // candidate boxes more elongated are lines
constexpr double kMinLinearity = 0.5;   // share of position variance a steady motion explains
constexpr float kSizeShare = 0.1f;      // growth cue: object pixels are P >= this x the peak
constexpr int kMinGrowthSamples = 12;  // history points before growth can confirm a track
constexpr double kMinGrowthFit = 0.6;   // share of the log-size variance the growth line explains
constexpr double kVacated = 0.5;        // motion cue: contrast at the old place now / then
constexpr int kLag = 4;                 // frames back for the appearance-change test
constexpr double kMinChange = 0.5;      // appearance change / local contrast of a moving target

struct Candidate {
  cv::Rect box;
  cv::Point2f centre;
  int area = 0;
  float peak = 0.0f, mean = 0.0f;
  bool touches_border = false;
  int stamp = -1;  // label of its region in the stamp image
  int size_px = 0;  // pixels of the object above kSizeShare x its peak (growth cue)
  bool still = false;  // its pixels have not changed for kStillFrames frames
};

constexpr int kHistory = 32;  // positions kept per track for the motion fit

cv::Point2f apply(const cv::Matx33d& h, cv::Point2f p) {
  const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1.0);
  return {static_cast<float>(q[0] / q[2]), static_cast<float>(q[1] / q[2])};
}

struct Track {
  // Ring buffer of (frame, image position, position in the first frame's background coordinates).
  std::array<int, kHistory> frames;
  std::array<cv::Point2f, kHistory> img, rel;
  std::array<float, kHistory> log_size;  // ln sqrt(size_px): the growth cue's size
  std::array<int, kHistory> contrast;    // local contrast at the position then (vacated test)
  int count = 0;
  void remember(int frame, cv::Point2f p, const cv::Matx33d& image_to_first, int size_px, int local_contrast) {
    const int k = count % kHistory;
    frames[k] = frame;
    contrast[k] = local_contrast;
    log_size[k] = 0.5f * std::log(static_cast<float>(std::max(1, size_px)));
    img[k] = p;
    rel[k] = apply(image_to_first, p);
    ++count;
  }
  cv::Point2f centre, velocity;
  cv::Rect box;
  int first_frame = 0, last_frame = 0, hits = 0, area = 0;
  double sum_peak = 0.0, last_mean = 0.0;
  bool touches_border = false;
  bool still = false;  // its last candidate was still (can only be confirmed by growth)
};

}  // namespace

struct AutoInitializer::Impl {
  Params params;
  MbdSaliency mbd;
  SaliencyDetector refiner;
  ExtentGrower extent;
  MatArena grey_arena, half_arena, up_arena, sal_arena, blur_arena, box_arena, contrast_arena, prob_arena;
  BackgroundMotion motion;
  OverlayMask overlay;
  cv::Point2d background{0.0, 0.0};
  // The background's motion since the first frame (first-frame coordinates -> this frame's) and
  // its inverse.
  cv::Matx33d first_to_image = cv::Matx33d::eye(), image_to_first = cv::Matx33d::eye();
  cv::Size size;
  int frame_index = 0;
  int horizon = -1;
  std::vector<int> stamp, queue;
  int stamp_value = 0;
  std::vector<float> cell_max;
  std::vector<uchar> text_flag;
  cv::Mat prev_grey, still, diff;  // persistent: previous grey frame, per-pixel still count
  std::array<cv::Mat, kLag + 1> past;          // grey frames t, t-1, ..., t-kLag (ring)
  std::array<cv::Matx33d, kLag + 1> past_image_to_first;
  cv::Mat contrast_map;                        // last frame's local contrast (CV_8U), for the lag test
  std::vector<Candidate> candidates;
  std::vector<Track> tracks;
  std::vector<SalientRegion> confirmed, raw;

  Impl() {
    candidates.reserve(64);
    tracks.reserve(kMaxTracks + 64);
    confirmed.reserve(64);
    raw.reserve(64);
  }

  void reset() {
    motion.reset();
    overlay.reset();
    prev_grey.release();
    background = cv::Point2d(0.0, 0.0);
    first_to_image = image_to_first = cv::Matx33d::eye();
    frame_index = 0;
    horizon = -1;
    tracks.clear();
    confirmed.clear();
    raw.clear();
  }

  void globalMotion(const cv::Mat& grey) {
    // The background's motion since the previous frame (background_motion.h), with no corner on
    // the overlay; the overlay mask learns from the same pair of frames. `background` follows the
    // frame centre's displacement, summed frame to frame.
    const BackgroundMotionEstimate& e = motion.update(grey, overlay.mask());
    if (e.known()) {
      overlay.update(motion.previousWorkingFrame(), motion.currentWorkingFrame(), motion.workingTransform());
      background += e.displacementAt(cv::Point2d(0.5 * (grey.cols - 1), 0.5 * (grey.rows - 1)));
      const cv::Matx23d& a = e.previous_to_current;
      first_to_image = cv::Matx33d(a(0, 0), a(0, 1), a(0, 2), a(1, 0), a(1, 1), a(1, 2), 0, 0, 1) * first_to_image;
      image_to_first = first_to_image.inv();
    }
    if (params.auto_init_horizon_prior) {
      // Row means of the shrunk frame; the horizon is the strongest step (over 4 rows) in the
      // middle 80 %, if it is at least 12 grey levels.
      const cv::Mat& small = motion.currentWorkingFrame();
      const double rows_per_row = static_cast<double>(grey.rows) / small.rows;
      horizon = -1;
      float best = 12.0f;
      const int rows = small.rows;
      for (int r = std::max(2, rows / 10); r < rows - std::max(2, rows / 10); ++r) {
        const float a = static_cast<float>(cv::mean(small.rowRange(r - 2, r))[0]);
        const float b = static_cast<float>(cv::mean(small.rowRange(r, r + 2))[0]);
        if (std::abs(a - b) > best) {
          best = std::abs(a - b);
          horizon = static_cast<int>(r * rows_per_row);
        }
      }
    }
  }

  // Share of a region's pixels (full-resolution indices y * cols + x) on the overlay mask.
  double overlayShare(const std::vector<int>& pixels, int cols) const {
    const cv::Mat& mask = overlay.mask();
    if (mask.empty() || pixels.empty()) return 0.0;
    const cv::Point2d s = motion.workingScale();
    int on = 0;
    for (const int q : pixels) {
      const int x = std::min(mask.cols - 1, static_cast<int>(s.x * (q % cols)));
      const int y = std::min(mask.rows - 1, static_cast<int>(s.y * (q / cols)));
      on += mask.ptr<uchar>(y)[x] != 0;
    }
    return static_cast<double>(on) / pixels.size();
  }

  // Per-pixel count of consecutive frames without change (saturating at 255).
  void updateStill(const cv::Mat& grey) {
    if (!params.auto_init_reject_static) return;
    if (prev_grey.size() != grey.size()) {
      grey.copyTo(prev_grey);
      still.create(grey.size(), CV_8U);
      still.setTo(0);
      return;
    }
    // still = unchanged ? min(255, still + 1) : 0, with OpenCV's vectorised element-wise ops.
    cv::absdiff(grey, prev_grey, diff);
    cv::compare(diff, kStillLevel, diff, cv::CMP_LE);  // 255 where unchanged
    cv::add(still, cv::Scalar(1), still);              // saturating
    cv::bitwise_and(still, diff, still);
    grey.copyTo(prev_grey);
  }

  // Pixels of r (inside the frame) unchanged for kStillFrames frames.
  int stillPixels(const cv::Rect& r) const {
    int n = 0;
    for (int y = r.y; y < r.y + r.height; ++y) {
      const uchar* sc = still.ptr<uchar>(y);
      for (int x = r.x; x < r.x + r.width; ++x) n += sc[x] >= kStillFrames;
    }
    return n;
  }

  // Candidate map P (CV_8U, native resolution).
  cv::Mat candidateMap(const cv::Mat& grey) {
    const int rows = grey.rows, cols = grey.cols;
    const bool halve = rows >= 64 && cols >= 64;
    cv::Mat half = grey;
    if (halve) {
      half = half_arena.get(rows / 2, cols / 2, CV_8U);
      cv::resize(grey(cv::Rect(0, 0, half.cols * 2, half.rows * 2)), half, half.size(), 0, 0, cv::INTER_AREA);
    }
    cv::Mat sal = sal_arena.get(half.rows, half.cols, CV_8U);
    Params mp = params;
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
    }
    return p;
  }

  void findCandidates(const cv::Mat& p) {
    candidates.clear();
    const int rows = p.rows, cols = p.cols;
    const int gw = (cols + kCell - 1) / kCell, gh = (rows + kCell - 1) / kCell;
    cell_max.assign(static_cast<size_t>(gw) * gh, -1.0f);
    int global_max = 0;
    for (int r = 0; r < rows; ++r) {
      const uchar* o = p.ptr<uchar>(r);
      float* cm = &cell_max[static_cast<size_t>(r / kCell) * gw];
      for (int gx = 0; gx < gw; ++gx) {
        const int x0 = gx * kCell, x1 = std::min(cols, x0 + kCell);
        uchar m = 0;
        for (int x = x0; x < x1; ++x) m = std::max(m, o[x]);  // vectorisable max
        cm[gx] = std::max(cm[gx], static_cast<float>(m));
      }
    }
    for (float v : cell_max) global_max = std::max(global_max, static_cast<int>(v));
    const float floor_value = std::max(8.0f, 0.1f * global_max);
    for (int gy = 0; gy < gh; ++gy)
      for (int gx = 0; gx < gw; ++gx) {
        const float v = cell_max[static_cast<size_t>(gy) * gw + gx];
        if (v < floor_value) continue;
        bool is_max = true;
        for (int dy = -1; dy <= 1 && is_max; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = gx + dx, ny = gy + dy;
            if ((dx || dy) && nx >= 0 && ny >= 0 && nx < gw && ny < gh &&
                cell_max[static_cast<size_t>(ny) * gw + nx] > v) {
              is_max = false;
              break;
            }
          }
        if (!is_max) continue;
        Candidate c;
        c.peak = v;
        // Where in the cell the maximum is (first in raster order).
        const int x0 = gx * kCell, y0 = gy * kCell;
        const int x1 = std::min(cols, x0 + kCell), y1 = std::min(rows, y0 + kCell);
        bool found = false;
        for (int y = y0; y < y1 && !found; ++y) {
          const uchar* o = p.ptr<uchar>(y);
          for (int x = x0; x < x1; ++x)
            if (o[x] == static_cast<uchar>(v)) {
              c.centre = cv::Point2f(static_cast<float>(x), static_cast<float>(y));
              found = true;
              break;
            }
        }
        candidates.push_back(c);
      }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.peak > b.peak; });
    const size_t pool = static_cast<size_t>(kPoolFactor * params.auto_init_candidates);
    if (candidates.size() > pool) candidates.resize(pool);

    // Grow each peak into its region (>= half the peak), drop duplicates and filtered regions.
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
      for (size_t q = 0; q < queue.size(); ++q) {
        const int y = queue[q] / cols, x = queue[q] % cols;
        sum += p.at<uchar>(y, x);
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < x_lo || nx > x_hi || ny < y_lo || ny > y_hi) continue;
            const size_t k = static_cast<size_t>(ny) * cols + nx;
            if (stamp[k] == stamp_value || p.at<uchar>(ny, nx) < thr) continue;
            stamp[k] = stamp_value;
            queue.push_back(ny * cols + nx);
          }
      }
      {
        // Size measure for the growth cue: pixels of P >= kSizeShare x the peak in a window
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
      if (c.touches_border && params.reject_border_regions) continue;
      // Size: the grown core of a target of a few pixels (or of a thin silhouette) is smaller than
      // the target, so the object pixels (size_px) count too.
      if (std::max(c.box.area(), c.size_px) < params.min_object_area || c.area > max_area) continue;
      // Most of its pixels locked to the image: part of the on-screen display (overlay_mask.h).
      if (overlayShare(queue, cols) >= AutoInitializer::kOverlayShare) continue;
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
        // cue to hold them back, so they are dropped as before.)
        c.still = still_px >= kStillShare * c.box.area() || still_region >= kStillShare * c.area;
        if (c.still && (params.auto_init_min_growth <= 0.0 || params.auto_init_min_motion <= 0.0)) continue;
      }
      candidates[kept++] = c;
    }
    candidates.resize(kept);
    if (params.auto_init_reject_text) rejectTextRows();
    // Best peaks first (ties: larger mean), at most auto_init_candidates.
    // Still candidates after the others, so that they never take a moving one's place.
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      if (a.still != b.still) return b.still;
      return a.peak != b.peak ? a.peak > b.peak : a.mean > b.mean;
    });
    if (static_cast<int>(candidates.size()) > params.auto_init_candidates)
      candidates.resize(static_cast<size_t>(params.auto_init_candidates));
  }

  // Text of an on-screen display: rows of >= 3 components of similar height, side by side.
  // A candidate with two or more such neighbours (centre rows within 40 % of its height, heights
  // within a factor 1.6, horizontal gap under 4 heights) is dropped.
  void rejectTextRows() {
    text_flag.assign(candidates.size(), 0);
    for (size_t i = 0; i < candidates.size(); ++i) {
      const Candidate& a = candidates[i];
      const float h = static_cast<float>(std::max(3, a.box.height));
      int neighbours = 0;
      for (size_t j = 0; j < candidates.size(); ++j) {
        if (i == j) continue;
        const Candidate& b = candidates[j];
        const float hb = static_cast<float>(std::max(3, b.box.height));
        if (std::abs(a.centre.y - b.centre.y) > 0.4f * h) continue;
        if (hb > 1.6f * h || h > 1.6f * hb) continue;
        if (std::abs(a.centre.x - b.centre.x) > 4.0f * h + 0.5f * (a.box.width + b.box.width)) continue;
        ++neighbours;
      }
      text_flag[i] = neighbours >= 2;
    }
    size_t kept = 0;
    for (size_t i = 0; i < candidates.size(); ++i)
      if (!text_flag[i]) candidates[kept++] = candidates[i];
    candidates.resize(kept);
  }

  void associate() {
    for (Candidate& c : candidates) {
      int best = -1;
      float best_d2 = 0.0f;
      for (size_t t = 0; t < tracks.size(); ++t) {
        Track& tr = tracks[t];
        if (tr.last_frame == frame_index) continue;  // already matched in this frame
        const float gap = static_cast<float>(frame_index - tr.last_frame);
        const cv::Point2f pred = tr.centre + tr.velocity * gap;  // image velocity (camera included)
        const float gate = std::max(8.0f, 0.75f * std::max(tr.box.width, tr.box.height)) + 2.0f * gap;
        const cv::Point2f d = c.centre - pred;
        const float d2 = d.dot(d);
        if (d2 <= gate * gate && (best < 0 || d2 < best_d2)) {
          best = static_cast<int>(t);
          best_d2 = d2;
        }
      }
      if (best >= 0) {
        Track& tr = tracks[static_cast<size_t>(best)];
        const float gap = static_cast<float>(frame_index - tr.last_frame);
        const cv::Point2f v = (c.centre - tr.centre) * (1.0f / gap);
        tr.velocity = tr.hits == 1 ? v : 0.5f * tr.velocity + 0.5f * v;
        tr.centre = c.centre;
        tr.box = c.box;
        tr.area = c.area;
        tr.last_frame = frame_index;
        ++tr.hits;
        tr.sum_peak += c.peak;
        tr.last_mean = c.mean;
        tr.touches_border = c.touches_border;
        tr.still = c.still;
        tr.remember(frame_index, c.centre, image_to_first, c.size_px, contrastAround(c.centre));
      } else if (tracks.size() < kMaxTracks) {
        Track tr;
        tr.centre = c.centre;
        tr.velocity = cv::Point2f(0.0f, 0.0f);
        tr.box = c.box;
        tr.area = c.area;
        tr.first_frame = tr.last_frame = frame_index;
        tr.hits = 1;
        tr.sum_peak = c.peak;
        tr.last_mean = c.mean;
        tr.touches_border = c.touches_border;
        tr.still = c.still;
        tr.remember(frame_index, c.centre, image_to_first, c.size_px, contrastAround(c.centre));
        tracks.push_back(tr);
      }
    }
    tracks.erase(std::remove_if(tracks.begin(), tracks.end(),
                                [&](const Track& t) { return frame_index - t.last_frame > kMaxMissed; }),
                 tracks.end());
  }

  // Appearance test of motion against the background: the box now against the same place of
  // the frame kLag frames ago, displaced by the background's motion since. A static structure
  // (or an overlay, once the background is accounted for) looks the same up to noise; a moving
  // target's box held background then. Mean absolute difference over the box (grown by 2 px),
  // relative to the mean local contrast there, must reach kMinChange. The region-centre motion
  // fit alone is fooled by regions whose extent fluctuates along a static edge.
  bool changedAgainstBackground(const cv::Rect& box) const {
    if (frame_index < kLag || contrast_map.empty()) return true;  // too early to tell
    const cv::Mat& now = past[static_cast<size_t>(frame_index % (kLag + 1))];
    const cv::Mat& then = past[static_cast<size_t>((frame_index - kLag) % (kLag + 1))];
    // Where the background at the box's centre was kLag frames ago, as a shift.
    const cv::Point2f centre(box.x + 0.5f * box.width, box.y + 0.5f * box.height);
    const cv::Matx33d then_to_now =
        first_to_image * past_image_to_first[static_cast<size_t>((frame_index - kLag) % (kLag + 1))];
    const cv::Point2d shift = cv::Point2d(centre) - cv::Point2d(apply(then_to_now.inv(), centre));
    const cv::Rect frame_rect(0, 0, now.cols, now.rows);
    const cv::Rect a = cv::Rect(box.x - 2, box.y - 2, box.width + 4, box.height + 4) & frame_rect;
    const cv::Point d(static_cast<int>(std::lround(shift.x)), static_cast<int>(std::lround(shift.y)));
    const cv::Rect b = (a - d) & frame_rect;  // where that content was kLag frames ago
    const cv::Rect a2 = b + d;
    if (a2.area() <= 0) return true;
    double diff_sum = 0.0, contrast_sum = 0.0;
    for (int y = 0; y < a2.height; ++y) {
      const uchar* p = now.ptr<uchar>(a2.y + y) + a2.x;
      const uchar* q = then.ptr<uchar>(b.y + y) + b.x;
      const uchar* c = contrast_map.ptr<uchar>(a2.y + y) + a2.x;
      for (int x = 0; x < a2.width; ++x) {
        diff_sum += std::abs(p[x] - q[x]);
        contrast_sum += c[x];
      }
    }
    return diff_sum >= kMinChange * (contrast_sum + a2.area());
  }

  // Largest local contrast in the 5x5 px around c (-1 outside the frame).
  int contrastAround(cv::Point2f c) const {
    if (contrast_map.empty()) return -1;
    const int cx = static_cast<int>(std::lround(c.x)), cy = static_cast<int>(std::lround(c.y));
    int best = -1;
    for (int y = std::max(0, cy - 2); y <= std::min(contrast_map.rows - 1, cy + 2); ++y) {
      const uchar* row = contrast_map.ptr<uchar>(y);
      for (int x = std::max(0, cx - 2); x <= std::min(contrast_map.cols - 1, cx + 2); ++x) {
        best = std::max(best, static_cast<int>(row[x]));
      }
    }
    return best;
  }

  // Vacated-position test for the motion cue: a mover leaves its old place to the background; a
  // candidate whose peak wanders along a static structure (a lattice tower under camera jitter,
  // an edge) leaves the structure where it was. The local contrast now at the track's oldest
  // remembered position (carried with the background to this frame) must have fallen below
  // kVacated x what it was when the track was there (maxima over 5x5 px).
  bool vacated(const Track& t) const {
    const int n = std::min(t.count, kHistory);
    if (n < 2 || contrast_map.empty()) return true;
    const size_t oldest = static_cast<size_t>(t.count <= kHistory ? 0 : t.count % kHistory);
    const int now = contrastAround(apply(first_to_image, t.rel[oldest]));
    if (now < 0 || t.contrast[oldest] <= 0) return true;  // its old place has left the frame
    return now < kVacated * t.contrast[oldest];
  }

  // Thin lines (reticles, poles, road markings): aspect above kMaxAspect.
  static bool isLine(const cv::Rect& b) {
    const float w = static_cast<float>(std::max(1, b.width)), h = static_cast<float>(std::max(1, b.height));
    return std::max(w / h, h / w) > kMaxAspect;
  }

  // Displacement of a track over its remembered history, from least-squares lines through its
  // positions against time (so that a region whose box jitters around a fixed point, e.g. a
  // textured structure, does not count as moving): the smaller of the displacement in the image
  // and the displacement against the background.
  // `linearity` receives the share of the positions' variance the line explains (for the
  // smaller displacement): near 1 for a target moving steadily, low for a jittering box.
  static double motionOf(const Track& t, double* linearity = nullptr) {
    const int n = std::min(t.count, kHistory);
    if (linearity) *linearity = 0.0;
    if (n < 2) return 0.0;
    double mt = 0.0;
    cv::Point2d mi(0, 0), mr(0, 0);
    int t_lo = INT32_MAX, t_hi = INT32_MIN;
    for (int k = 0; k < n; ++k) {
      mt += t.frames[k];
      mi += cv::Point2d(t.img[k]);
      mr += cv::Point2d(t.rel[k]);
      t_lo = std::min(t_lo, t.frames[k]);
      t_hi = std::max(t_hi, t.frames[k]);
    }
    mt /= n;
    mi *= 1.0 / n;
    mr *= 1.0 / n;
    double stt = 0.0, vi = 0.0, vr = 0.0;
    cv::Point2d si(0, 0), sr(0, 0);
    for (int k = 0; k < n; ++k) {
      const double dt = t.frames[k] - mt;
      const cv::Point2d di = cv::Point2d(t.img[k]) - mi, dr = cv::Point2d(t.rel[k]) - mr;
      stt += dt * dt;
      si += dt * di;
      sr += dt * dr;
      vi += di.dot(di);
      vr += dr.dot(dr);
    }
    if (stt <= 0.0) return 0.0;
    const double span = t_hi - t_lo;
    const double ni = std::hypot(si.x, si.y), nr = std::hypot(sr.x, sr.y);
    const bool img_smaller = ni < nr;
    if (linearity) {
      const double explained = (img_smaller ? ni * ni : nr * nr) / stt;
      const double total = img_smaller ? vi : vr;
      *linearity = total > 0.0 ? explained / total : 0.0;
    }
    return span * std::min(ni, nr) / stt;
  }

  // Growth of a track over its remembered history: the least-squares line through
  // ln sqrt(size_px) (its object pixels, see findCandidates) against time, times the time span
  // (so 0.2 = the size grew by e^0.2 = 22 %). An obstacle on a collision course keeps its bearing, so it has no motion across the image or against
  // the background to confirm it by; its growth is the cue (looming, as in the TTC literature:
  // Lee 1976). `fit` receives the share of the log sizes' variance the line explains (a region
  // whose extent fluctuates grows and shrinks without a trend). Needs kMinGrowthSamples points.
  static double growthOf(const Track& t, double* fit) {
    const int n = std::min(t.count, kHistory);
    *fit = 0.0;
    if (n < kMinGrowthSamples) return 0.0;
    double mt = 0.0, ms = 0.0;
    int t_lo = INT32_MAX, t_hi = INT32_MIN;
    for (int k = 0; k < n; ++k) {
      mt += t.frames[k];
      ms += t.log_size[k];
      t_lo = std::min(t_lo, t.frames[k]);
      t_hi = std::max(t_hi, t.frames[k]);
    }
    mt /= n;
    ms /= n;
    double stt = 0.0, sts = 0.0, sss = 0.0;
    for (int k = 0; k < n; ++k) {
      const double dt = t.frames[k] - mt, ds = t.log_size[k] - ms;
      stt += dt * dt;
      sts += dt * ds;
      sss += ds * ds;
    }
    if (stt <= 0.0) return 0.0;
    const double slope = sts / stt;
    *fit = sss > 0.0 ? slope * sts / sss : 0.0;
    return slope * (t_hi - t_lo);
  }

  static SalientRegion toRegion(const cv::Rect& box, int area, double mean, double score, bool border) {
    SalientRegion r;
    r.box = cv::Rect2f(box);
    r.area = static_cast<float>(area);
    r.mean_saliency = static_cast<float>(mean / 255.0);
    r.score = static_cast<float>(score);
    r.touches_border = border;
    return r;
  }

  // The candidate's region is the core of the target (>= 0.3 x the peak of P); the saliency
  // detector in a window around it, at native resolution, gives the object's own extent. Kept
  // when the best region there contains the candidate's centre.
  void refine(const cv::Mat& frame, SalientRegion& region) {
    const auto& found = refiner.detectInWindow(frame, region.box);
    const cv::Point2f c(region.box.x + 0.5f * region.box.width, region.box.y + 0.5f * region.box.height);
    const float max_area = kRefineMaxGrowth * std::max(16.0f, region.box.area());
    for (const SalientRegion& r : found) {
      if (!r.box.contains(c) || r.box.area() > max_area) continue;
      region.box = r.box;
      region.area = r.area;
      break;
    }
    region.box = extent.grow(frame, region.box, params.extent_contrast);
  }

  void confirm(const cv::Mat& frame) {
    confirmed.clear();
    raw.clear();
    for (const Candidate& c : candidates) raw.push_back(toRegion(c.box, c.area, c.mean, c.peak / 255.0, c.touches_border));
    for (const Track& t : tracks) {
      // Soft sky prior: below the horizon a track must persist twice as long.
      const bool below = params.auto_init_horizon_prior && horizon >= 0 && t.centre.y > horizon;
      const int need = below ? 2 * params.auto_init_frames : params.auto_init_frames;
      if (t.last_frame != frame_index || t.hits < need) continue;
      const int age = frame_index - t.first_frame + 1;
      const double seen = static_cast<double>(t.hits) / age;
      if (params.auto_init_frames > 1 && seen < 0.6) continue;
      if (params.auto_init_shape_filter && isLine(t.box)) continue;

      double score = t.sum_peak / (255.0 * t.hits) * seen;
      if (params.auto_init_min_motion > 0.0) {
        double linearity = 0.0;
        const double motion = motionOf(t, &linearity);
        // At least auto_init_min_motion and half the candidate's size: a region whose extent
        // fluctuates (a textured structure grown at 0.3 x its peak) moves its centre by a
        // fraction of its size without going anywhere.
        const double needed = std::max(params.auto_init_min_motion, 0.5 * std::max(t.box.width, t.box.height));
        if (!t.still && motion >= needed && linearity >= kMinLinearity && changedAgainstBackground(t.box) &&
            vacated(t)) {
          // Steady motion raises the score up to 3x the threshold.
          score *= std::min(1.0, motion / (3.0 * params.auto_init_min_motion));
        } else {
          // No motion: a collision course shows as steady growth instead.
          double fit = 0.0;
          const double growth = params.auto_init_min_growth > 0.0 ? growthOf(t, &fit) : 0.0;
          if (!(growth >= params.auto_init_min_growth) || fit < kMinGrowthFit) continue;
          score *= std::min(1.0, growth / (3.0 * params.auto_init_min_growth));
        }
      }
      if (below) score *= 0.5;
      SalientRegion region = toRegion(t.box, t.area, t.last_mean, score, t.touches_border);
      refine(frame, region);
      confirmed.push_back(region);
    }
    std::sort(confirmed.begin(), confirmed.end(),
              [](const SalientRegion& a, const SalientRegion& b) { return a.score > b.score; });
  }
};

AutoInitializer::AutoInitializer(const Params& params) : impl_(new Impl) { setParams(params); }
AutoInitializer::~AutoInitializer() { delete impl_; }

void AutoInitializer::setParams(const Params& params) {
  impl_->params = params;
  validate(impl_->params);
  Params refine = impl_->params;
  refine.search_window_scale = kRefineWindowScale;
  refine.min_object_area = 1.0;
  impl_->refiner.setParams(refine);
}

void AutoInitializer::reset() { impl_->reset(); }

const std::vector<SalientRegion>& AutoInitializer::update(const cv::Mat& frame, double stamp) {
  (void)stamp;
  if (frame.empty()) throw std::invalid_argument("AutoInitializer::update: empty frame");
  if (frame.type() != CV_8UC1 && frame.type() != CV_8UC3)
    throw std::invalid_argument("AutoInitializer::update: frame must be CV_8UC1 or CV_8UC3");
  Impl& m = *impl_;
  if (frame.size() != m.size) {
    m.reset();
    m.size = frame.size();
  }
  cv::Mat grey = frame;
  if (frame.channels() == 3) {
    grey = m.grey_arena.get(frame.rows, frame.cols, CV_8U);
    cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
  }
  m.globalMotion(grey);
  m.updateStill(grey);
  {
    cv::Mat& slot = m.past[static_cast<size_t>(m.frame_index % (kLag + 1))];
    grey.copyTo(slot);  // allocates once per frame size
    m.past_image_to_first[static_cast<size_t>(m.frame_index % (kLag + 1))] = m.image_to_first;
  }
  const cv::Mat p = m.candidateMap(grey);
  m.findCandidates(p);
  m.associate();
  m.confirm(frame);
  ++m.frame_index;
  return m.confirmed;
}

double AutoInitializer::stillShare(const cv::Rect2f& box) const {
  const cv::Mat& still = impl_->still;
  if (still.empty() || still.size() != impl_->size || !impl_->params.auto_init_reject_static) return 0.0;
  const cv::Rect r = cv::Rect(box) & cv::Rect(0, 0, still.cols, still.rows);
  if (r.area() <= 0) return 0.0;
  return static_cast<double>(impl_->stillPixels(r)) / r.area();
}

double AutoInitializer::overlayShare(const cv::Rect2f& box) const {
  const cv::Point2d s = impl_->motion.workingScale();
  const cv::Rect working(cv::Point(static_cast<int>(box.x * s.x), static_cast<int>(box.y * s.y)),
                         cv::Point(static_cast<int>(std::ceil((box.x + box.width) * s.x)),
                                   static_cast<int>(std::ceil((box.y + box.height) * s.y))));
  return impl_->overlay.share(working);
}

const std::vector<SalientRegion>& AutoInitializer::candidates() const { return impl_->raw; }
cv::Point2d AutoInitializer::backgroundMotion() const { return impl_->background; }

}  // namespace core
}  // namespace obstacle_tracker
