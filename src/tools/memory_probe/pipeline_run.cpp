// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "memory_probe/pipeline_run.h"

#include <algorithm>
#include <cstddef>
#include <exception>
#include <string>

#include "memory_probe/allocation_counter.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/pipeline.h"

namespace core = obstacle_tracker::core;

namespace obstacle_tracker {
namespace memory_probe_tool {
namespace {

void startTracks(core::Pipeline& pipeline, const RenderedScene& scene, int start_count,
                 PipelineMemory* m) {
  try {
    for (int k = 0; k < start_count; ++k) {
      const auto& out =
          pipeline.startTrack(scene.frames[0], 0.0, scene.start_boxes[static_cast<std::size_t>(k)]);
      m->started = static_cast<int>(out.size());
    }
  } catch (const std::exception& e) {
    throw ProbeFailure(std::string("startTrack failed: ") + e.what());
  }
  if (m->started != start_count) {
    throw ProbeFailure("after " + std::to_string(start_count) +
                       " startTrack calls the pipeline reports " + std::to_string(m->started) +
                       " tracks");
  }
}

// Frame i: processed, its allocation calls counted when past the warm-up, its tracks and the heap
// noted.
void processFrame(core::Pipeline& pipeline, const RenderedScene& scene, std::size_t i, int warmup,
                  PipelineMemory* m) {
  const bool count = static_cast<int>(i) > warmup;
  // Only the pipeline's own call is counted: nothing else runs while counting is on.
  const long before = allocationCalls();
  setCountingAllocations(count);
  const auto& out = pipeline.process(scene.frames[i], static_cast<double>(i) / scene.fps);
  setCountingAllocations(false);
  const long calls = allocationCalls() - before;
  int alive = 0;
  bool redetecting = false;
  for (const auto& o : out) {
    alive += o.state != core::TrackState::kLost ? 1 : 0;
    redetecting = redetecting || o.state == core::TrackState::kRedetecting;
  }
  m->heap_peak = std::max(m->heap_peak, heapInUse() - m->heap_before);
  if (count) {
    ++m->counted_frames;
    ++m->alive_frames[alive];
    m->redetecting_frames += redetecting ? 1 : 0;
    m->calls_total += calls;
    m->calls_max = std::max(m->calls_max, calls);
    if (calls > 0) {
      ++m->frames_with_calls;
      if (m->alloc_frames.size() < 10) m->alloc_frames.push_back(static_cast<int>(i));
    }
  }
  if (static_cast<int>(i) == warmup || (warmup == 0 && i == 1)) {
    m->heap_warm = heapInUse() - m->heap_before;
    m->status_warm = readProcStatus();
  }
}

}  // namespace

PipelineMemory measurePipeline(const RenderedScene& scene, int warmup, int start_count) {
  PipelineMemory m;
  m.status_before = readProcStatus();
  m.heap_before = heapInUse();
  const long long live_before = liveBytes();
  resetPeakLiveBytes(live_before);
  {
    core::Params params;
    params.max_obstacles = 3;
    core::Pipeline pipeline(params);
    // As the nodelet does before its first frame: one run over a synthetic clip, so that buffers,
    // OpenCV's tables and threads exist before the first real frame.
    pipeline.prepare(scene.frames.front().size(), scene.frames.front().type());
    startTracks(pipeline, scene, start_count, &m);
    m.heap_peak = std::max(m.heap_peak, heapInUse() - m.heap_before);
    for (std::size_t i = 1; i < scene.frames.size(); ++i) processFrame(pipeline, scene, i, warmup, &m);
    m.heap_end = heapInUse() - m.heap_before;
  }
  m.status_end = readProcStatus();
  m.heap_after = heapInUse() - m.heap_before;
  m.exact_peak = kCountsAllocations ? peakLiveBytes() - live_before : m.heap_peak;
  return m;
}

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
