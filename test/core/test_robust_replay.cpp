// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Long replay: generated scenes looped through core::Pipeline for OT_REPLAY_FRAMES
// frames (default two schedule periods, 1440, here; scripts/extra_tests.d/10-sanitizers.sh runs
// 10 000 under AddressSanitizer + LeakSanitizer, where a leak fails the program at exit). The loops
// of the "bag" follow a schedule of kPeriod loops: each scene, one or several obstacles, detection
// every frame or every third, one grey loop; stamps continue across loops (the object jumps back:
// re-detection) except every third loop, where time goes backwards (reset). Heap in use must not
// grow: its highest level over the last whole period may exceed that over the first by at most
// 1 MiB. Both periods visit the same states (buffers sized by the scene, the number of tracks,
// grey or colour), so the comparison does not depend on where in the schedule the replay stops.
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

constexpr int kFramesPerLoop = 120;
constexpr int kPeriod = 6;  // loops

int replayFrames() {
  const char* env = std::getenv("OT_REPLAY_FRAMES");
  const int n = env ? std::atoi(env) : 2 * kPeriod * kFramesPerLoop;
  return n > 0 ? n : 2 * kPeriod * kFramesPerLoop;
}

// One loop of the schedule: which scene, the parameters, grey or colour, and whether the bag's
// time jumps back before it.
struct LoopPlan {
  int scene;  // 0 demo, 1 multi, 2 out_of_view
  int max_obstacles;
  int detection_interval;
  bool grey;        // the demo scene as grey frames
  bool time_back;  // stamps go 30 s back (the bag loops: reset); not before the very first loop
};

LoopPlan planOf(int loop) {
  static const LoopPlan plans[kPeriod] = {
      {0, 1, 1, false, true}, {1, 4, 1, false, false}, {2, 1, 3, false, false},
      {0, 1, 1, true, true},  {1, 4, 3, false, false}, {2, 4, 1, false, false},
  };
  return plans[loop % kPeriod];
}

}  // namespace

TEST(RobustReplay, LoopedScenesThroughThePipelineDoNotGrowTheHeap) {
  cv::setNumThreads(1);  // OpenCV's worker threads keep per-thread buffers; one thread is steadier
  const cv::Size size(320, 240);
  // Pre-rendered frames (the generator's own buffers are freed before the replay starts).
  std::vector<std::vector<cv::Mat>> scenes;
  for (const char* name : {"demo", "multi", "out_of_view"}) {
    os::SceneGenerator gen = os::makeScenario(name, 11, kFramesPerLoop, size);
    std::vector<cv::Mat> frames(static_cast<std::size_t>(gen.frameCount()));
    for (int i = 0; i < gen.frameCount(); ++i) gen.renderFrame(i, frames[static_cast<std::size_t>(i)]);
    scenes.push_back(std::move(frames));
  }
  std::vector<cv::Mat> grey(scenes[0].size());
  for (std::size_t i = 0; i < grey.size(); ++i) cv::cvtColor(scenes[0][i], grey[i], cv::COLOR_BGR2GRAY);

  const int total = replayFrames();
  const int loops = (total + kFramesPerLoop - 1) / kFramesPerLoop;  // the last may be partial
  const int periods = (total / kFramesPerLoop) / kPeriod;  // of whole loops only
  ASSERT_GE(periods, 2) << "OT_REPLAY_FRAMES=" << total << " holds fewer than two schedule periods ("
                        << 2 * kPeriod * kFramesPerLoop << " frames): nothing to compare";
  oc::Pipeline pipeline;
  double stamp = 1000.0;
  int frames = 0, with_obstacles = 0;
  std::size_t heap_first_period = 0, heap_last_period = 0;
  for (int loop = 0; loop < loops && frames < total; ++loop) {
    const LoopPlan plan = planOf(loop);
    oc::Params p;
    p.max_obstacles = plan.max_obstacles;
    p.detection_interval = plan.detection_interval;
    pipeline.setParams(p);
    if (loop > 0 && plan.time_back) stamp -= 30.0;
    const std::vector<cv::Mat>& seq = plan.grey ? grey : scenes[static_cast<std::size_t>(plan.scene)];
    for (std::size_t i = 0; i < seq.size() && frames < total; ++i, ++frames) {
      stamp += 1.0 / 30.0;
      const std::vector<oc::Obstacle>& out = pipeline.process(seq[i], stamp);
      if (!out.empty()) ++with_obstacles;
      for (const oc::Obstacle& o : out) {
        ASSERT_TRUE(std::isfinite(o.box.x) && std::isfinite(o.box.width)) << "frame " << frames;
        ASSERT_TRUE(o.confidence >= 0.0f && o.confidence <= 1.0f) << "frame " << frames;
      }
    }
    const int period = loop / kPeriod;
    if (period == 0) heap_first_period = std::max(heap_first_period, heapInUse());
    if (period == periods - 1) heap_last_period = std::max(heap_last_period, heapInUse());
  }
  const double growth = static_cast<double>(heap_last_period) - static_cast<double>(heap_first_period);
  std::printf("replay: %d frames in %d loops (%d periods of %d), %d with obstacles; highest heap in use "
              "%.2f MiB over the first period, %.2f MiB over the last (%s)\n",
              frames, loops, periods, kPeriod, with_obstacles, heap_first_period / 1048576.0,
              heap_last_period / 1048576.0,
              __sanitizer_get_current_allocated_bytes ? "ASan allocator" : "mallinfo2");
  EXPECT_EQ(frames, total);
  EXPECT_GT(with_obstacles, frames / 4) << "the replay hardly tracked anything: it exercised little";
  EXPECT_LT(growth, 1048576.0) << "heap grew by " << growth / 1048576.0 << " MiB";
}
