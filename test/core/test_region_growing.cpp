// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// growRegion8 (region_growing.h) on small images with known regions: 8-connectivity (diagonal
// steps join, a gap of one pixel does not), the breadth-first order of the pixels, the clip
// rectangle, several seeds, a visit that stops the growth, and no reallocation of the queue.
#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "obstacle_tracker/core/region_growing.h"

namespace oc = obstacle_tracker::core;

namespace {

// Grows from `seeds` over the pixels of `image` >= `level`, marking taken pixels in a label image
// (as the auto-initialiser does). Returns the queue: the region's pixels in the order reached.
std::vector<int> grow(const cv::Mat& image, const std::vector<cv::Point>& seeds, int level, const cv::Rect& clip,
                      bool* completed = nullptr) {
  cv::Mat taken(image.size(), CV_8U, cv::Scalar(0));
  std::vector<int> queue;
  for (const cv::Point& s : seeds) {
    taken.at<std::uint8_t>(s) = 1;
    queue.push_back(s.y * image.cols + s.x);
  }
  auto claim = [&](int x, int y) {
    if (taken.at<std::uint8_t>(y, x) != 0 || image.at<std::uint8_t>(y, x) < level) return false;
    taken.at<std::uint8_t>(y, x) = 1;
    return true;
  };
  const bool done = oc::growRegion8(queue, image.cols, clip, claim, [](int, int) { return true; });
  if (completed != nullptr) *completed = done;
  return queue;
}

cv::Mat image5x5(std::initializer_list<std::uint8_t> values) {
  cv::Mat m(5, 5, CV_8U);
  std::copy(values.begin(), values.end(), m.begin<std::uint8_t>());
  return m;
}

}  // namespace

TEST(RegionGrowing, DiagonalStepsJoinAGapDoesNot) {
  const cv::Mat image = image5x5({0, 0, 0, 0, 0,  //
                                  0, 9, 0, 0, 0,  //
                                  0, 0, 9, 9, 0,  //
                                  0, 0, 0, 0, 0,  //
                                  0, 0, 0, 0, 9});
  bool completed = false;
  const std::vector<int> region = grow(image, {{1, 1}}, 5, cv::Rect(0, 0, 5, 5), &completed);
  EXPECT_TRUE(completed);
  // (1,1), then its diagonal neighbour (2,2), then (3,2); (4,4) is two rows below (3,2).
  EXPECT_EQ(region, (std::vector<int>{6, 12, 13}));
}

TEST(RegionGrowing, BreadthFirstInRowOrderOfTheNeighbours) {
  const cv::Mat image(5, 5, CV_8U, cv::Scalar(9));
  const std::vector<int> region = grow(image, {{2, 2}}, 5, cv::Rect(1, 1, 3, 3));
  // The seed, then its 8 neighbours row by row, left to right; nothing outside the clip.
  EXPECT_EQ(region, (std::vector<int>{12, 6, 7, 8, 11, 13, 16, 17, 18}));
}

TEST(RegionGrowing, TheClipBoundsTheRegion) {
  cv::Mat image(5, 5, CV_8U, cv::Scalar(0));
  image.row(2).setTo(9);  // a line across the middle row
  EXPECT_EQ(grow(image, {{2, 2}}, 5, cv::Rect(1, 0, 3, 5)), (std::vector<int>{12, 11, 13}));
  EXPECT_EQ(grow(image, {{2, 2}}, 5, cv::Rect(0, 0, 5, 5)), (std::vector<int>{12, 11, 13, 10, 14}));
}

TEST(RegionGrowing, SeveralSeedsAndAPixelJoinsOnce) {
  // Two blobs, a seed in each, and a third seed in the first: the union, each pixel once.
  cv::Mat image = image5x5({9, 9, 0, 0, 0,  //
                            9, 9, 0, 0, 0,  //
                            0, 0, 0, 0, 0,  //
                            0, 0, 0, 9, 9,  //
                            0, 0, 0, 0, 9});
  // Marking by clearing the pixel, as the extent grower does.
  std::vector<int> queue;
  for (const cv::Point s : {cv::Point(0, 0), cv::Point(1, 1), cv::Point(4, 4)}) {
    image.at<std::uint8_t>(s) = 0;
    queue.push_back(s.y * 5 + s.x);
  }
  auto claim = [&](int x, int y) {
    if (image.at<std::uint8_t>(y, x) <= 4) return false;
    image.at<std::uint8_t>(y, x) = 0;
    return true;
  };
  EXPECT_TRUE(oc::growRegion8(queue, 5, cv::Rect(0, 0, 5, 5), claim, [](int, int) { return true; }));
  EXPECT_EQ(queue, (std::vector<int>{0, 6, 24, 1, 5, 18, 19}));
  EXPECT_EQ(cv::countNonZero(image), 0);
}

TEST(RegionGrowing, AVisitThatReturnsFalseStopsTheGrowth) {
  cv::Mat taken(5, 5, CV_8U, cv::Scalar(0));
  std::vector<int> queue{12};
  taken.at<std::uint8_t>(2, 2) = 1;
  auto claim = [&](int x, int y) {
    if (taken.at<std::uint8_t>(y, x) != 0) return false;
    taken.at<std::uint8_t>(y, x) = 1;
    return true;
  };
  int visited = 0;
  // Stop at the first pixel on the image's edge (the extent grower's "joined to the surroundings").
  auto visit = [&](int x, int y) {
    ++visited;
    return x > 0 && y > 0 && x < 4 && y < 4;
  };
  EXPECT_FALSE(oc::growRegion8(queue, 5, cv::Rect(0, 0, 5, 5), claim, visit));
  // The centre and its 8 neighbours are inside; the 10th pixel visited, (0,0) (reached from
  // (1,1)), is the first on the edge.
  EXPECT_EQ(visited, 10);
}

TEST(RegionGrowing, EachPixelIsQueuedOnceFromSeveralSeeds) {
  // The extent grower seeds with every pixel of the core: growth from several seeds reaches each
  // pixel of the region once.
  cv::Mat taken(5, 5, CV_8U, cv::Scalar(0));
  std::vector<int> queue = {0, 24};
  taken.at<std::uint8_t>(0, 0) = 1;
  taken.at<std::uint8_t>(4, 4) = 1;
  auto claim = [&](int x, int y) {
    if (taken.at<std::uint8_t>(y, x) != 0) return false;
    taken.at<std::uint8_t>(y, x) = 1;
    return true;
  };
  EXPECT_TRUE(oc::growRegion8(queue, 5, cv::Rect(0, 0, 5, 5), claim, [](int, int) { return true; }));
  ASSERT_EQ(queue.size(), 25u);
  std::vector<int> region = queue;
  std::sort(region.begin(), region.end());
  for (int i = 0; i < 25; ++i) EXPECT_EQ(region[static_cast<std::size_t>(i)], i);
}
