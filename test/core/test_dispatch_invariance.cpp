// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The same frames give the same outputs on every CPU: OpenCV chooses SSE, AVX2 or AVX-512 kernels
// at run time, and cv::setUseOptimized(false) makes it use the baseline ones. The pipeline's
// outputs (boxes, scores, states, looming) must be bit-identical either way, auto-started and
// started from a box, colour and grey; the scenes include re-detection and the scale search.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace oc = obstacle_tracker::core;
namespace os = obstacle_tracker::scene;

namespace {

struct Clip {
  std::vector<cv::Mat> frames;
  cv::Rect2f first_box;
  double fps = 30.0;
};

// Rendered once, before either run: the scene generator's own OpenCV calls are not under test.
Clip render(const std::string& scenario, int frames, bool grey) {
  os::SceneGenerator gen = os::makeScenario(scenario, 3, frames, cv::Size(480, 360));
  Clip c;
  c.fps = gen.fps();
  for (int i = 0; i < frames; ++i) {
    cv::Mat frame;
    os::FrameTruth truth;
    gen.renderFrame(i, frame, &truth);
    if (grey) cv::cvtColor(frame, frame, cv::COLOR_BGR2GRAY);
    if (i == 0 && truth.find(1) != nullptr) c.first_box = truth.find(1)->box;
    c.frames.push_back(frame);
  }
  return c;
}

std::vector<std::string> track(const Clip& c, bool from_box) {
  oc::Pipeline pipeline;
  std::vector<std::string> log;
  for (std::size_t i = 0; i < c.frames.size(); ++i) {
    const double stamp = static_cast<double>(i) / c.fps;
    const bool start = from_box && i == 0 && c.first_box.area() > 0;
    const auto& out = start ? pipeline.startTrack(c.frames[i], stamp, c.first_box) : pipeline.process(c.frames[i], stamp);
    std::string line = std::to_string(i) + ":";
    char buf[256];
    for (const oc::Obstacle& o : out) {
      std::snprintf(buf, sizeof(buf), " [%d %a %a %a %a %a %a %a %d %a]", o.id, o.box.x, o.box.y, o.box.width,
                    o.box.height, o.confidence, o.peak, o.psr, static_cast<int>(o.state), o.expansion_rate);
      line += buf;
    }
    log.push_back(line);
  }
  return log;
}

void expectDispatchInvariant(const std::string& scenario, int frames, bool from_box, bool grey) {
  cv::setUseOptimized(true);
  const Clip clip = render(scenario, frames, grey);
  const std::vector<std::string> optimised = track(clip, from_box);
  cv::setUseOptimized(false);
  const std::vector<std::string> baseline = track(clip, from_box);
  cv::setUseOptimized(true);
  ASSERT_EQ(optimised.size(), baseline.size());
  int with_box = 0;
  for (std::size_t i = 0; i < optimised.size(); ++i) {
    ASSERT_EQ(optimised[i], baseline[i]) << scenario << ": first difference at frame " << i;
    with_box += optimised[i].find('[') != std::string::npos ? 1 : 0;
  }
  EXPECT_GT(with_box, frames / 3) << scenario << ": too few frames with a track to prove much";
}

}  // namespace

TEST(DispatchInvariance, CrossingWithJerksFromTheBox) { expectDispatchInvariant("crossing+jerk", 150, true, false); }
TEST(DispatchInvariance, CloudOcclusionFromTheBoxGrey) { expectDispatchInvariant("crossing+occlusion", 120, true, true); }
TEST(DispatchInvariance, BirdAutoStarted) { expectDispatchInvariant("bird", 150, false, false); }
TEST(DispatchInvariance, ApproachAutoStartedGrey) { expectDispatchInvariant("approach", 120, false, true); }
