// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Per-frame cost of the detection front end while it searches (AutoInitializer::update: background
// motion, overlay mask, candidate map, candidate tracks) at 640x512 and 1920x1080 on the generated
// demo scene. The target for the front end is 1080p within 2x 640x512's time per frame: a wider
// frame is shrunk once to auto_init_max_width and searched at that size (only the refinement of
// a confirmed box runs at the frame's own). Third argument 1: the whole search at the frame's
// own resolution (auto_init_max_width at its maximum), for comparison.
//   cmake --build BUILD --target bench_core && BUILD/bench_core --benchmark_filter=AutoInit
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>

#include "obstacle_tracker/core/auto_init.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace oc = obstacle_tracker::core;
namespace os = obstacle_tracker::scene;

namespace {

constexpr int kRendered = 24;  // frames rendered; played forwards then backwards

std::vector<cv::Mat> demoCycle(cv::Size size, double* fps) {
  os::SceneGenerator gen = os::makeScenario("demo", 7, kRendered, size);
  std::vector<cv::Mat> rendered(kRendered), cycle;
  for (int i = 0; i < kRendered; ++i) gen.renderFrame(i, rendered[i], nullptr);
  for (int i = 0; i < kRendered; ++i) cycle.push_back(rendered[i]);
  for (int i = kRendered - 2; i > 0; --i) cycle.push_back(rendered[i]);
  *fps = gen.fps();
  return cycle;
}

// Every frame goes through update(), as while no track is held. The initialiser is reset every
// cycle so that its candidate tracks stay those of a search, not of a long-confirmed target.
void BM_AutoInitSearch(benchmark::State& state) {
  double fps = 30.0;
  const std::vector<cv::Mat> frames =
      demoCycle(cv::Size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))), &fps);
  oc::SaliencyParams params;
  if (state.range(2) != 0) params.auto_init_max_width = 8192;
  oc::AutoInitializer init(params);
  size_t i = 0;
  double stamp = 0.0;
  for (auto _ : state) {
    if (i == frames.size()) {
      state.PauseTiming();
      init.reset();
      i = 0;
      state.ResumeTiming();
    }
    stamp += 1.0 / fps;
    benchmark::DoNotOptimize(init.update(frames[i++], stamp).data());
  }
  state.counters["megapixels"] = static_cast<double>(state.range(0)) * state.range(1) * 1e-6;
}

}  // namespace

BENCHMARK(BM_AutoInitSearch)
    ->Args({640, 512, 0})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->Unit(benchmark::kMillisecond);
