// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// A generated flight scene rendered into memory once (frames and the main obstacle's box per
// frame), for tests that run the pipeline over the same frames more than once.
#pragma once

#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/scene/scene_generator.h"

namespace obstacle_tracker {
namespace test {

struct RenderedClip {
  std::vector<cv::Mat> frames;
  std::vector<cv::Rect2f> truth;  // the main obstacle (id 1); empty where it is not visible
  double fps = 30.0;
};

inline RenderedClip renderClip(const std::string& scenario, unsigned long long seed, int frames, cv::Size size,
                               bool grey) {
  scene::SceneGenerator gen = scene::makeScenario(scenario, seed, frames, size);
  RenderedClip c;
  c.fps = gen.fps();
  for (int i = 0; i < gen.frameCount(); ++i) {
    cv::Mat frame;
    scene::FrameTruth truth;
    gen.renderFrame(i, frame, &truth);
    if (grey && frame.channels() == 3) cv::cvtColor(frame, frame, cv::COLOR_BGR2GRAY);
    const scene::ObstacleTruth* main = truth.find(1);
    c.truth.push_back(main != nullptr && main->visible ? main->box : cv::Rect2f());
    c.frames.push_back(frame);
  }
  return c;
}

}  // namespace test
}  // namespace obstacle_tracker
