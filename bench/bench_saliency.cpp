// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Saliency detection speed beside OpenCV's spectral-residual saliency (Hou & Zhang, CVPR 2007;
// opencv_contrib saliency::StaticSaliencySpectralResidual) on the same generated frame, followed
// by the same Otsu / regions step. Whole frame: 640x480 and 1280x720 colour, 640x512 mono.
// Windowed re-detection around a 20 px and an 80 px box (search_window_scale x the box).
//   cmake --build BUILD --target bench_core && BUILD/bench_core --benchmark_filter=Saliency
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/saliency.hpp>

#include "obstacle_tracker/core/region_extractor.h"
#include "obstacle_tracker/core/saliency.h"
#include "obstacle_tracker/core/salient_region.h"

namespace oc = obstacle_tracker::core;

namespace {

// Sky gradient, blurred-noise clouds, a textured ground band and a dark 30x14 px "aircraft".
cv::Mat makeFrame(cv::Size size, bool colour) {
  cv::RNG rng(1234);
  cv::Mat f(size, CV_32FC3);
  for (int r = 0; r < size.height; ++r)
    f.row(r).setTo(cv::Scalar(200 - 60.0 * r / size.height, 170 - 40.0 * r / size.height, 140));
  cv::Mat noise(size.height / 8, size.width / 8, CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 12.0);
  cv::resize(noise, noise, size, 0, 0, cv::INTER_CUBIC);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 5.0);
  cv::Mat n3;
  cv::merge(std::vector<cv::Mat>{noise, noise, noise}, n3);
  f += n3;
  const int g = size.height * 3 / 4;
  cv::Mat tex(size.height - g, size.width, CV_32FC3);
  rng.fill(tex, cv::RNG::NORMAL, 70.0, 15.0);
  tex.copyTo(f.rowRange(g, size.height));
  cv::ellipse(f, cv::Point(size.width * 3 / 5, size.height / 3), cv::Size(15, 7), 0, 0, 360,
              cv::Scalar(40, 40, 50), cv::FILLED);
  cv::Mat u8;
  f.convertTo(u8, CV_8U);
  if (!colour) cv::cvtColor(u8, u8, cv::COLOR_BGR2GRAY);
  return u8;
}

cv::Size sizeOf(int index) {
  static const cv::Size sizes[3] = {cv::Size(640, 480), cv::Size(1280, 720), cv::Size(640, 512)};
  return sizes[index];
}
bool colourOf(int index) { return index != 2; }
const char* const kNames[3] = {"640x480 colour", "1280x720 colour", "640x512 mono"};

// Spectral residual + the same Otsu / regions step as ours.
struct SpectralResidualDetector {
  cv::Ptr<cv::saliency::StaticSaliencySpectralResidual> sr =
      cv::saliency::StaticSaliencySpectralResidual::create();
  cv::Mat map_f, map_u8;
  oc::RegionExtractor extractor;
  std::vector<oc::SalientRegion> regions;
  oc::Params params;
  void run(const cv::Mat& image, cv::Point offset, double frame_area) {
    sr->computeSaliency(image, map_f);
    double mx = 0.0;
    cv::minMaxLoc(map_f, nullptr, &mx);
    map_f.convertTo(map_u8, CV_8U, mx > 0 ? 255.0 / mx : 0.0);
    oc::RegionExtractor::Geometry g;
    g.offset = offset;
    g.frame_area = frame_area;
    extractor.extract(map_u8, g, params, regions);
  }
};

void BM_Saliency_WholeFrame_MBD(benchmark::State& state) {
  const cv::Mat frame = makeFrame(sizeOf(state.range(0)), colourOf(state.range(0)));
  oc::SaliencyDetector det;
  for (auto _ : state) benchmark::DoNotOptimize(det.detect(frame).data());
  state.SetLabel(kNames[state.range(0)]);
}
BENCHMARK(BM_Saliency_WholeFrame_MBD)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

void BM_Saliency_WholeFrame_SpectralResidual(benchmark::State& state) {
  const cv::Mat frame = makeFrame(sizeOf(state.range(0)), colourOf(state.range(0)));
  SpectralResidualDetector det;
  for (auto _ : state) {
    det.run(frame, cv::Point(0, 0), static_cast<double>(frame.total()));
    benchmark::DoNotOptimize(det.regions.data());
  }
  state.SetLabel(kNames[state.range(0)]);
}
BENCHMARK(BM_Saliency_WholeFrame_SpectralResidual)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// Windowed re-detection on the 640x480 colour frame, box of side range(0) on the object.
cv::Rect2f boxOf(const cv::Mat& frame, int side) {
  return cv::Rect2f(frame.cols * 3 / 5 - side / 2.0f, frame.rows / 3 - side / 2.0f, side, side);
}

void BM_Saliency_Window_MBD(benchmark::State& state) {
  const cv::Mat frame = makeFrame(sizeOf(0), true);
  oc::SaliencyDetector det;
  const cv::Rect2f box = boxOf(frame, static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(det.detectInWindow(frame, box).data());
  state.SetLabel("640x480 colour, box " + std::to_string(state.range(0)) + " px");
}
BENCHMARK(BM_Saliency_Window_MBD)->Arg(20)->Arg(80)->Unit(benchmark::kMicrosecond);

void BM_Saliency_Window_SpectralResidual(benchmark::State& state) {
  const cv::Mat frame = makeFrame(sizeOf(0), true);
  SpectralResidualDetector det;
  const cv::Rect win = oc::SaliencyDetector::searchWindow(frame.size(), boxOf(frame, static_cast<int>(state.range(0))),
                                                          det.params.search_window_scale);
  for (auto _ : state) {
    det.run(frame(win), win.tl(), static_cast<double>(frame.total()));
    benchmark::DoNotOptimize(det.regions.data());
  }
  state.SetLabel("640x480 colour, box " + std::to_string(state.range(0)) + " px");
}
BENCHMARK(BM_Saliency_Window_SpectralResidual)->Arg(20)->Arg(80)->Unit(benchmark::kMicrosecond);

}  // namespace
