// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Bad input into core::Pipeline: empty and wrong-type frames, tiny, thin and huge
// frames, resolution and type changes mid-stream, flat, saturated and noise frames, duplicate,
// backward, jumping and non-finite stamps, non-contiguous frames, bad startTrack boxes and
// NaN / infinite / negative / huge parameters. Nothing may crash; the only exception allowed is
// std::invalid_argument with a message, and the pipeline must work normally afterwards.
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

namespace oc = obstacle_tracker::core;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// A dark, slightly graded background with a bright square: the simplest salient object.
cv::Mat squareFrame(cv::Size size, int type, const cv::Rect& square, int background = 30,
                    int foreground = 220) {
  cv::Mat frame(size, type);
  for (int r = 0; r < size.height; ++r) {
    frame.row(r).setTo(cv::Scalar::all(background + (size.height > 1 ? 10 * r / size.height : 0)));
  }
  cv::rectangle(frame, square, cv::Scalar::all(foreground), cv::FILLED);
  return frame;
}

// Every reported obstacle is finite, inside the frame, with confidence in [0, 1].
void expectValid(const std::vector<oc::Obstacle>& obstacles, cv::Size size, const std::string& what) {
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
bool refusedOrProcessed(const std::function<void()>& f, const std::string& what) {
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
void expectStillWorks(oc::Pipeline& pipeline, double stamp, const std::string& what) {
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
    const cv::Point2f c(obstacles[0].box.x + obstacles[0].box.width / 2,
                        obstacles[0].box.y + obstacles[0].box.height / 2);
    EXPECT_NEAR(c.x, square.x + 10, 4.0) << what;
    EXPECT_NEAR(c.y, square.y + 10, 4.0) << what;
  }
}

}  // namespace

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

TEST(RobustPipeline, DuplicateStampsAndJumpsOfHoursKeepLoomingFinite) {
  oc::Pipeline pipeline;
  const cv::Size size(200, 150);
  cv::Rect square(80, 60, 20, 20);
  double stamp = 100.0;
  ASSERT_FALSE(pipeline.startTrack(squareFrame(size, CV_8UC1, square), stamp, cv::Rect2f(square)).empty());
  auto step = [&](double t, const std::string& what) {
    square.x += 1;
    square.width += 1;  // growing: looming has something to measure
    square.height += 1;
    const auto& obstacles = pipeline.process(squareFrame(size, CV_8UC1, square), t);
    expectValid(obstacles, size, what);
    return obstacles.size();
  };
  for (int i = 0; i < 5; ++i) step(stamp += 0.033, "normal");
  for (int i = 0; i < 5; ++i) step(stamp, "duplicate stamp");  // dt = 0
  step(stamp += 3 * 3600.0, "jump of three hours");
  for (int i = 0; i < 5; ++i) step(stamp += 0.033, "after the jump");
  step(stamp += 1e-9, "tiny dt");
  expectStillWorks(pipeline, stamp + 1.0, "after duplicate stamps and jumps");
}

TEST(RobustPipeline, StampGoingBackwardsResetsTheTracks) {
  oc::Pipeline pipeline;
  const cv::Size size(200, 150);
  const cv::Rect square(80, 60, 20, 20);
  double stamp = 50.0;
  ASSERT_FALSE(pipeline.startTrack(squareFrame(size, CV_8UC1, square), stamp, cv::Rect2f(square)).empty());
  int old_id = -1, old_age = 0;
  for (int i = 0; i < 10; ++i) {
    const auto& obstacles = pipeline.process(squareFrame(size, CV_8UC1, square), stamp += 0.033);
    ASSERT_FALSE(obstacles.empty());
    old_id = obstacles[0].id;
    old_age = obstacles[0].age;
  }
  ASSERT_GE(old_age, 10);
  // A bag that loops: time jumps back by a minute. The old track must not continue.
  const auto& obstacles = pipeline.process(squareFrame(size, CV_8UC1, square), stamp - 60.0);
  expectValid(obstacles, size, "stamp going backwards");
  for (const oc::Obstacle& o : obstacles) {
    EXPECT_NE(o.id, old_id) << "the track survived time going backwards";
    EXPECT_LT(o.age, old_age);
  }
}

TEST(RobustPipeline, NonFiniteStampsAreRefusedOrProcessed) {
  oc::Pipeline pipeline;
  const cv::Size size(160, 120);
  const cv::Rect square(60, 40, 20, 20);
  ASSERT_FALSE(pipeline.startTrack(squareFrame(size, CV_8UC1, square), 1.0, cv::Rect2f(square)).empty());
  for (double stamp : {kNan, kInf, -kInf, -1e300, 1e300, 0.0, -5.0}) {
    const std::string what = "stamp " + std::to_string(stamp);
    refusedOrProcessed([&] { expectValid(pipeline.process(squareFrame(size, CV_8UC1, square), stamp), size, what); }, what);
  }
  expectStillWorks(pipeline, 1e6, "after non-finite stamps");
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

TEST(RobustPipeline, BadStartTrackBoxesAreRefusedOrClipped) {
  oc::Pipeline pipeline;
  const cv::Size size(160, 120);
  const cv::Mat frame = squareFrame(size, CV_8UC3, cv::Rect(60, 40, 20, 20));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<cv::Rect2f> boxes = {
      {nan, 40, 20, 20},   {60, nan, 20, 20},  {60, 40, nan, 20},  {60, 40, 20, inf},
      {-inf, 40, 20, 20},  {60, 40, 0, 20},    {60, 40, 20, 0},    {60, 40, -20, 20},
      {500, 400, 20, 20},  {-100, -100, 20, 20}, {150, 110, 40, 40}, {-10, -10, 30, 30},
      {0, 0, 160, 120},    {-1e9f, -1e9f, 2e9f, 2e9f}, {60.5f, 40.25f, 0.5f, 0.5f},
      {159, 119, 1, 1},    {0, 0, 1e30f, 1e30f}};
  double stamp = 1.0;
  for (const cv::Rect2f& box : boxes) {
    std::ostringstream what;
    what << "startTrack box " << box;
    refusedOrProcessed([&] { expectValid(pipeline.startTrack(frame, stamp, box), size, what.str()); }, what.str());
    refusedOrProcessed([&] { expectValid(pipeline.process(frame, stamp + 0.01), size, what.str() + " then process"); },
                       what.str() + " then process");
    stamp += 0.1;
  }
  expectStillWorks(pipeline, stamp, "after bad startTrack boxes");
}

TEST(RobustPipeline, NonFiniteNegativeAndHugeParametersAreValidated) {
  oc::Pipeline pipeline;
  const cv::Size size(160, 120);
  cv::Rect square(60, 40, 20, 20);
  double stamp = 1.0;
  ASSERT_FALSE(pipeline.startTrack(squareFrame(size, CV_8UC1, square), stamp, cv::Rect2f(square)).empty());
  for (const oc::ParamInfo& info : oc::paramTable()) {
    const std::string type = info.type;
    std::vector<double> values;
    if (type == "double") values = {kNan, kInf, -kInf, -1.0, -1e300, 1e300, 0.0};
    if (type == "int") values = {-1.0, 0.0, 2147483647.0, -2147483648.0};
    for (double v : values) {
      oc::Params p = pipeline.params();
      // Raw writes into the struct, bypassing setParam: setParams must validate them.
#define OT_ROBUST_SET_(t, field, def, lo, hi, unit, doc) \
  if (info.name == std::string(#field)) p.field = static_cast<t>(v);
      if (type == "double") {
        OT_PARAMS(OT_ROBUST_SET_)
      } else if (type == "int") {
        OT_PARAMS(OT_ROBUST_SET_)
      }
#undef OT_ROBUST_SET_
      pipeline.setParams(p);
      const oc::Params& used = pipeline.params();
      for (const oc::ParamInfo& check : oc::paramTable()) {
        const double u = oc::getParam(used, check.name);
        EXPECT_TRUE(u >= check.min_value && u <= check.max_value)
            << check.name << " = " << u << " after setting " << info.name << " = " << v;
      }
      if (std::isnan(v)) {
        EXPECT_EQ(oc::getParam(used, info.name), oc::getParam(oc::Params(), info.name))
            << info.name << ": NaN must fall back to the default";
      }
      for (int i = 0; i < 2; ++i) {
        square.x = 50 + (square.x + 1) % 20;
        const std::string what = std::string(info.name) + " = " + std::to_string(v);
        try {
          expectValid(pipeline.process(squareFrame(size, CV_8UC1, square), stamp += 0.033), size, what);
        } catch (const std::exception& e) {
          ADD_FAILURE() << what << ": " << e.what();
        }
      }
      pipeline.setParams(oc::Params());
    }
  }
  expectStillWorks(pipeline, stamp + 1.0, "after bad parameters");
}

TEST(RobustPipeline, ExtremeValidParameterSetsWork) {
  oc::Params lo, hi;
  for (const oc::ParamInfo& info : oc::paramTable()) {
    oc::setParam(lo, info.name, info.min_value);
    oc::setParam(hi, info.name, info.max_value);
  }
  // The largest saliency side and template size are expensive; a small frame keeps this quick.
  for (const oc::Params* p : {&lo, &hi}) {
    oc::Pipeline pipeline(*p);
    const cv::Size size(96, 72);
    cv::Rect square(40, 30, 12, 12);
    double stamp = 1.0;
    for (int i = 0; i < 6; ++i) {
      const std::string what = std::string(p == &lo ? "all minimum" : "all maximum") + " frame " +
                               std::to_string(i);
      try {
        const auto& obstacles = (i == 1) ? pipeline.startTrack(squareFrame(size, CV_8UC3, square), stamp, cv::Rect2f(square))
                                         : pipeline.process(squareFrame(size, CV_8UC3, square), stamp);
        expectValid(obstacles, size, what);
      } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": " << e.what();
      }
      stamp += 0.033;
      square.x += 1;
    }
  }
}
