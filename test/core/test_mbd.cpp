// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// FastMBD against hand-computed answers and against the brute-force exact MBD (mbd.h).
#include <algorithm>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/mbd.h"

namespace oc = obstacle_tracker::core;

namespace {

cv::Mat runFast(const cv::Mat& img, int passes, int* run = nullptr) {
  cv::Mat d, u, l;
  const int r = oc::fastMbd(img, passes, d, u, l);
  if (run) *run = r;
  return d;
}

int maxAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  double mx = 0.0;
  cv::minMaxLoc(diff.reshape(1), nullptr, &mx);
  return static_cast<int>(mx);
}

}  // namespace

TEST(Mbd, HandComputedPlateau) {
  // Border 10, a 3x3 plateau of 50 in a 7x7 image, one pixel of 10 between: every plateau pixel
  // has barrier |50 - 10| = 40, the background ring 0.
  cv::Mat img(7, 7, CV_8UC1, cv::Scalar(10));
  img(cv::Rect(2, 2, 3, 3)).setTo(50);
  cv::Mat expected(7, 7, CV_8UC1, cv::Scalar(0));
  expected(cv::Rect(2, 2, 3, 3)).setTo(40);
  EXPECT_EQ(maxAbsDiff(runFast(img, 3), expected), 0);
  EXPECT_EQ(maxAbsDiff(oc::exactMbd(img), expected), 0);
}

TEST(Mbd, HandComputedRingAroundDarkCentre) {
  // 9x9: border 0, a closed ring of 100 at distance 2, inside it 30. Any path from the centre
  // crosses the ring and reaches a 0 -> barrier 100; the ring itself: 100 - 0 = 100; the gap
  // ring of 0 between border and ring: 0.
  cv::Mat img(9, 9, CV_8UC1, cv::Scalar(0));
  cv::rectangle(img, cv::Rect(2, 2, 5, 5), cv::Scalar(100), 1);
  img(cv::Rect(3, 3, 3, 3)).setTo(30);
  cv::Mat expected(9, 9, CV_8UC1, cv::Scalar(0));
  expected(cv::Rect(2, 2, 5, 5)).setTo(100);
  EXPECT_EQ(maxAbsDiff(oc::exactMbd(img), expected), 0);
  EXPECT_EQ(maxAbsDiff(runFast(img, 3), expected), 0);
}

// Random non-touching rectangles of random values on a flat background: every pixel's best path
// goes straight out of its rectangle (a raster move), so FastMBD is exact.
static cv::Mat rectanglesImage(cv::RNG& rng, int rows, int cols) {
  cv::Mat img(rows, cols, CV_8UC1, cv::Scalar(rng.uniform(0, 256)));
  cv::Mat used(rows, cols, CV_8UC1, cv::Scalar(0));
  for (int k = 0; k < 4; ++k) {
    const int w = rng.uniform(1, cols / 2), h = rng.uniform(1, rows / 2);
    const cv::Rect r(rng.uniform(1, cols - w), rng.uniform(1, rows - h), w, h);
    const cv::Rect grown = (r + cv::Size(2, 2)) - cv::Point(1, 1);
    if (cv::countNonZero(used(grown & cv::Rect(0, 0, cols, rows))) > 0) continue;
    img(r).setTo(rng.uniform(0, 256));
    used(r).setTo(1);
  }
  return img;
}

TEST(Mbd, ExactOnSeparatedRectanglesOnFlatBackground) {
  cv::RNG rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    const cv::Mat img = rectanglesImage(rng, rng.uniform(8, 20), rng.uniform(8, 20));
    const cv::Mat exact = oc::exactMbd(img);
    EXPECT_GT(cv::countNonZero(exact), 0) << "trial " << trial;  // not all-zero by construction
    EXPECT_EQ(maxAbsDiff(runFast(img, 3), exact), 0) << "trial " << trial;
  }
}

TEST(Mbd, ColourChannelsAreIndependentTransforms) {
  // The interleaved 3-channel path gives each channel its own exact transform.
  cv::RNG rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const int rows = rng.uniform(8, 18), cols = rng.uniform(8, 18);
    cv::Mat ch[3], ex[3];
    for (int k = 0; k < 3; ++k) {
      ch[k] = rectanglesImage(rng, rows, cols);
      ex[k] = oc::exactMbd(ch[k]);
    }
    cv::Mat colour, expected;
    cv::merge(ch, 3, colour);
    cv::merge(ex, 3, expected);
    EXPECT_EQ(maxAbsDiff(runFast(colour, 3), expected), 0) << "trial " << trial;
  }
}

TEST(Mbd, NeverBelowExactOnNoise) {
  // Every FastMBD value is the barrier of a real path, so it bounds the exact MBD from above.
  cv::RNG rng(3);
  int worse = 0;
  for (int trial = 0; trial < 30; ++trial) {
    cv::Mat img(12, 12, CV_8UC1);
    rng.fill(img, cv::RNG::UNIFORM, 0, 256);
    const cv::Mat fast = runFast(img, 3), exact = oc::exactMbd(img);
    cv::Mat below;
    cv::compare(fast, exact, below, cv::CMP_LT);
    EXPECT_EQ(cv::countNonZero(below), 0) << "trial " << trial;
    worse += cv::countNonZero(fast != exact);
  }
  // Noise is the hard case: the test must be able to see a difference (it is not vacuous).
  EXPECT_GT(worse, 0);
}

TEST(Mbd, ConvergedErrorWithinTwiceLocalVariation) {
  // Zhang et al. (ICCV 2015, Sec. 3): the converged raster scan over-estimates the exact MBD by
  // less than 2 eps, eps = the largest 4-neighbour difference. Random smooth images.
  cv::RNG rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    const int rows = rng.uniform(10, 24), cols = rng.uniform(10, 24);
    cv::Mat noise(rows, cols, CV_32F);
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), rng.uniform(0.8, 2.5));
    cv::Mat img;
    cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
    noise.convertTo(img, CV_8U);
    int eps = 0;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        if (c + 1 < cols) eps = std::max(eps, std::abs(img.at<uchar>(r, c) - img.at<uchar>(r, c + 1)));
        if (r + 1 < rows) eps = std::max(eps, std::abs(img.at<uchar>(r, c) - img.at<uchar>(r + 1, c)));
      }
    int run = 0;
    const cv::Mat fast = runFast(img, 10, &run), exact = oc::exactMbd(img);
    cv::Mat diff;
    cv::subtract(fast, exact, diff, cv::noArray(), CV_32S);
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(diff, &lo, &hi);
    EXPECT_GE(lo, 0.0) << "trial " << trial;
    EXPECT_LT(hi, 2.0 * eps) << "trial " << trial << " eps " << eps;
  }
}

TEST(Mbd, StopsWhenConverged) {
  cv::Mat img(10, 10, CV_8UC1, cv::Scalar(20));
  img(cv::Rect(3, 3, 4, 4)).setTo(200);
  int run = 0;
  runFast(img, 10, &run);
  EXPECT_GE(run, 2);
  EXPECT_LT(run, 10);
}

TEST(Mbd, TinyImagesAreAllSeeds) {
  cv::Mat img(2, 5, CV_8UC1, cv::Scalar(90));
  EXPECT_EQ(cv::countNonZero(runFast(img, 3)), 0);
}

TEST(Mbd, BadInputThrows) {
  cv::Mat d, u, l;
  EXPECT_THROW(oc::fastMbd(cv::Mat(), 3, d, u, l), std::invalid_argument);
  EXPECT_THROW(oc::fastMbd(cv::Mat(5, 5, CV_32F, cv::Scalar(0)), 3, d, u, l), std::invalid_argument);
  EXPECT_THROW(oc::fastMbd(cv::Mat(5, 5, CV_8UC1, cv::Scalar(0)), 0, d, u, l), std::invalid_argument);
  EXPECT_THROW(oc::exactMbd(cv::Mat(5, 5, CV_8UC3)), std::invalid_argument);
}
