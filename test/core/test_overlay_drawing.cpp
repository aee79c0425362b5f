// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known answers for the overlay (overlay_drawing.h): the obstacles' boxes in their state colours,
// the ground-truth box of track_sequence --overlay (white, beneath the obstacles, only when
// given) and the status banner.
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "obstacle_tracker/core/overlay_drawing.h"

namespace core = obstacle_tracker::core;

namespace {

const cv::Vec3b kGrey(100, 100, 100);
const cv::Vec3b kWhite(255, 255, 255);
const cv::Vec3b kBlack(0, 0, 0);

core::Obstacle obstacleAt(const cv::Rect2f& box, core::TrackState state) {
  core::Obstacle o;
  o.id = 1;
  o.box = box;
  o.state = state;
  return o;
}

int countColour(const cv::Mat& image, const cv::Vec3b& colour) {
  int n = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) n += image.at<cv::Vec3b>(y, x) == colour ? 1 : 0;
  }
  return n;
}

}  // namespace

TEST(Overlay, BoxIsDrawnInTheStateColour) {
  const cv::Mat grey(120, 160, CV_8UC1, cv::Scalar(100));
  cv::Mat out;
  core::OverlayExtras extras;
  extras.status = "tracking";
  core::drawOverlay(grey, {obstacleAt(cv::Rect2f(40.0f, 40.0f, 50.0f, 30.0f), core::TrackState::kTracking)},
                    extras, out);
  ASSERT_EQ(out.type(), CV_8UC3);
  EXPECT_EQ(out.at<cv::Vec3b>(55, 40), cv::Vec3b(0, 255, 0));  // left edge of the box
  EXPECT_EQ(out.at<cv::Vec3b>(55, 65), kGrey);                  // inside: untouched
}

TEST(Overlay, EachStateHasItsColour) {
  const cv::Mat bgr(120, 160, CV_8UC3, cv::Scalar(100, 100, 100));
  const std::vector<std::pair<core::TrackState, cv::Vec3b>> cases = {
      {core::TrackState::kTracking, {0, 255, 0}},
      {core::TrackState::kRedetecting, {0, 165, 255}},
      {core::TrackState::kLost, {0, 0, 255}},
      {core::TrackState::kSearching, {255, 255, 0}}};
  for (const auto& c : cases) {
    cv::Mat out;
    core::drawOverlay(bgr, {obstacleAt(cv::Rect2f(40.0f, 40.0f, 50.0f, 30.0f), c.first)}, {}, out);
    EXPECT_EQ(out.at<cv::Vec3b>(55, 40), c.second) << core::toString(c.first);
  }
  EXPECT_EQ(bgr.at<cv::Vec3b>(55, 40), kGrey);  // the frame itself is not drawn on
}

TEST(Overlay, GroundTruthIsWhiteBeneathTheObstaclesAndOnlyWhenGiven) {
  const cv::Mat grey(120, 160, CV_8UC1, cv::Scalar(100));
  // The obstacle shares the ground truth's left edge from row 40 to 70.
  const std::vector<core::Obstacle> obstacles = {
      obstacleAt(cv::Rect2f(20.0f, 40.0f, 50.0f, 30.0f), core::TrackState::kTracking)};
  core::OverlayExtras extras;
  extras.ground_truth = cv::Rect2f(20.0f, 20.0f, 100.0f, 80.0f);
  cv::Mat out;
  core::drawOverlay(grey, obstacles, extras, out);
  EXPECT_EQ(out.at<cv::Vec3b>(30, 20), kWhite);                 // left edge above the obstacle
  EXPECT_EQ(out.at<cv::Vec3b>(99, 70), kWhite);                 // bottom edge
  EXPECT_EQ(out.at<cv::Vec3b>(55, 20), cv::Vec3b(0, 255, 0));   // the obstacle's box on top
  EXPECT_EQ(out.at<cv::Vec3b>(60, 100), kGrey);                 // inside: untouched

  cv::Mat without;
  core::drawOverlay(grey, obstacles, {}, without);
  EXPECT_EQ(without.at<cv::Vec3b>(30, 20), kGrey);
  EXPECT_EQ(countColour(without, kWhite), 0);

  extras.ground_truth = cv::Rect2f(20.0f, 20.0f, 0.0f, 0.0f);  // absent (evaluation's 0,0,0,0)
  core::drawOverlay(grey, obstacles, extras, out);
  EXPECT_EQ(countColour(out, kWhite), 0);
}

TEST(Overlay, StatusIsABannerInTheTopLeftCorner) {
  const cv::Mat grey(120, 160, CV_8UC1, cv::Scalar(100));
  core::OverlayExtras extras;
  extras.status = "frame 12  tracking  obstacles: 1";
  cv::Mat out;
  core::drawOverlay(grey, {}, extras, out);
  EXPECT_EQ(out.at<cv::Vec3b>(1, 1), kBlack);
  // The text, anti-aliased: light grey to white on the black banner.
  cv::Mat banner_grey;
  cv::extractChannel(out(cv::Rect(0, 0, 100, 12)), banner_grey, 0);
  EXPECT_GT(cv::countNonZero(banner_grey > 150), 10);
  EXPECT_EQ(out.at<cv::Vec3b>(110, 150), kGrey);

  core::drawOverlay(grey, {}, {}, out);
  EXPECT_EQ(out.at<cv::Vec3b>(1, 1), kGrey);
  EXPECT_EQ(countColour(out, kWhite), 0);
}
