// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Per-frame cost of the detection front end's motion parts (background_motion.h, overlay_mask.h)
// at 640x512 and 1920x1080 under a steady pan: after the one shrinking pass to the working
// width, the work is the same at every resolution, so 1080p should cost about 640x512's plus
// that pass.
//   cmake --build BUILD --target bench_core && BUILD/bench_core --benchmark_filter=BackgroundMotion
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/background_motion.h"
#include "obstacle_tracker/core/overlay_mask.h"

namespace oc = obstacle_tracker::core;

namespace {

// Frames of a textured world panned by 2 px per frame (scaled with the width), with a text row
// drawn at a fixed image position.
std::vector<cv::Mat> pannedFrames(cv::Size size, int count) {
  cv::RNG rng(77);
  cv::Mat coarse(size.height / 8 + 40, size.width / 8 + 40, CV_32F);
  rng.fill(coarse, cv::RNG::UNIFORM, 60.0, 190.0);
  cv::Mat world;
  cv::resize(coarse, world, cv::Size(coarse.cols * 8, coarse.rows * 8), 0, 0, cv::INTER_CUBIC);
  world.convertTo(world, CV_8U);
  std::vector<cv::Mat> frames;
  const double step = 2.0 * size.width / 640.0;
  for (int i = 0; i < count; ++i) {
    cv::Mat f;
    cv::warpAffine(world, f, cv::Matx23d(1, 0, -step * i, 0, 1, -0.3 * step * i), size);
    cv::putText(f, "AZ 123.4 EL 05.6", cv::Point(20, 40), cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(255), 2);
    frames.push_back(f);
  }
  return frames;
}

void BM_BackgroundMotion(benchmark::State& state) {
  const cv::Size size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const std::vector<cv::Mat> frames = pannedFrames(size, 16);
  oc::BackgroundMotion motion;
  oc::OverlayMask overlay;
  size_t i = 0;
  for (auto _ : state) {
    const auto& e = motion.update(frames[i++ % frames.size()], overlay.mask());
    if (e.known()) overlay.update(motion.previousWorkingFrame(), motion.currentWorkingFrame(), motion.workingTransform());
    benchmark::DoNotOptimize(e.quality);
  }
}

}  // namespace

BENCHMARK(BM_BackgroundMotion)->Args({640, 512})->Args({1920, 1080})->Unit(benchmark::kMillisecond);
