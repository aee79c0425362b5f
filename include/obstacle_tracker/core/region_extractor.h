// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The Otsu / connected-regions step that turns any 8-bit saliency map into ranked
// SalientRegions. A building block of the saliency detector (saliency.h), exposed for tests,
// benchmarks and tools.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/mat_arena.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/salient_region.h"

namespace obstacle_tracker {
namespace core {

// Otsu threshold (cv::threshold THRESH_OTSU), 8-connected regions (our own union-find labelling:
// cv::connectedComponents allocates its label table on every call), statistics, filtering and
// ranking (the score is documented in region_extractor.cpp). Regions are mapped to frame
// coordinates with map pixel (c, r) -> frame (offset.x + c * sx, offset.y + r * sy).
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

}  // namespace core
}  // namespace obstacle_tracker
