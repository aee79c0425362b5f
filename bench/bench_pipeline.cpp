// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Whole loop per frame: core::Pipeline::process on a generated flight scene (the README demo
// scenario: an aircraft approaching over clouds and a tree line, camera jitter, sensor noise) at
// 640x480 and 1280x720, started by itself (auto) or from the first ground-truth box (gt), beside
// OpenCV's TrackerKCF and TrackerCSRT updated on the same frames from the same box, in the same
// run. The clip is played forwards then backwards (a cycle without a jump), so a benchmark can
// loop over it for as long as it needs; frames are rendered once, before timing.
//   bench_core --benchmark_filter=Loop
#include <cmath>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/tracking.hpp>

#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace oc = obstacle_tracker::core;
namespace os = obstacle_tracker::scene;

namespace {

constexpr int kRendered = 40;  // frames rendered; the cycle is 2 * kRendered - 2 long

struct Clip {
  std::vector<cv::Mat> frames;  // the cycle, as shared headers
  cv::Rect2f first_box;
  double fps = 30.0;
};

const Clip& clip(int width, int height) {
  static Clip small, large;
  Clip& c = width <= 640 ? small : large;
  if (!c.frames.empty()) return c;
  os::SceneGenerator gen = os::makeScenario("demo", 7, kRendered, cv::Size(width, height));
  std::vector<cv::Mat> rendered(kRendered);
  for (int i = 0; i < kRendered; ++i) {
    os::FrameTruth truth;
    gen.renderFrame(i, rendered[i], &truth);
    if (i == 0) {
      const os::ObstacleTruth* main = truth.find(1);
      c.first_box = main != nullptr ? main->box : cv::Rect2f();
    }
  }
  for (int i = 0; i < kRendered; ++i) c.frames.push_back(rendered[i]);
  for (int i = kRendered - 2; i > 0; --i) c.frames.push_back(rendered[i]);
  c.fps = gen.fps();
  return c;
}

// Pipeline::process per frame. auto_init: the pipeline finds the target itself; otherwise the
// track starts on the first ground-truth box (outside the timing).
void BM_LoopPipeline(benchmark::State& state, bool auto_init) {
  const Clip& c = clip(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  oc::Pipeline pipeline;
  double stamp = 0.0;
  const double dt = 1.0 / c.fps;
  if (!auto_init) pipeline.startTrack(c.frames[0], stamp, c.first_box);
  size_t i = 1, tracked = 0, frames = 0;
  for (auto _ : state) {
    stamp += dt;
    const std::vector<oc::Obstacle>& out = pipeline.process(c.frames[i], stamp);
    benchmark::DoNotOptimize(out.data());
    tracked += out.empty() ? 0 : 1;
    ++frames;
    if (++i == c.frames.size()) i = 0;
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["reported"] = frames > 0 ? static_cast<double>(tracked) / frames : 0.0;
}

// OpenCV's trackers on the same frames, from the same first box.
void BM_LoopOpenCv(benchmark::State& state, bool csrt) {
  const Clip& c = clip(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  cv::Ptr<cv::Tracker> tracker =
      csrt ? cv::Ptr<cv::Tracker>(cv::TrackerCSRT::create()) : cv::Ptr<cv::Tracker>(cv::TrackerKCF::create());
  tracker->init(c.frames[0], cv::Rect(c.first_box));
  size_t i = 1, ok = 0, frames = 0;
  cv::Rect box;
  for (auto _ : state) {
    ok += tracker->update(c.frames[i], box) ? 1 : 0;
    benchmark::DoNotOptimize(box);
    ++frames;
    if (++i == c.frames.size()) i = 0;
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["reported"] = frames > 0 ? static_cast<double>(ok) / frames : 0.0;
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Args({640, 480})->Args({1280, 720})->Unit(benchmark::kMillisecond)->MinTime(1.0);
}

}  // namespace

BENCHMARK_CAPTURE(BM_LoopPipeline, ours_auto, true)->Apply(sizes);
BENCHMARK_CAPTURE(BM_LoopPipeline, ours_gt, false)->Apply(sizes);
BENCHMARK_CAPTURE(BM_LoopOpenCv, KCF, false)->Apply(sizes);
BENCHMARK_CAPTURE(BM_LoopOpenCv, CSRT, true)->Apply(sizes);
