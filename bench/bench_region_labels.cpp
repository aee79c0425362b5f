// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The saliency's region step (RegionExtractor::extract: Otsu, our union-find 8-connected
// labelling, statistics, ranking) beside its OpenCV peer on the same map (cv::threshold Otsu +
// cv::connectedComponentsWithStats, which allocates its label table on every call). Maps: the
// MBD saliency map of a generated 1280x720 scene at the detector's working size (300x169), and a
// noisy 300x169 map with many small components (the labelling's worst case).
//   cmake --build BUILD --target bench_core && BUILD/bench_core --benchmark_filter=RegionStep
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/mbd_saliency.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/region_extractor.h"
#include "obstacle_tracker/core/salient_region.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace oc = obstacle_tracker::core;
namespace os = obstacle_tracker::scene;

namespace {

cv::Mat makeMap(int which) {
  if (which == 0) {
    os::SceneGenerator gen = os::makeScenario("multi", 1, 60, cv::Size(1280, 720));
    cv::Mat frame, small, map;
    gen.renderFrame(30, frame);
    cv::resize(frame, small, cv::Size(300, 169), 0, 0, cv::INTER_AREA);
    map.create(small.size(), CV_8UC1);
    oc::MbdSaliency mbd;
    mbd.compute(small, oc::Params(), map);
    return map;
  }
  cv::Mat map(169, 300, CV_8UC1);
  cv::RNG rng(3);
  rng.fill(map, cv::RNG::UNIFORM, 0, 256);
  return map;
}

const char* const kNames[2] = {"MBD map of multi 300x169", "noise 300x169"};

void BM_RegionStep_Ours(benchmark::State& state) {
  const cv::Mat map = makeMap(static_cast<int>(state.range(0)));
  oc::RegionExtractor ex;
  oc::Params p;
  oc::RegionExtractor::Geometry g;
  g.frame_area = 1280.0 * 720.0;
  std::vector<oc::SalientRegion> regions;
  for (auto _ : state) {
    ex.extract(map, g, p, regions);
    benchmark::DoNotOptimize(regions.data());
  }
  state.SetLabel(kNames[state.range(0)]);
}
BENCHMARK(BM_RegionStep_Ours)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);

void BM_RegionStep_OpenCvStats(benchmark::State& state) {
  const cv::Mat map = makeMap(static_cast<int>(state.range(0)));
  cv::Mat binary, labels, stats, centroids;
  for (auto _ : state) {
    cv::threshold(map, binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    benchmark::DoNotOptimize(cv::connectedComponentsWithStats(binary, labels, stats, centroids, 8, CV_32S));
  }
  state.SetLabel(kNames[state.range(0)]);
}
BENCHMARK(BM_RegionStep_OpenCvStats)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);

}  // namespace
