// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// What the bad-input tests of core::Pipeline share (test_robust_pipeline.cpp,
// test_robust_pipeline_stamps.cpp): a salient square frame, the output contract every answer must
// meet, "refused with std::invalid_argument or processed", and a check that the pipeline still
// works afterwards.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/pipeline.h"

namespace obstacle_tracker {
namespace test {

namespace oc = obstacle_tracker::core;


inline const double kNan = std::numeric_limits<double>::quiet_NaN();
inline const double kInf = std::numeric_limits<double>::infinity();

// A dark, slightly graded background with a bright square: the simplest salient object.
inline cv::Mat squareFrame(cv::Size size, int type, const cv::Rect& square, int background = 30,
                    int foreground = 220) {
  cv::Mat frame(size, type);
  for (int r = 0; r < size.height; ++r) {
    frame.row(r).setTo(cv::Scalar::all(background + (size.height > 1 ? 10 * r / size.height : 0)));
  }
  cv::rectangle(frame, square, cv::Scalar::all(foreground), cv::FILLED);
  return frame;
}

// Every reported obstacle is finite, inside the frame, with confidence in [0, 1].
inline void expectValid(const std::vector<oc::Obstacle>& obstacles, cv::Size size, const std::string& what) {
  for (const oc::Obstacle& o : obstacles) {
    EXPECT_TRUE(std::isfinite(o.box.x) && std::isfinite(o.box.y) && std::isfinite(o.box.width) &&
                std::isfinite(o.box.height))
        << what;
    EXPECT_GT(o.box.width, 0.0f) << what;
    EXPECT_GT(o.box.height, 0.0f) << what;
    // Boxes may leave the frame by a margin when the object does, but never far.
    EXPECT_GT(o.box.x + o.box.width, -1.0f) << what;
    EXPECT_GT(o.box.y + o.box.height, -1.0f) << what;
    EXPECT_LT(o.box.x, size.width + 1.0f) << what;
    EXPECT_LT(o.box.y, size.height + 1.0f) << what;
    EXPECT_GE(o.confidence, 0.0f) << what;
    EXPECT_LE(o.confidence, 1.0f) << what;
    EXPECT_GE(o.id, 0) << what;
    EXPECT_FALSE(std::isnan(o.expansion_rate)) << what;
    EXPECT_FALSE(std::isnan(o.time_to_contact)) << what;
    EXPECT_FALSE(std::isinf(o.expansion_rate)) << what;
  }
}

// Calls f; passes when it returns, or throws std::invalid_argument with a message. Any other
// exception fails the test. Returns true when it threw.
inline bool refusedOrProcessed(const std::function<void()>& f, const std::string& what) {
  try {
    f();
    return false;
  } catch (const std::invalid_argument& e) {
    EXPECT_GT(std::string(e.what()).size(), 10u) << what << ": message too short: " << e.what();
    return true;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": exception other than std::invalid_argument: " << e.what();
    return true;
  }
}

// Runs a few frames of a moving square and checks the pipeline still works (it is not left in
// a broken state by what came before): with startTrack the square is tracked and followed.
inline void expectStillWorks(oc::Pipeline& pipeline, double stamp, const std::string& what) {
  const cv::Size size(160, 120);
  cv::Rect square(60, 40, 20, 20);
  const auto& start = pipeline.startTrack(squareFrame(size, CV_8UC1, square), stamp,
                                          cv::Rect2f(square));
  ASSERT_FALSE(start.empty()) << what << ": startTrack on a clean square gave no obstacle";
  for (int i = 1; i <= 5; ++i) {
    square.x += 2;
    const auto& obstacles = pipeline.process(squareFrame(size, CV_8UC1, square), stamp + i / 30.0);
    expectValid(obstacles, size, what);
    ASSERT_FALSE(obstacles.empty()) << what << ": lost a clean moving square at frame " << i;
    const cv::Point2f c = oc::boxCentre(obstacles[0].box);
    EXPECT_NEAR(c.x, square.x + 10, 4.0) << what;
    EXPECT_NEAR(c.y, square.y + 10, 4.0) << what;
  }
}

}  // namespace test
}  // namespace obstacle_tracker
