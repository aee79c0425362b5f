// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// portable_math.h: known answers. expInPlace must give e^x rounded to float (what the double exp
// gives, rounded) over the kernel's range, and its limits; blendInPlace and sumOfSquares their
// formulas.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/portable_math.h"

namespace oc = obstacle_tracker::core;

TEST(PortableMath, ExpIsTheDoubleExpRoundedToFloat) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(-87.0f, 10.0f);
  std::vector<float> x(200000), e;
  for (float& v : x) v = value(rng);
  e = x;
  oc::expInPlace(e.data(), static_cast<int>(e.size()));
  int differ = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    differ += e[i] != static_cast<float>(std::exp(static_cast<double>(x[i])));
  }
  EXPECT_EQ(differ, 0);
}

TEST(PortableMath, ExpKnownValuesAndLimits) {
  std::vector<float> x = {0.0f,   1.0f,   -1.0f, std::log(2.0f), -0.5f, -87.0f,
                          -90.0f, -1e30f, 88.0f, 1e30f,          std::numeric_limits<float>::quiet_NaN()};
  oc::expInPlace(x.data(), static_cast<int>(x.size()));
  EXPECT_EQ(x[0], 1.0f);
  EXPECT_EQ(x[1], static_cast<float>(std::exp(1.0)));
  EXPECT_EQ(x[2], static_cast<float>(std::exp(-1.0)));
  EXPECT_EQ(x[3], static_cast<float>(std::exp(static_cast<double>(std::log(2.0f)))));
  EXPECT_EQ(x[4], static_cast<float>(std::exp(-0.5)));
  EXPECT_GT(x[5], 0.0f);  // e^-87 is still a normal float
  EXPECT_EQ(x[6], 0.0f);  // below the normal range
  EXPECT_EQ(x[7], 0.0f);  // clamped, not NaN
  EXPECT_EQ(x[8], static_cast<float>(std::exp(88.0)));
  EXPECT_EQ(x[9], static_cast<float>(std::exp(88.0)));  // clamped, finite
  EXPECT_TRUE(std::isnan(x[10]));
}

TEST(PortableMath, BlendAndSumOfSquares) {
  cv::Mat model = (cv::Mat_<float>(1, 3) << 1.0f, 2.0f, -4.0f);
  const cv::Mat update = (cv::Mat_<float>(1, 3) << 3.0f, 2.0f, 4.0f);
  oc::blendInPlace(model, update, 0.25f);
  EXPECT_FLOAT_EQ(model.at<float>(0), 1.5f);
  EXPECT_FLOAT_EQ(model.at<float>(1), 2.0f);
  EXPECT_FLOAT_EQ(model.at<float>(2), -2.0f);
  EXPECT_DOUBLE_EQ(oc::sumOfSquares(model), 2.25 + 4.0 + 4.0);
}
