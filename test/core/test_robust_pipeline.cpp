// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Bad frames into core::Pipeline: empty and wrong-type frames, tiny, thin and huge frames,
// resolution and type changes mid-stream, flat, saturated and noise frames, non-contiguous frames.
// Nothing may crash; the only exception allowed is std::invalid_argument with a message, and the
// pipeline must work normally afterwards.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/pipeline.h"
#include "robust_pipeline_checks.h"

namespace oc = obstacle_tracker::core;
using obstacle_tracker::test::expectStillWorks;
using obstacle_tracker::test::expectValid;
using obstacle_tracker::test::kNan;
using obstacle_tracker::test::refusedOrProcessed;
using obstacle_tracker::test::squareFrame;

TEST(RobustPipeline, EmptyAndWrongTypeFramesAreRefusedWithAMessage) {
  oc::Pipeline pipeline;
  const std::vector<cv::Mat> bad = {
      cv::Mat(),
      cv::Mat(0, 10, CV_8UC1),
      cv::Mat(10, 0, CV_8UC3),
      cv::Mat(32, 32, CV_16UC1, cv::Scalar(1000)),
      cv::Mat(32, 32, CV_32FC1, cv::Scalar(kNan)),
      cv::Mat(32, 32, CV_8UC2, cv::Scalar::all(9)),
      cv::Mat(32, 32, CV_8UC4, cv::Scalar::all(9)),
      cv::Mat(32, 32, CV_8SC1, cv::Scalar(-3)),
      cv::Mat(32, 32, CV_64FC3, cv::Scalar::all(0.5)),
  };
  double stamp = 1.0;
  for (const cv::Mat& frame : bad) {
    const std::string what = "type " + std::to_string(frame.type()) + " size " +
                             std::to_string(frame.cols) + "x" + std::to_string(frame.rows);
    try {
      pipeline.process(frame, stamp);
      ADD_FAILURE() << what << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_GT(std::string(e.what()).size(), 10u) << what << ": " << e.what();
    }
    try {
      pipeline.startTrack(frame, stamp, cv::Rect2f(2, 2, 8, 8));
      ADD_FAILURE() << what << " accepted by startTrack";
    } catch (const std::invalid_argument& e) {
      EXPECT_GT(std::string(e.what()).size(), 10u) << what << ": " << e.what();
    }
    stamp += 0.1;
  }
  expectStillWorks(pipeline, stamp, "after refused frames");
}

TEST(RobustPipeline, TinyAndThinFramesAreProcessed) {
  const std::vector<cv::Size> sizes = {{1, 1}, {2, 2}, {3, 3}, {7, 5}, {1, 4000}, {4000, 1},
                                       {2, 4000}, {4000, 2}, {17, 1}, {1, 17}};
  for (int type : {CV_8UC1, CV_8UC3}) {
    for (const cv::Size& size : sizes) {
      oc::Pipeline pipeline;
      cv::RNG rng(size.area() + type);
      for (int i = 0; i < 6; ++i) {
        cv::Mat frame(size, type);
        if (i % 3 == 0) {
          frame.setTo(cv::Scalar::all(i * 40));
        } else if (i % 3 == 1) {
          rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
        } else {
          frame.setTo(cv::Scalar::all(20));
          frame.at<std::uint8_t>(size.height / 2, size.width / 2 * frame.channels()) = 255;
        }
        const std::string what = std::to_string(size.width) + "x" + std::to_string(size.height) +
                                 " type " + std::to_string(type) + " frame " + std::to_string(i);
        try {
          expectValid(pipeline.process(frame, 1.0 + i / 30.0), size, what);
        } catch (const std::exception& e) {
          ADD_FAILURE() << what << ": a small but valid frame threw: " << e.what();
        }
      }
      // startTrack on the whole tiny frame and on a 1x1 box.
      const std::string what = std::to_string(size.width) + "x" + std::to_string(size.height) +
                               " startTrack";
      cv::Mat frame = squareFrame(size, type, cv::Rect(0, 0, 1, 1));
      refusedOrProcessed([&] { expectValid(pipeline.startTrack(frame, 2.0, cv::Rect2f(0, 0, size.width, size.height)), size, what); }, what);
      refusedOrProcessed([&] { expectValid(pipeline.startTrack(frame, 2.1, cv::Rect2f(0, 0, 1, 1)), size, what); }, what);
      refusedOrProcessed([&] { expectValid(pipeline.process(frame, 2.2), size, what); }, what);
    }
  }
}

TEST(RobustPipeline, HugeFrameIsProcessedOrRefusedClearly) {
  // 8000 x 8000 grey (64 MB): one frame, processed or refused with a message; then the pipeline
  // goes on with normal frames.
  oc::Pipeline pipeline;
  const cv::Size size(8000, 8000);
  cv::Mat frame = squareFrame(size, CV_8UC1, cv::Rect(3900, 3900, 200, 200));
  const bool refused = refusedOrProcessed(
      [&] { expectValid(pipeline.process(frame, 1.0), size, "8000x8000"); }, "8000x8000");
  if (refused) {
    std::printf("8000x8000 frame refused (documented maximum)\n");
  }
  frame.release();
  expectStillWorks(pipeline, 2.0, "after an 8000x8000 frame");
}

TEST(RobustPipeline, ResolutionAndTypeChangesMidStreamResetTheTracks) {
  oc::Pipeline pipeline;
  cv::Size size(320, 240);
  cv::Rect square(200, 150, 24, 24);
  double stamp = 10.0;
  ASSERT_FALSE(pipeline.startTrack(squareFrame(size, CV_8UC1, square), stamp, cv::Rect2f(square)).empty());
  int old_id = -1;
  for (int i = 0; i < 5; ++i) {
    const auto& obstacles = pipeline.process(squareFrame(size, CV_8UC1, square), stamp += 0.033);
    ASSERT_FALSE(obstacles.empty());
    old_id = obstacles[0].id;
  }
  // Smaller frame: the old box (around x = 200) lies outside it.
  const cv::Size small(120, 90);
  for (int i = 0; i < 5; ++i) {
    const auto& obstacles =
        pipeline.process(squareFrame(small, CV_8UC1, cv::Rect(50, 35, 16, 16)), stamp += 0.033);
    expectValid(obstacles, small, "after shrinking to 120x90");
    for (const oc::Obstacle& o : obstacles) EXPECT_NE(o.id, old_id) << "track survived a size change";
  }
  // Larger, and colour instead of grey.
  const cv::Size large(640, 480);
  for (int i = 0; i < 5; ++i) {
    const auto& obstacles =
        pipeline.process(squareFrame(large, CV_8UC3, cv::Rect(300, 200, 30, 30)), stamp += 0.033);
    expectValid(obstacles, large, "after growing to 640x480 colour");
  }
  // Same size, grey again, while a track may run.
  for (int i = 0; i < 3; ++i) {
    expectValid(pipeline.process(squareFrame(large, CV_8UC1, cv::Rect(300, 200, 30, 30)), stamp += 0.033),
                large, "colour -> grey");
  }
  expectStillWorks(pipeline, stamp + 1.0, "after size and type changes");
}

TEST(RobustPipeline, FlatFramesGiveNoObstacles) {
  for (int type : {CV_8UC1, CV_8UC3}) {
    for (int value : {0, 128, 255}) {
      oc::Pipeline pipeline;
      const cv::Size size(160, 120);
      for (int i = 0; i < 8; ++i) {
        const auto& obstacles = pipeline.process(cv::Mat(size, type, cv::Scalar::all(value)), 1.0 + i / 30.0);
        EXPECT_TRUE(obstacles.empty()) << "flat frame of value " << value << " type " << type
                                       << " gave " << obstacles.size() << " obstacles";
      }
    }
  }
}

TEST(RobustPipeline, TrackIntoBlackThenSaturatedFramesEndsWithoutStaleBoxes) {
  oc::Pipeline pipeline;
  const cv::Size size(160, 120);
  cv::Rect square(60, 40, 20, 20);
  double stamp = 5.0;
  ASSERT_FALSE(pipeline.startTrack(squareFrame(size, CV_8UC1, square), stamp, cv::Rect2f(square)).empty());
  const int frames = pipeline.params().max_redetect_failures + 5;
  for (int value : {0, 255}) {
    std::size_t last = 1;
    for (int i = 0; i < frames; ++i) {
      const auto& obstacles = pipeline.process(cv::Mat(size, CV_8UC1, cv::Scalar(value)), stamp += 0.033);
      expectValid(obstacles, size, "flat frames while tracking");
      last = obstacles.size();
    }
    EXPECT_EQ(last, 0u) << "still reporting an obstacle after " << frames << " flat frames of " << value;
    EXPECT_EQ(pipeline.state(), oc::TrackState::kSearching);
  }
  expectStillWorks(pipeline, stamp + 1.0, "after flat frames");
}

TEST(RobustPipeline, NoiseFramesNeverBreakTheContract) {
  for (int type : {CV_8UC1, CV_8UC3}) {
    oc::Params params;
    params.max_obstacles = 8;
    oc::Pipeline pipeline(params);
    const cv::Size size(200, 150);
    cv::RNG rng(type + 7);
    cv::Mat frame(size, type);
    for (int i = 0; i < 40; ++i) {
      if (i % 10 < 7) {
        rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
      } else {
        rng.fill(frame, cv::RNG::NORMAL, 128, 60);  // saturates at 0 and 255
      }
      expectValid(pipeline.process(frame, 1.0 + i / 30.0), size, "noise frame " + std::to_string(i));
    }
  }
}

TEST(RobustPipeline, NonContiguousFramesGiveTheSameResultsAsContiguousOnes) {
  // A frame that is a view into a larger buffer (step > width * channels), as a ROI or a driver's
  // padded rows give: must give exactly what its contiguous copy gives.
  for (int type : {CV_8UC1, CV_8UC3}) {
    oc::Pipeline view_pipeline, copy_pipeline;
    const cv::Size size(180, 130);
    cv::Rect square(70, 50, 22, 22);
    double stamp = 3.0;
    for (int i = 0; i < 12; ++i) {
      cv::Mat big = squareFrame(cv::Size(size.width + 37, size.height + 11), type,
                                cv::Rect(square.x + 13, square.y + 5, square.width, square.height));
      cv::Mat view = big(cv::Rect(13, 5, size.width, size.height));
      ASSERT_FALSE(view.isContinuous());
      cv::Mat copy = view.clone();
      stamp += 0.033;
      const auto a = (i == 0) ? view_pipeline.startTrack(view, stamp, cv::Rect2f(square))
                              : view_pipeline.process(view, stamp);
      const auto b = (i == 0) ? copy_pipeline.startTrack(copy, stamp, cv::Rect2f(square))
                              : copy_pipeline.process(copy, stamp);
      ASSERT_EQ(a.size(), b.size()) << "frame " << i;
      for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].box, b[k].box) << "frame " << i;
        EXPECT_EQ(a[k].confidence, b[k].confidence) << "frame " << i;
      }
      square.x += 2;
      square.y += 1;
    }
  }
}
