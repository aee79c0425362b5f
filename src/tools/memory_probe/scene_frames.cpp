// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "memory_probe/scene_frames.h"

#include <malloc.h>

#include <cstddef>

namespace obstacle_tracker {
namespace memory_probe_tool {

RenderedScene renderScene(const scene::ScenarioConfig& config) {
  RenderedScene rendered;
  {
    scene::SceneGenerator gen(config);
    rendered.fps = gen.fps();
    std::vector<cv::Mat>& frames = rendered.frames;
    frames.resize(static_cast<std::size_t>(gen.frameCount()));
    scene::FrameTruth truth0;
    for (int i = 0; i < gen.frameCount(); ++i) {
      gen.renderFrame(i, frames[static_cast<std::size_t>(i)], i == 0 ? &truth0 : nullptr);
      rendered.frame_bytes += static_cast<long long>(frames[static_cast<std::size_t>(i)].total() *
                                                     frames[static_cast<std::size_t>(i)].elemSize());
    }
    for (const auto& o : truth0.obstacles) {
      if (!o.distractor && o.visible && o.box.area() >= 1.0f) rendered.start_boxes.push_back(o.box);
    }
  }
  malloc_trim(0);  // the generator's freed memory back to the system before the baseline
  return rendered;
}

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
