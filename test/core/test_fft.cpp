// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// fft.h: known answers. The transforms against a direct DFT in double (every length 1-64, so
// every radix path and the direct sum of prime lengths), their layouts against cv::dft's, the
// inverse after the forward, the twiddles against the double sin/cos, and a bit pattern that a
// machine with other rounding would not reproduce.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "obstacle_tracker/core/fft.h"

namespace oc = obstacle_tracker::core;

namespace {

cv::Mat randomReal(int rows, int cols, unsigned seed) {
  cv::Mat m(rows, cols, CV_32F);
  std::mt19937 rng(seed);  // integers only: the same values from every standard library
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) m.at<float>(r, c) = static_cast<float>(static_cast<int>(rng() % 2001u) - 1000) / 1000.0f;
  }
  return m;
}

// Direct 2-D DFT in double of a real matrix (rows_only: each row's 1-D DFT).
cv::Mat directDft(const cv::Mat& x, bool rows_only) {
  const int R = x.rows, C = x.cols;
  cv::Mat out(R, C, CV_64FC2, cv::Scalar(0, 0));
  for (int u = 0; u < R; ++u) {
    for (int v = 0; v < C; ++v) {
      double re = 0.0, im = 0.0;
      for (int r = 0; r < R; ++r) {
        if (rows_only && r != u) continue;
        for (int c = 0; c < C; ++c) {
          const double a = -2.0 * M_PI * ((rows_only ? 0.0 : static_cast<double>(u) * r / R) +
                                          static_cast<double>(v) * c / C);
          re += x.at<float>(r, c) * std::cos(a);
          im += x.at<float>(r, c) * std::sin(a);
        }
      }
      out.at<cv::Vec2d>(u, v) = cv::Vec2d(re, im);
    }
  }
  return out;
}

double maxError(const cv::Mat& spectrum_f, const cv::Mat& reference_d) {
  double worst = 0.0;
  for (int r = 0; r < reference_d.rows; ++r) {
    for (int c = 0; c < reference_d.cols; ++c) {
      const cv::Vec2f a = spectrum_f.at<cv::Vec2f>(r, c);
      const cv::Vec2d b = reference_d.at<cv::Vec2d>(r, c);
      worst = std::max(worst, std::hypot(a[0] - b[0], a[1] - b[1]));
    }
  }
  return worst;
}

}  // namespace

TEST(Fft, TwiddlesAreTheDoubleSinCosRoundedToFloat) {
  int differ = 0, total = 0;
  for (long n : {1L, 2L, 3L, 5L, 7L, 8L, 24L, 33L, 100L, 360L, 1000L, 4096L}) {
    for (long k = 0; k < n; ++k) {
      const oc::ComplexF w = oc::unitRootTurn(k, n);
      const double a = 2.0 * M_PI * static_cast<double>(k) / static_cast<double>(n);
      // The double sin/cos are within an ulp of the truth; a float rounding of the two can differ
      // only where the value lies within that ulp of a float rounding boundary. Where the truth is
      // 0 (quarter turns), double's pi is not exact but ours is: exactly 0.
      auto same = [](float ours, double reference) {
        return std::abs(reference) < 1e-12 ? ours == 0.0f : ours == static_cast<float>(reference);
      };
      differ += !same(w.re, std::cos(a)) || !same(w.im, -std::sin(a));
      EXPECT_LE(std::abs(w.re - std::cos(a)), 6e-8) << k << "/" << n;
      EXPECT_LE(std::abs(w.im + std::sin(a)), 6e-8) << k << "/" << n;
      ++total;
    }
  }
  EXPECT_LE(differ, total / 1000);
  // Exact values where they exist.
  EXPECT_EQ(oc::unitRootTurn(0, 7).re, 1.0f);
  EXPECT_EQ(oc::unitRootTurn(0, 7).im, 0.0f);
  EXPECT_EQ(oc::unitRootTurn(1, 4).re, 0.0f);
  EXPECT_EQ(oc::unitRootTurn(1, 4).im, -1.0f);
  EXPECT_EQ(oc::unitRootTurn(2, 4).re, -1.0f);
  EXPECT_EQ(oc::unitRootTurn(-1, 4).im, 1.0f);
}

TEST(Fft, ComplexTransformOfEveryLengthMatchesTheDirectSum) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (int n = 1; n <= 64; ++n) {
    std::vector<oc::ComplexF> in(static_cast<std::size_t>(2 * n)), out(static_cast<std::size_t>(n)),
        back(static_cast<std::size_t>(n));
    for (auto& z : in) z = {value(rng), value(rng)};
    oc::ComplexFft fft(n);
    fft.forward(in.data(), 2, out.data());  // every other value: the stride is honoured
    double worst = 0.0;
    for (int k = 0; k < n; ++k) {
      double re = 0.0, im = 0.0;
      for (int j = 0; j < n; ++j) {
        const double a = -2.0 * M_PI * static_cast<double>(j) * k / n;
        const oc::ComplexF x = in[static_cast<std::size_t>(2 * j)];
        re += x.re * std::cos(a) - x.im * std::sin(a);
        im += x.re * std::sin(a) + x.im * std::cos(a);
      }
      worst = std::max(worst, std::hypot(out[static_cast<std::size_t>(k)].re - re,
                                         out[static_cast<std::size_t>(k)].im - im));
    }
    EXPECT_LT(worst, 4e-6 * n) << "n " << n;
    fft.inverse(out.data(), 1, back.data());
    for (int j = 0; j < n; ++j) {
      EXPECT_NEAR(back[static_cast<std::size_t>(j)].re / n, in[static_cast<std::size_t>(2 * j)].re, 2e-6) << n;
      EXPECT_NEAR(back[static_cast<std::size_t>(j)].im / n, in[static_cast<std::size_t>(2 * j)].im, 2e-6) << n;
    }
  }
}

// Transforms side by side (forwardBatch / inverseBatch) give the bits of the same transforms one
// at a time (forward / inverse), for every radix path (lengths 1-40, primes above 5 by the direct
// sum) and batch sizes 1, 3 and 13, read element-major (element i of transform b at i count + b)
// and transform-major (at b n + i). That the bits are also those of the code before the batches is
// BitsAreTheSameOnEveryMachine's job.
TEST(Fft, BatchGivesTheSameBitsAsOneAtATime) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (int n = 1; n <= 40; ++n) {
    oc::ComplexFft fft(n);
    for (int count : {1, 3, 13}) {
      std::vector<oc::ComplexF> in(static_cast<std::size_t>(n) * count);
      for (auto& z : in) z = {value(rng), value(rng)};
      std::vector<float> re(in.size()), im(in.size());
      std::vector<oc::ComplexF> one(static_cast<std::size_t>(n));
      for (bool element_major : {true, false}) {
        const int in_stride = element_major ? count : 1;
        const int batch_stride = element_major ? 1 : n;
        for (bool forward : {true, false}) {
          if (forward) {
            fft.forwardBatch(in.data(), in_stride, batch_stride, count, re.data(), im.data());
          } else {
            fft.inverseBatch(in.data(), in_stride, batch_stride, count, re.data(), im.data());
          }
          int differ = 0;
          for (int b = 0; b < count; ++b) {
            const oc::ComplexF* first = in.data() + static_cast<std::size_t>(b) * batch_stride;
            if (forward) {
              fft.forward(first, in_stride, one.data());
            } else {
              fft.inverse(first, in_stride, one.data());
            }
            for (int i = 0; i < n; ++i) {
              const std::size_t at = static_cast<std::size_t>(i) * count + b;
              differ += std::memcmp(&re[at], &one[static_cast<std::size_t>(i)].re, sizeof(float)) != 0;
              differ += std::memcmp(&im[at], &one[static_cast<std::size_t>(i)].im, sizeof(float)) != 0;
            }
          }
          EXPECT_EQ(differ, 0) << "n " << n << " count " << count << (element_major ? " element" : " transform")
                               << "-major" << (forward ? " forward" : " inverse");
        }
      }
    }
  }
}

TEST(Fft, RealTransformsMatchTheDirectSumAndCvDftLayouts) {
  oc::RealFft2d fft;
  const int sizes[][2] = {{1, 1}, {1, 8}, {8, 1}, {2, 3}, {3, 2}, {5, 5}, {7, 11},
                          {24, 24}, {10, 24}, {24, 15}, {9, 16}, {13, 6}};
  unsigned seed = 1;
  for (const auto& s : sizes) {
    const cv::Mat x = randomReal(s[0], s[1], seed++);
    fft.configure(s[0], s[1]);
    cv::Mat spectrum, back, rows_spectrum, cv_spectrum;
    fft.forward(x, spectrum);
    EXPECT_LT(maxError(spectrum, directDft(x, false)), 2e-5 * s[0] * s[1]) << s[0] << "x" << s[1];
    cv::dft(x, cv_spectrum, cv::DFT_COMPLEX_OUTPUT);
    EXPECT_LT(cv::norm(spectrum, cv_spectrum, cv::NORM_INF), 2e-5 * s[0] * s[1]) << s[0] << "x" << s[1];
    fft.forwardEachRow(x, rows_spectrum);
    EXPECT_LT(maxError(rows_spectrum, directDft(x, true)), 2e-5 * s[1]) << s[0] << "x" << s[1];
    fft.inverse(spectrum, back);
    ASSERT_EQ(back.type(), CV_32F);
    EXPECT_LT(cv::norm(back, x, cv::NORM_INF), 2e-6 * std::log2(2.0 * s[0] * s[1]) + 1e-6) << s[0] << "x" << s[1];
    // The inverse reads columns 0 .. cols/2 only: the others may hold anything.
    for (int r = 0; r < spectrum.rows; ++r) {
      for (int c = s[1] / 2 + 1; c < s[1]; ++c) spectrum.at<cv::Vec2f>(r, c) = cv::Vec2f(1e6f, -1e6f);
    }
    cv::Mat back2;
    fft.inverse(spectrum, back2);
    EXPECT_EQ(cv::norm(back, back2, cv::NORM_INF), 0.0);
  }
}

TEST(Fft, SpectrumOfARealSignalIsExactlyConjugateSymmetric) {
  oc::RealFft2d fft;
  fft.configure(10, 24);
  cv::Mat spectrum;
  fft.forward(randomReal(10, 24, 9), spectrum);
  for (int r = 0; r < 10; ++r) {
    for (int c = 0; c < 24; ++c) {
      const cv::Vec2f a = spectrum.at<cv::Vec2f>(r, c);
      const cv::Vec2f b = spectrum.at<cv::Vec2f>((10 - r) % 10, (24 - c) % 24);
      EXPECT_EQ(a[0], b[0]);
      EXPECT_EQ(a[1], -b[1]);
    }
  }
}

TEST(Fft, KnownAnswers) {
  oc::RealFft2d fft;
  fft.configure(6, 10);
  // A unit impulse at (0, 0) has a flat spectrum; a constant has all its energy at (0, 0).
  cv::Mat impulse = cv::Mat::zeros(6, 10, CV_32F), spectrum;
  impulse.at<float>(0, 0) = 1.0f;
  fft.forward(impulse, spectrum);
  for (int i = 0; i < 60; ++i) {
    EXPECT_EQ(spectrum.at<cv::Vec2f>(i / 10, i % 10), cv::Vec2f(1.0f, 0.0f));
  }
  fft.forward(cv::Mat(6, 10, CV_32F, cv::Scalar(2.0f)), spectrum);
  EXPECT_EQ(spectrum.at<cv::Vec2f>(0, 0), cv::Vec2f(120.0f, 0.0f));
  for (int i = 1; i < 60; ++i) EXPECT_LT(cv::norm(spectrum.at<cv::Vec2f>(i / 10, i % 10)), 1e-5);
  // A cosine of 2 cycles along the rows: +-N/2 at (0, +-2).
  cv::Mat wave(6, 10, CV_32F);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 10; ++c) wave.at<float>(r, c) = static_cast<float>(std::cos(2.0 * M_PI * 2.0 * c / 10.0));
  }
  fft.forward(wave, spectrum);
  EXPECT_NEAR(spectrum.at<cv::Vec2f>(0, 2)[0], 30.0f, 1e-4);
  EXPECT_NEAR(spectrum.at<cv::Vec2f>(0, 8)[0], 30.0f, 1e-4);
  EXPECT_NEAR(spectrum.at<cv::Vec2f>(1, 2)[0], 0.0f, 1e-4);
}

// The same input gives the same bits on every machine: a checksum of the spectra's bit patterns,
// recorded once, over shapes that take every path: radix 4, 2, 3 and 5 (10 x 24), the direct sum
// of primes 7, 11 and 13 with odd row counts (7 x 11, 13 x 6), and row spectra alone of a prime
// times 3 (3 x 33, forwardEachRow). A build whose arithmetic rounds differently (fused
// multiply-adds, another summation order, the C library's sin/cos) changes it.
TEST(Fft, BitsAreTheSameOnEveryMachine) {
  std::uint64_t hash = 1469598103934665603ULL;  // FNV-1a over the float bit patterns
  auto feed = [&hash](const cv::Mat& m) {
    const float* p = m.ptr<float>();
    for (std::size_t i = 0; i < m.total() * m.channels(); ++i) {
      std::uint32_t bits;
      std::memcpy(&bits, &p[i], sizeof bits);
      hash = (hash ^ bits) * 1099511628211ULL;
    }
  };
  oc::RealFft2d fft;
  cv::Mat spectrum, back;
  fft.configure(10, 24);
  const cv::Mat x = randomReal(10, 24, 42);
  fft.forward(x, spectrum);
  fft.inverse(spectrum, back);
  feed(spectrum);
  feed(back);
  EXPECT_EQ(hash, 1074497883954837568ULL) << "record this value if the transform was changed on purpose";
  const int odd_sizes[][2] = {{7, 11}, {13, 6}};
  for (const auto& s : odd_sizes) {
    fft.configure(s[0], s[1]);
    fft.forward(randomReal(s[0], s[1], 43), spectrum);
    fft.inverse(spectrum, back);
    feed(spectrum);
    feed(back);
  }
  fft.configure(1, 33);
  fft.forwardEachRow(randomReal(3, 33, 44), spectrum);
  feed(spectrum);
  EXPECT_EQ(hash, 5817248832401544468ULL) << "record this value if the transform was changed on purpose";
}
