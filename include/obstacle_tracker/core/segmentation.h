// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Building blocks of the saliency detector, exposed for tests, benchmarks and tools: the MBD
// saliency map of an image (FastMBD + optional MB+ terms) and the Otsu / connected-regions step
// that turns any 8-bit saliency map into ranked SalientRegions.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/saliency.h"

namespace obstacle_tracker {
namespace core {

// A memory block that hands out cv::Mat views; it grows only when a larger view is asked for,
// so a sequence of calls with varying sizes stops allocating once the largest size was seen.
class MatArena {
 public:
  cv::Mat get(int rows, int cols, int type);

 private:
  std::vector<std::uint8_t> memory_;
};

// MBD saliency map (CV_8U, 0..255, max-normalised) of `image` (CV_8UC1 or CV_8UC3 BGR), computed
// at the image's own resolution. Colour: CIE Lab (8-bit OpenCV scaling), the three channel MBD
// maps summed. Options from SaliencyParams: saliency_median, saliency_passes,
// saliency_backgroundness, saliency_postprocess.
class MbdSaliency {
 public:
  // `out` must be a CV_8UC1 Mat of image.size() (a view is fine); it is written in place.
  void compute(const cv::Mat& image, const SaliencyParams& params, cv::Mat& out);

 private:
  void sumChannels(const cv::Mat& dist, int cn, cv::Mat& f);
  void addBackgroundness(const cv::Mat& src, cv::Mat& f);
  void postprocess(cv::Mat& out);

  MatArena lab_, median_, dist_, upper_, lower_, fmap_, fbg_, tmp_a_, tmp_b_;
};

// Otsu threshold (cv::threshold THRESH_OTSU), 8-connected regions (our own union-find labelling:
// cv::connectedComponents allocates its label table on every call), statistics, filtering and
// ranking. Regions are mapped to frame coordinates with map pixel (c, r) -> frame
// (offset.x + c * sx, offset.y + r * sy).
class RegionExtractor {
 public:
  struct Geometry {
    cv::Point2f offset{0.0f, 0.0f};  // frame position of map pixel (0, 0)'s corner
    float sx = 1.0f, sy = 1.0f;      // frame pixels per map pixel
    double frame_area = 0.0;         // for max_object_area_fraction
    bool centre_prior = false;       // windowed mode: favour regions near the map centre
  };
  // Returns the Otsu threshold used.
  double extract(const cv::Mat& map, const Geometry& geometry, const SaliencyParams& params,
                 std::vector<SalientRegion>& regions);
  const cv::Mat& binary() const { return binary_; }

 private:
  int labelComponents();
  struct Accumulator {
    int area, x0, y0, x1, y1;
    std::uint64_t sum;
  };
  MatArena binary_arena_, labels_arena_;
  cv::Mat binary_, labels_;
  std::vector<Accumulator> acc_;
  std::vector<int> parent_;  // union-find of the provisional labels (kept: no allocation per call)
};

// Grows a box found by saliency to the object's visible extent. Otsu's level lies halfway
// between object and background, so on a small or blurred target (a drone of 10x6 px in
// infrared, the thin wings of an aircraft) the salient region is the bright core, while the
// object (and the box a human draws around it) reaches out to where its contrast fades into the
// background. In a window of the core box plus max(6 px, its longer side) on each side:
//   background = per-channel median of the window's outer 2-pixel ring;
//   contrast c = max over channels of |pixel - background|; noise = 1.4826 x median(c) on the ring;
//   object = the 8-connected pixels with c > max(contrast x the 90th percentile of c in the core,
//            3 x noise, 2 grey levels) that are connected to a core pixel above that level.
// The result is the union of the core box and the object's box. The core box comes back
// unchanged when the object reaches the window's edge (it is joined to background structure or
// leaves the frame), when the result would cover more than 4x the core's area, or when the core
// does not stand out of the noise. No heap allocation once the largest window was seen.
class ExtentGrower {
 public:
  // frame: CV_8UC1 or CV_8UC3; contrast: the share of the core's contrast that still counts as
  // object (extent_contrast; <= 0 returns the core unchanged).
  cv::Rect2f grow(const cv::Mat& frame, const cv::Rect2f& core, double contrast);

 private:
  bool growRegion(cv::Mat& c, const cv::Rect& core, int threshold, cv::Rect& bounds);

  MatArena contrast_arena_;
  std::vector<int> queue_;
};

// Ranking score of a region (documented in saliency.cpp): saliency mass = area * mean saliency
// (or area alone with saliency_rank_by_area), times a centre prior in windowed mode.

}  // namespace core
}  // namespace obstacle_tracker
