// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Whole loop per frame: core::Pipeline::process on a generated flight scene (the README demo
// scenario: an aircraft approaching over clouds and a tree line, camera jitter, sensor noise) at
// 640x480 and 1280x720, started by itself (auto) or from the first ground-truth box (gt), beside
// OpenCV's TrackerKCF and TrackerCSRT updated on the same frames from the same box, in the same
// run. The clip is played forwards then backwards (a cycle without a jump), so a benchmark can
// loop over it for as long as it needs; frames are rendered once, before timing.
//   bench_core --benchmark_filter=Loop
// ColdStart: the first frame of a pipeline in a fresh process (auto mode), without and with
// Pipeline::prepare beforehand, against the 99th percentile of the frames after it (counters
// first_ms = median over the runs, p99_ms, first_over_p99; the benchmark's time is the first
// frame's).
//   bench_core --benchmark_filter=ColdStart
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
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

// Frame times (ms) of a new pipeline over the whole cycle, in a forked child: a new process, so
// that OpenCV's process-wide lazy set-up (tables, thread pool, allocator arenas) counts as it does
// for a freshly launched nodelet. Empty when the child failed.
std::vector<double> freshProcessFrameTimes(const Clip& c, bool prepared) {
  int fds[2];
  if (pipe(fds) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    oc::Pipeline pipeline;
    if (prepared) pipeline.prepare(c.frames[0].size(), c.frames[0].type());
    std::vector<double> ms(c.frames.size());
    for (size_t i = 0; i < c.frames.size(); ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(pipeline.process(c.frames[i], static_cast<double>(i) / c.fps).data());
      ms[i] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    const ssize_t bytes = static_cast<ssize_t>(ms.size() * sizeof(double));
    _exit(write(fds[1], ms.data(), static_cast<size_t>(bytes)) == bytes ? 0 : 1);
  }
  close(fds[1]);
  std::vector<double> ms(c.frames.size());
  size_t got = 0;
  char* out = reinterpret_cast<char*>(ms.data());
  ssize_t n = 0;
  while (got < ms.size() * sizeof(double) && (n = read(fds[0], out + got, ms.size() * sizeof(double) - got)) > 0) {
    got += static_cast<size_t>(n);
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got != ms.size() * sizeof(double) || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return {};
  return ms;
}

// The first frame of a freshly started pipeline process; the benchmark's time is that frame's.
void BM_ColdStart(benchmark::State& state, bool prepared) {
  const Clip& c = clip(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  std::vector<double> first_ms, later_ms;
  for (auto _ : state) {
    const std::vector<double> ms = freshProcessFrameTimes(c, prepared);
    if (ms.empty()) {
      state.SkipWithError("the benchmark's child process failed");
      return;
    }
    first_ms.push_back(ms[0]);
    later_ms.insert(later_ms.end(), ms.begin() + 1, ms.end());
    state.SetIterationTime(ms[0] * 1e-3);
  }
  std::sort(first_ms.begin(), first_ms.end());
  std::sort(later_ms.begin(), later_ms.end());
  const double first = first_ms[first_ms.size() / 2];
  const double p99 = later_ms[static_cast<size_t>(0.99 * static_cast<double>(later_ms.size() - 1))];
  state.counters["first_ms"] = first;
  state.counters["p99_ms"] = p99;
  state.counters["first_over_p99"] = first / p99;
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Args({640, 480})->Args({1280, 720})->Unit(benchmark::kMillisecond)->MinTime(1.0);
}

}  // namespace

BENCHMARK_CAPTURE(BM_LoopPipeline, ours_auto, true)->Apply(sizes);
BENCHMARK_CAPTURE(BM_LoopPipeline, ours_gt, false)->Apply(sizes);
BENCHMARK_CAPTURE(BM_LoopOpenCv, KCF, false)->Apply(sizes);
BENCHMARK_CAPTURE(BM_LoopOpenCv, CSRT, true)->Apply(sizes);
BENCHMARK_CAPTURE(BM_ColdStart, unprepared, false)->Args({640, 480})->Args({1280, 720})->UseManualTime()->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ColdStart, prepared, true)->Args({640, 480})->Args({1280, 720})->UseManualTime()->Iterations(10)->Unit(benchmark::kMillisecond);
