// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Per-frame update cost of our KCF (template 96 and 64) beside OpenCV's TrackerKCF and
// TrackerCSRT (opencv_contrib), initialised from the same box and updated on the same frames,
// in the same run. Frames: 640x480 BGR and 640x512 grey (the infrared clips' size) with a
// textured 40x30 target moving on a circle over a textured background (a cyclic sequence, so
// the benchmark can loop over it without a jump).
//   bench_core --benchmark_filter='KcfUpdate|OpenCvUpdate'
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/tracking.hpp>

#include "obstacle_tracker/core/kcf.h"

namespace oc = obstacle_tracker::core;

namespace {

constexpr int kFrames = 64;

struct Clip {
  std::vector<cv::Mat> frames;
  std::vector<cv::Mat> frames_bgr;  // the same frames as BGR (OpenCV's KCF needs 3 channels)
  cv::Rect2f first_box;
};

cv::Mat texture(cv::Size size, int seed, double blur) {
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), blur);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat out;
  noise.convertTo(out, CV_8U);
  return out;
}

const Clip& clip(bool colour) {
  static Clip clips[2];
  Clip& c = clips[colour ? 1 : 0];
  if (!c.frames.empty()) return c;
  const cv::Size fs = colour ? cv::Size(640, 480) : cv::Size(640, 512);
  const cv::Mat bg = texture(fs, 1, 3.0);
  const cv::Mat obj = texture(cv::Size(40, 30), 2, 1.5);
  for (int i = 0; i < kFrames; ++i) {
    const double a = 2.0 * M_PI * i / kFrames;
    const int x = static_cast<int>(std::lround(300 + 60 * std::cos(a)));
    const int y = static_cast<int>(std::lround(240 + 60 * std::sin(a)));
    cv::Mat f = bg.clone();
    obj.copyTo(f(cv::Rect(x, y, obj.cols, obj.rows)));
    if (colour) {
      cv::Mat ch[3] = {f, 255 - f, f / 2 + 64};
      cv::merge(ch, 3, f);
    }
    c.frames.push_back(f);
    if (colour) {
      c.frames_bgr.push_back(f);
    } else {
      cv::Mat bgr;
      cv::cvtColor(f, bgr, cv::COLOR_GRAY2BGR);
      c.frames_bgr.push_back(bgr);
    }
    if (i == 0) c.first_box = cv::Rect2f(static_cast<float>(x), static_cast<float>(y), 40, 30);
  }
  return c;
}

void setLabel(benchmark::State& state, bool colour) {
  state.SetLabel(colour ? "640x480 BGR" : "640x512 grey");
}

void BM_KcfUpdate(benchmark::State& state) {
  const bool colour = state.range(0) != 0;
  const Clip& c = clip(colour);
  oc::Params p;
  p.kcf_template_size = static_cast<int>(state.range(1));
  p.scale_count = static_cast<int>(state.range(2));
  oc::KcfTracker kcf(p);
  kcf.init(c.frames[0], c.first_box);
  int i = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(kcf.update(c.frames[i]));
    i = (i + 1) % kFrames;
  }
  setLabel(state, colour);
}

// OpenCV's trackers get the grey clip as BGR (TrackerKCF's colour-names features need 3
// channels); the conversion is done before timing.
template <class T>
void BM_OpenCvUpdate(benchmark::State& state) {
  const bool colour = state.range(0) != 0;
  const Clip& c = clip(colour);
  cv::Ptr<cv::Tracker> tracker = T::create();
  const cv::Rect2f& b = c.first_box;
  tracker->init(c.frames_bgr[0],
                cv::Rect(cvRound(b.x), cvRound(b.y), cvRound(b.width), cvRound(b.height)));
  cv::Rect box;
  int i = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tracker->update(c.frames_bgr[i], box));
    i = (i + 1) % kFrames;
  }
  setLabel(state, colour);
}

// CPU time of the whole process (OpenCV's trackers use worker threads), so the comparison holds
// on a loaded machine; wall time is reported too. Args: colour, template size, scale count.
BENCHMARK(BM_KcfUpdate)
    ->ArgNames({"colour", "template", "scales"})
    ->Args({1, 96, 3})
    ->Args({1, 64, 3})
    ->Args({0, 96, 3})
    ->Args({0, 64, 3})
    ->Args({0, 96, 1})
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_OpenCvUpdate, cv::TrackerKCF)
    ->ArgNames({"colour"})
    ->Arg(1)
    ->Arg(0)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_OpenCvUpdate, cv::TrackerCSRT)
    ->ArgNames({"colour"})
    ->Arg(1)
    ->Arg(0)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
