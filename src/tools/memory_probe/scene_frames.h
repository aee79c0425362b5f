// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The generated scene memory_probe feeds the pipeline, rendered completely before anything is
// measured.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/scene/scene_generator.h"

namespace obstacle_tracker {
namespace memory_probe_tool {

struct RenderedScene {
  std::vector<cv::Mat> frames;
  std::vector<cv::Rect2f> start_boxes;  // the visible target boxes of frame 0 (no distractors)
  double fps = 30.0;
  long long frame_bytes = 0;            // pixel bytes of all frames
};

// Renders every frame of the scene; the generator is gone and its freed memory returned to the
// system (malloc_trim) when this returns, so that it does not count. Throws what the scene
// generator throws.
RenderedScene renderScene(const scene::ScenarioConfig& config);

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
