// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Bad stamps, boxes and parameters into core::Pipeline: duplicate, backward, jumping and
// non-finite stamps, bad startTrack boxes, NaN / infinite / negative / huge parameters and extreme
// valid ones. Nothing may crash; the only exception allowed is std::invalid_argument with a
// message, and the pipeline must work normally afterwards.
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
using obstacle_tracker::test::kInf;
using obstacle_tracker::test::kNan;
using obstacle_tracker::test::refusedOrProcessed;
using obstacle_tracker::test::squareFrame;

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
