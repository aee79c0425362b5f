// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/fhog.h"

namespace oc = obstacle_tracker::core;
using Fhog = oc::FhogExtractor;

namespace {

// Sum of channel c over the interior cells (excluding the outer ring).
double channelSum(const cv::Mat& f, int rows, int cols, int c, bool interior = true) {
  double s = 0.0;
  const int m = interior ? 1 : 0;
  for (int r = m; r < rows - m; ++r) {
    for (int k = m; k < cols - m; ++k) s += f.at<float>(c * rows + r, k);
  }
  return s;
}

int strongestSensitiveBin(const cv::Mat& f, int rows, int cols) {
  int best = -1;
  double best_v = -1.0;
  for (int o = 0; o < Fhog::kOrientations; ++o) {
    const double v = channelSum(f, rows, cols, o);
    if (v > best_v) {
      best_v = v;
      best = o;
    }
  }
  return best;
}

}  // namespace

TEST(Fhog, SizesAndLayout) {
  Fhog fhog;
  cv::Mat patch(50, 37, CV_8UC3, cv::Scalar(10, 20, 30));
  cv::Mat out;
  fhog.compute(patch, 4, out);
  EXPECT_EQ(out.type(), CV_32F);
  EXPECT_EQ(out.rows, Fhog::kChannels * (50 / 4));
  EXPECT_EQ(out.cols, 37 / 4);
  EXPECT_TRUE(out.isContinuous());
  fhog.compute(patch(cv::Rect(0, 0, 8, 8)), 8, out);
  EXPECT_EQ(out.rows, Fhog::kChannels);
  EXPECT_EQ(out.cols, 1);
}

TEST(Fhog, ConstantImageHasZeroGradientChannelsAndItsGreyLevel) {
  Fhog fhog;
  cv::Mat out;
  for (int value : {0, 128, 255}) {
    cv::Mat patch(32, 48, CV_8UC1, cv::Scalar(value));
    fhog.compute(patch, 4, out);
    const int rows = 8, cols = 12;
    for (int c = 0; c < Fhog::kHogChannels; ++c) {
      EXPECT_EQ(channelSum(out, rows, cols, c, false), 0.0) << "channel " << c;
    }
    const float expected = value / 255.0f - 0.5f;
    for (int r = 0; r < rows; ++r) {
      for (int k = 0; k < cols; ++k) {
        EXPECT_NEAR(out.at<float>(Fhog::kGreyChannel * rows + r, k), expected, 1e-5);
      }
    }
  }
}

TEST(Fhog, VerticalEdgeVotesIntoTheHorizontalGradientBins) {
  Fhog fhog;
  cv::Mat out;
  const int rows = 8, cols = 8;
  // Dark left half, bright right half: gradient points +x -> sensitive bin 0 (0 degrees),
  // insensitive bin 0.
  cv::Mat patch(32, 32, CV_8UC1, cv::Scalar(20));
  patch(cv::Rect(16, 0, 16, 32)).setTo(200);
  fhog.compute(patch, 4, out);
  EXPECT_EQ(strongestSensitiveBin(out, rows, cols), 0);
  EXPECT_GT(channelSum(out, rows, cols, 18), 0.0);
  for (int o = 1; o < 9; ++o) EXPECT_EQ(channelSum(out, rows, cols, 18 + o), 0.0) << o;
  // Mirrored: gradient points -x -> sensitive bin 9 (180 degrees), same insensitive bin.
  cv::flip(patch, patch, 1);
  fhog.compute(patch, 4, out);
  EXPECT_EQ(strongestSensitiveBin(out, rows, cols), 9);
  EXPECT_GT(channelSum(out, rows, cols, 18), 0.0);
  // Horizontal edge, bright bottom (image y grows downwards): 90 degrees -> bin 4.5 is not a bin;
  // the 9 directions are k * 20 degrees, so 90 degrees lies between bins 4 (80) and 5 (100)
  // at equal distance; rotate the edge to 60 degrees instead (bin 3) with an analytic image.
  cv::Mat ramp(32, 32, CV_8UC1);
  const double a = 60.0 * M_PI / 180.0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      ramp.at<uchar>(y, x) = cv::saturate_cast<uchar>(128 + 3.0 * (std::cos(a) * (x - 16) +
                                                                    std::sin(a) * (y - 16)));
    }
  }
  fhog.compute(ramp, 4, out);
  EXPECT_EQ(strongestSensitiveBin(out, rows, cols), 3);
}

TEST(Fhog, ColourUsesTheStrongestChannelAndTruncationHolds) {
  Fhog fhog;
  cv::Mat out_colour, out_grey;
  // Only the red channel has an edge; the grey conversion would weaken it but fHOG takes the
  // channel with the largest gradient, so the orientation energy equals the single-channel case.
  cv::Mat colour(32, 32, CV_8UC3, cv::Scalar(50, 50, 20));
  colour(cv::Rect(16, 0, 16, 32)).setTo(cv::Scalar(50, 50, 220));
  cv::Mat red(32, 32, CV_8UC1, cv::Scalar(20));
  red(cv::Rect(16, 0, 16, 32)).setTo(220);
  fhog.compute(colour, 4, out_colour);
  fhog.compute(red, 4, out_grey);
  const int rows = 8, cols = 8;
  for (int c = 0; c < Fhog::kHogChannels; ++c) {
    EXPECT_NEAR(channelSum(out_colour, rows, cols, c, false),
                channelSum(out_grey, rows, cols, c, false), 1e-4)
        << c;
  }
  // Each orientation value is half a sum of 4 values truncated at 0.2: at most 0.4.
  cv::Mat noise(64, 64, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  fhog.compute(noise, 4, out_colour);
  double mn, mx;
  cv::minMaxLoc(out_colour.rowRange(0, 27 * 16), &mn, &mx);
  EXPECT_GE(mn, 0.0);
  EXPECT_LE(mx, 0.4 + 1e-6);
  cv::minMaxLoc(out_colour.rowRange(27 * 16, 31 * 16), &mn, &mx);
  EXPECT_LE(mx, 0.2357 * 18 * 0.2 + 1e-5);
}

TEST(Fhog, IsInvariantToContrastScaling) {
  // Block normalisation: multiplying the gradients by 2 leaves the HOG channels (almost) unchanged.
  Fhog fhog;
  cv::Mat base(40, 40, CV_8UC1);
  cv::RNG rng(3);
  rng.fill(base, cv::RNG::UNIFORM, 40, 100);
  cv::GaussianBlur(base, base, cv::Size(5, 5), 1.0);
  cv::Mat doubled;
  base.convertTo(doubled, CV_8U, 2.0);
  cv::Mat a, b;
  fhog.compute(base, 4, a);
  fhog.compute(doubled, 4, b);
  const int plane = 10 * 10;
  double max_diff = 0.0;
  for (int i = 0; i < Fhog::kHogChannels * plane; ++i) {
    max_diff = std::max(max_diff, std::abs(static_cast<double>(a.ptr<float>()[i] - b.ptr<float>()[i])));
  }
  EXPECT_LT(max_diff, 0.03);
}

TEST(Fhog, BadInputThrows) {
  Fhog fhog;
  cv::Mat out;
  EXPECT_THROW(fhog.compute(cv::Mat(), 4, out), std::invalid_argument);
  EXPECT_THROW(fhog.compute(cv::Mat(16, 16, CV_32F, cv::Scalar(0)), 4, out), std::invalid_argument);
  EXPECT_THROW(fhog.compute(cv::Mat(16, 16, CV_8UC1, cv::Scalar(0)), 0, out), std::invalid_argument);
  EXPECT_THROW(fhog.compute(cv::Mat(3, 16, CV_8UC1, cv::Scalar(0)), 4, out), std::invalid_argument);
}

// The same patch gives the same bits on every machine and on every code path: a checksum of the
// features' bit patterns over grey and BGR patches whose widths take the vectorised gradient's
// full blocks, its scalar ends (first and last pixel, the tail after the last block), rows with no
// whole block, and sides that are not a multiple of the cell. A change of rounding or of the
// channel select (ties keep the first channel) changes it.
TEST(Fhog, BitsAreTheSameOnEveryMachineAndPath) {
  std::uint64_t hash = 1469598103934665603ULL;  // FNV-1a over the float bit patterns
  auto feed = [&hash](const cv::Mat& m) {
    for (int r = 0; r < m.rows; ++r) {
      const float* p = m.ptr<float>(r);
      for (int i = 0; i < m.cols; ++i) {
        std::uint32_t bits;
        std::memcpy(&bits, &p[i], sizeof bits);
        hash = (hash ^ bits) * 1099511628211ULL;
      }
    }
  };
  cv::RNG rng(20261206);
  Fhog fhog;
  cv::Mat features;
  const int widths[] = {1, 2, 3, 8, 16, 17, 18, 19, 33, 34, 35, 50, 67, 97};
  for (const int type : {CV_8UC1, CV_8UC3}) {
    for (const int w : widths) {
      for (const int h : {3, 5, 9}) {
        cv::Mat patch(h, w, type);
        rng.fill(patch, cv::RNG::UNIFORM, 0, 256);
        // Ties that decide: in the rows up to the middle one, channel 1 is channel 0 mirrored
        // (255 - v) and channel 2 a quarter of it, so on the rows above the middle channels 0 and
        // 1 have the same gradient magnitude in opposite directions, and the select must keep
        // channel 0's. The rows below keep three independent channels.
        if (type == CV_8UC3) {
          for (int y = 0; y <= h / 2; ++y) {
            for (int x = 0; x < w; ++x) {
              cv::Vec3b& p = patch.at<cv::Vec3b>(y, x);
              p[1] = static_cast<uchar>(255 - p[0]);
              p[2] = static_cast<uchar>(p[0] / 4);
            }
          }
        }
        const int cell = w < 8 ? 1 : 4;
        if (h < cell) continue;
        fhog.compute(patch, cell, features);
        feed(features);
      }
    }
  }
  EXPECT_EQ(hash, 8919528066802695106ULL) << "record this value if the features were changed on purpose";
}
