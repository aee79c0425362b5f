// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Long replay: generated scenes looped through core::Pipeline for OT_REPLAY_FRAMES
// frames (default 600 here; scripts/extra_tests.d/10-sanitizers.sh runs 10 000 under
// AddressSanitizer + LeakSanitizer, where a leak fails the program at exit). Each loop of the
// "bag" continues the stamps (the object jumps back: re-detection) except every third loop, where
// time goes backwards (reset); the parameters change every loop (single / several obstacles,
// detection interval) and one loop is grey instead of colour. Heap in use must not grow after
// the first loops: growth of more than 1 MiB between the end of the warm-up and the end fails.
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/scene/scene_generator.h"

// Present only under AddressSanitizer (its allocator replaces malloc; mallinfo2 then says nothing).
extern "C" std::size_t __sanitizer_get_current_allocated_bytes() __attribute__((weak));

namespace oc = obstacle_tracker::core;
namespace os = obstacle_tracker::scene;

namespace {

std::size_t heapInUse() {
  if (__sanitizer_get_current_allocated_bytes != nullptr) return __sanitizer_get_current_allocated_bytes();
  const struct mallinfo2 mi = mallinfo2();
  return mi.uordblks + mi.hblkhd;
}

int replayFrames() {
  const char* env = std::getenv("OT_REPLAY_FRAMES");
  const int n = env ? std::atoi(env) : 600;
  return n > 0 ? n : 600;
}

}  // namespace

TEST(RobustReplay, LoopedScenesThroughThePipelineDoNotGrowTheHeap) {
  cv::setNumThreads(1);  // OpenCV's worker threads keep per-thread buffers; one thread is steadier
  const cv::Size size(320, 240);
  const int per_scene = 120;
  // Pre-rendered frames (the generator's own buffers are freed before the replay starts).
  std::vector<std::vector<cv::Mat>> scenes;
  for (const char* name : {"demo", "multi", "out_of_view"}) {
    os::SceneGenerator gen = os::makeScenario(name, 11, per_scene, size);
    std::vector<cv::Mat> frames(static_cast<std::size_t>(gen.frameCount()));
    for (int i = 0; i < gen.frameCount(); ++i) gen.renderFrame(i, frames[static_cast<std::size_t>(i)]);
    scenes.push_back(std::move(frames));
  }
  std::vector<cv::Mat> grey(scenes[0].size());
  for (std::size_t i = 0; i < grey.size(); ++i) cv::cvtColor(scenes[0][i], grey[i], cv::COLOR_BGR2GRAY);

  const int total = replayFrames();
  const int loop_frames = per_scene;
  const int loops = (total + loop_frames - 1) / loop_frames;
  const int warmup_loops = std::min(std::max(2, loops / 3), loops - 1);
  oc::Pipeline pipeline;
  double stamp = 1000.0;
  int frames = 0, with_obstacles = 0, loops_done = 0;
  std::size_t heap_after_warmup = 0, heap_max_after_warmup = 0;
  for (int loop = 0; loop < loops && frames < total; ++loop) {
    oc::Params p;
    p.max_obstacles = (loop % 3 == 1) ? 4 : 1;
    p.detection_interval = (loop % 4 == 3) ? 3 : 1;
    pipeline.setParams(p);
    if (loop > 0 && loop % 3 == 0) stamp -= 30.0;  // the bag loops: time goes backwards
    const int scene = loop % 3;
    const bool use_grey = loop % 5 == 4;
    const std::vector<cv::Mat>& seq = use_grey ? grey : scenes[static_cast<std::size_t>(scene)];
    for (std::size_t i = 0; i < seq.size() && frames < total; ++i, ++frames) {
      stamp += 1.0 / 30.0;
      const std::vector<oc::Obstacle>& out = pipeline.process(seq[i], stamp);
      if (!out.empty()) ++with_obstacles;
      for (const oc::Obstacle& o : out) {
        ASSERT_TRUE(std::isfinite(o.box.x) && std::isfinite(o.box.width)) << "frame " << frames;
        ASSERT_TRUE(o.confidence >= 0.0f && o.confidence <= 1.0f) << "frame " << frames;
      }
    }
    ++loops_done;
    if (loop + 1 == warmup_loops) heap_after_warmup = heapInUse();
    if (loop + 1 > warmup_loops) heap_max_after_warmup = std::max(heap_max_after_warmup, heapInUse());
  }
  const std::size_t heap_end = heapInUse();
  std::printf("replay: %d frames in %d loops, %d with obstacles; heap in use %.2f MiB after warm-up "
              "(%d loops), %.2f MiB at the end, max %.2f MiB (%s)\n",
              frames, loops_done, with_obstacles, heap_after_warmup / 1048576.0, warmup_loops,
              heap_end / 1048576.0, heap_max_after_warmup / 1048576.0,
              __sanitizer_get_current_allocated_bytes ? "ASan allocator" : "mallinfo2");
  EXPECT_EQ(frames, total);
  EXPECT_GT(with_obstacles, frames / 4) << "the replay hardly tracked anything: it exercised little";
  EXPECT_LT(static_cast<double>(heap_end) - static_cast<double>(heap_after_warmup), 1048576.0)
      << "heap grew by " << (static_cast<double>(heap_end) - heap_after_warmup) / 1048576.0 << " MiB";
}
