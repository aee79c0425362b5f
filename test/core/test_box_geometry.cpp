// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known answers of box_geometry.h's boxNearFrameEdge (the verification's growth test follows it).
#include <gtest/gtest.h>

#include "obstacle_tracker/core/box_geometry.h"

namespace obstacle_tracker {
namespace core {
namespace {

const cv::Size kFrame(640, 512);

TEST(BoxGeometry, BoxInTheMiddleIsNotNearTheEdge) {
  EXPECT_FALSE(boxNearFrameEdge(cv::Rect2f(300.0f, 240.0f, 40.0f, 30.0f), kFrame));
}

// Exactly its own size from an edge is far enough; a tenth of a pixel closer is not. Each edge
// is compared with the box's size along its own axis.
TEST(BoxGeometry, NearEachEdgeByTheBoxsOwnSize) {
  const float w = 20.0f, h = 10.0f;
  EXPECT_FALSE(boxNearFrameEdge(cv::Rect2f(w, h, w, h), kFrame));
  EXPECT_TRUE(boxNearFrameEdge(cv::Rect2f(w - 0.1f, 200.0f, w, h), kFrame));          // left
  EXPECT_TRUE(boxNearFrameEdge(cv::Rect2f(300.0f, h - 0.1f, w, h), kFrame));          // top
  EXPECT_FALSE(boxNearFrameEdge(cv::Rect2f(640.0f - 2 * w, 200.0f, w, h), kFrame));   // right, just far
  EXPECT_TRUE(boxNearFrameEdge(cv::Rect2f(640.0f - 2 * w + 0.1f, 200.0f, w, h), kFrame));
  EXPECT_FALSE(boxNearFrameEdge(cv::Rect2f(300.0f, 512.0f - 2 * h, w, h), kFrame));  // bottom, just far
  EXPECT_TRUE(boxNearFrameEdge(cv::Rect2f(300.0f, 512.0f - 2 * h + 0.1f, w, h), kFrame));
}

// A tall thin box 6 px above the bottom edge (a pole entering the view): near along its height,
// although its width is far from both side edges; the same box turned on its side is not.
TEST(BoxGeometry, ThinBoxesAreJudgedPerAxis) {
  EXPECT_TRUE(boxNearFrameEdge(cv::Rect2f(598.0f, 488.0f, 2.0f, 18.0f), kFrame));
  EXPECT_FALSE(boxNearFrameEdge(cv::Rect2f(580.0f, 488.0f, 18.0f, 2.0f), kFrame));
}

TEST(BoxGeometry, BoxOutsideOrAcrossTheFrameIsNear) {
  EXPECT_TRUE(boxNearFrameEdge(cv::Rect2f(-5.0f, 100.0f, 20.0f, 20.0f), kFrame));
  EXPECT_TRUE(boxNearFrameEdge(cv::Rect2f(630.0f, 100.0f, 20.0f, 20.0f), kFrame));
  EXPECT_TRUE(boxNearFrameEdge(cv::Rect2f(0.0f, 0.0f, 640.0f, 512.0f), kFrame));
}

}  // namespace
}  // namespace core
}  // namespace obstacle_tracker
