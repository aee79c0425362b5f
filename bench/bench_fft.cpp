// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// One real 2-D forward + inverse transform of the correlation filter's sizes (a 24 x 24 cell
// template, and 20 x 30 for a wide one) with our portable FFT (fft.h) beside cv::dft, in the same
// run: what the portability costs or saves.
//   bench_core --benchmark_filter='Fft'
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>

#include "obstacle_tracker/core/fft.h"

namespace {

cv::Mat randomPlane(int rows, int cols) {
  cv::Mat m(rows, cols, CV_32F);
  cv::RNG rng(7);
  rng.fill(m, cv::RNG::UNIFORM, -1.0, 1.0);
  return m;
}

void BM_FftOurs(benchmark::State& state) {
  const cv::Mat x = randomPlane(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  obstacle_tracker::core::RealFft2d fft;
  fft.configure(x.rows, x.cols);
  cv::Mat spectrum, back;
  for (auto _ : state) {
    fft.forward(x, spectrum);
    fft.inverse(spectrum, back);
    benchmark::DoNotOptimize(back.data);
  }
}

void BM_FftOpenCv(benchmark::State& state) {
  const cv::Mat x = randomPlane(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  cv::Mat spectrum, back;
  for (auto _ : state) {
    cv::dft(x, spectrum, cv::DFT_COMPLEX_OUTPUT);
    cv::dft(spectrum, back, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
    benchmark::DoNotOptimize(back.data);
  }
}

}  // namespace

BENCHMARK(BM_FftOurs)->Args({24, 24})->Args({20, 30});
BENCHMARK(BM_FftOpenCv)->Args({24, 24})->Args({20, 30});
