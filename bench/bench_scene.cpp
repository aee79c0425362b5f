// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Scene generator speed (target: every scenario >= 200 frames/s at 640x480). Items/s = frames
// per second of renderFrame (construction, i.e. the panorama, is outside the timed loop). Peer:
// decoding the same frame from JPEG, which is what reading a stored sequence costs at least.
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>

#include "obstacle_tracker/scene/scene_generator.h"

namespace os = obstacle_tracker::scene;

namespace {

const std::vector<std::string>& benchScenarios() {
  static const std::vector<std::string> names = {
      "demo", "approach", "crossing", "rotation", "out_of_view", "multi", "bird", "tiny",
      "approach+jitter", "approach+jerk", "crossing+blur", "approach+noise", "crossing+illumination",
      "crossing+occlusion", "crossing+flock", "tiny+overlay", "crossing+glare", "approach+clutter",
      "approach+large", "multi+jitter+noise+flock+overlay"};
  return names;
}

void BM_RenderScene(benchmark::State& state) {
  const std::string& name = benchScenarios()[static_cast<std::size_t>(state.range(0))];
  const bool mono16 = state.range(1) != 0;
  os::SceneGenerator gen = os::makeScenario(name, 7, 0, cv::Size(640, 480), mono16);
  cv::Mat frame;
  int i = 0;
  for (auto _ : state) {
    gen.renderFrame(i, frame);
    benchmark::DoNotOptimize(frame.data);
    i = (i + 1) % gen.frameCount();
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(name + (mono16 ? " mono16" : " bgr8"));
}

void sceneArgs(benchmark::internal::Benchmark* b) {
  for (int k = 0; k < static_cast<int>(benchScenarios().size()); ++k) b->Args({k, 0});
  for (int k : {0, 3, 7}) b->Args({k, 1});
}
BENCHMARK(BM_RenderScene)->Apply(sceneArgs)->Unit(benchmark::kMillisecond)->MinTime(0.3);

void BM_DecodeJpegPeer(benchmark::State& state) {
  os::SceneGenerator gen = os::makeScenario("demo", 7, 0, cv::Size(640, 480));
  cv::Mat frame;
  gen.renderFrame(100, frame);
  std::vector<uchar> jpg;
  cv::imencode(".jpg", frame, jpg, {cv::IMWRITE_JPEG_QUALITY, 95});
  cv::Mat out;
  for (auto _ : state) {
    out = cv::imdecode(jpg, cv::IMREAD_COLOR);
    benchmark::DoNotOptimize(out.data);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("peer: JPEG decode 640x480");
}
BENCHMARK(BM_DecodeJpegPeer)->Unit(benchmark::kMillisecond)->MinTime(0.3);

void BM_SceneConstruction(benchmark::State& state) {
  for (auto _ : state) {
    os::SceneGenerator gen = os::makeScenario("demo", 7, 0, cv::Size(640, 480));
    benchmark::DoNotOptimize(&gen);
  }
  state.SetLabel("panorama + tables, demo 640x480");
}
BENCHMARK(BM_SceneConstruction)->Unit(benchmark::kMillisecond)->MinTime(0.3);

}  // namespace
