// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Saliency detector (Bharati et al., T-IV 2018, Algorithm 1 and the re-detection step):
//   1. shrink the frame (or search window) so its longer side is at most saliency_max_side;
//   2. MBD saliency map by FastMBD (Zhang et al., ICCV 2015) on Lab (colour) or grey (thermal),
//      optionally plus MB+'s backgroundness map and smoothing / contrast stretch;
//   3. Otsu threshold of the 8-bit map (cv::threshold THRESH_OTSU is the paper's eqs. 6-11);
//   4. 8-connected regions with area, box, mean saliency, border contact; filtered by
//      min_object_area, max_object_area_fraction and reject_border_regions; ranked (steps 3 and
//      4 and the ranking score: RegionExtractor, region_extractor.cpp).
#include "obstacle_tracker/core/saliency.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/frame_check.h"
#include "obstacle_tracker/core/mat_arena.h"
#include "obstacle_tracker/core/mbd_saliency.h"
#include "obstacle_tracker/core/region_extractor.h"

namespace obstacle_tracker {
namespace core {

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
