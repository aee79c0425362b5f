// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// RegionExtractor's own 8-connected labelling (src/core/region_extractor.cpp, replaces
// cv::connectedComponents, which allocates its label table on every call): the same components
// and statistics as cv::connectedComponentsWithStats on maps built to stress the union-find
// (noise at every density, U shapes and staircases that join late, diagonal-only contacts,
// single rows and columns), and no heap allocation once the largest map was seen.
// malloc & co. are interposed as in test_kcf_alloc.cpp; the allocation test is skipped under a
// sanitizer or without glibc.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <map>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/region_extractor.h"
#include "obstacle_tracker/core/salient_region.h"

#include "alloc_counter.h"

namespace oc = obstacle_tracker::core;

namespace {

// A saliency-like map whose Otsu binary is the given mask (255 on it, 0 elsewhere: Otsu puts the
// threshold between the two levels) with grey variation on the foreground for the sums.
cv::Mat mapFromMask(const cv::Mat& mask, cv::RNG& rng) {
  cv::Mat map(mask.size(), CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < mask.rows; ++r)
    for (int c = 0; c < mask.cols; ++c)
      if (mask.at<uchar>(r, c)) map.at<uchar>(r, c) = static_cast<uchar>(rng.uniform(200, 256));
  return map;
}

cv::Mat randomMask(cv::RNG& rng, cv::Size size) {
  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  switch (rng.uniform(0, 4)) {
    case 0: {  // noise of a random density
      const double density = rng.uniform(0.05, 0.9);
      for (int r = 0; r < size.height; ++r)
        for (int c = 0; c < size.width; ++c) mask.at<uchar>(r, c) = rng.uniform(0.0, 1.0) < density ? 1 : 0;
      break;
    }
    case 1: {  // U shapes and combs: arms labelled separately that join on a lower row
      for (int k = 0; k < 4; ++k) {
        const int x0 = rng.uniform(0, size.width), y0 = rng.uniform(0, size.height);
        const int arms = rng.uniform(2, 6), gap = rng.uniform(1, 4), len = rng.uniform(2, 20);
        for (int a = 0; a < arms; ++a) cv::line(mask, {x0 + a * (gap + 1), y0}, {x0 + a * (gap + 1), y0 + len}, 1);
        cv::line(mask, {x0, y0 + len}, {x0 + (arms - 1) * (gap + 1), y0 + len}, 1);
      }
      break;
    }
    case 2: {  // staircases and diagonal-only contacts
      for (int k = 0; k < 5; ++k) {
        int x = rng.uniform(0, size.width), y = rng.uniform(0, size.height);
        const int dir = rng.uniform(0, 2) ? 1 : -1;
        for (int s = 0; s < 25; ++s) {
          if (x >= 0 && x < size.width && y >= 0 && y < size.height) mask.at<uchar>(y, x) = 1;
          x += dir;
          y += 1;
        }
      }
      break;
    }
    default: {  // dots on a grid: one component per 2x2 block at most
      for (int r = 0; r < size.height; r += 2)
        for (int c = 0; c < size.width; c += 2) mask.at<uchar>(r, c) = rng.uniform(0, 3) ? 1 : 0;
      break;
    }
  }
  return mask;
}

using Key = std::tuple<int, int, int, int, int>;  // x, y, w, h, area (map pixels)

}  // namespace

TEST(RegionLabels, SameComponentsAndStatisticsAsOpenCv) {
  cv::RNG rng(77);
  oc::RegionExtractor ex;
  oc::Params p;
  p.min_object_area = 1.0;
  p.max_object_area_fraction = 1.0;
  p.reject_border_regions = false;
  std::vector<oc::SalientRegion> regions;
  int compared = 0;
  for (int trial = 0; trial < 400; ++trial) {
    cv::Size size(rng.uniform(1, 90), rng.uniform(1, 70));
    if (trial % 10 == 0) size.height = 1;
    if (trial % 10 == 1) size.width = 1;
    const cv::Mat mask = randomMask(rng, size);
    if (cv::countNonZero(mask) == 0 || cv::countNonZero(mask) == static_cast<int>(mask.total())) continue;  // no Otsu split
    const cv::Mat map = mapFromMask(mask, rng);
    oc::RegionExtractor::Geometry g;
    g.frame_area = 1e9;
    ex.extract(map, g, p, regions);
    ASSERT_EQ(cv::countNonZero(ex.binary() != mask * 255), 0) << "trial " << trial;

    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(ex.binary(), labels, stats, centroids, 8, CV_32S);
    std::map<Key, double> want;  // -> mean saliency
    for (int i = 1; i < n; ++i) {
      const Key k{stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                  stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT),
                  stats.at<int>(i, cv::CC_STAT_AREA)};
      want[k] = cv::mean(map, labels == i)[0] / 255.0;
    }
    ASSERT_EQ(static_cast<int>(regions.size()), n - 1) << "trial " << trial << " size " << size;
    std::map<Key, double> got;
    for (const auto& r : regions) {
      got[Key{static_cast<int>(r.box.x), static_cast<int>(r.box.y), static_cast<int>(r.box.width),
              static_cast<int>(r.box.height), static_cast<int>(r.area)}] = r.mean_saliency;
    }
    ASSERT_EQ(got.size(), want.size()) << "trial " << trial;
    for (const auto& kv : want) {
      const auto it = got.find(kv.first);
      ASSERT_NE(it, got.end()) << "trial " << trial << ": a component missing or with other statistics";
      EXPECT_NEAR(it->second, kv.second, 1e-5);
    }
    ++compared;
  }
  EXPECT_GT(compared, 300);
}

TEST(RegionLabels, NoHeapAllocationAfterTheLargestMap) {
  OT_SKIP_UNLESS_COUNTING_ALLOCATIONS();
  cv::RNG rng(5);
  oc::RegionExtractor ex;
  oc::Params p;
  p.min_object_area = 1.0;
  p.max_object_area_fraction = 1.0;
  p.reject_border_regions = false;
  std::vector<oc::SalientRegion> regions;
  regions.reserve(100 * 80);
  oc::RegionExtractor::Geometry g;
  g.frame_area = 1e9;
  // The largest map, with the most components it can have (isolated dots on a 2-pixel grid).
  cv::Mat dots(80, 100, CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < dots.rows; r += 2)
    for (int c = 0; c < dots.cols; c += 2) dots.at<uchar>(r, c) = 1;
  ex.extract(mapFromMask(dots, rng), g, p, regions);
  ASSERT_EQ(regions.size(), 40u * 50u);
  std::vector<cv::Mat> maps;
  for (int i = 0; i < 30; ++i) maps.push_back(mapFromMask(randomMask(rng, cv::Size(rng.uniform(2, 101), rng.uniform(2, 81))), rng));
  g_allocations = 0;
  g_counting = true;
  for (const auto& m : maps) ex.extract(m, g, p, regions);
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 0);
}
