// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// memory_probe's measured run: a core::Pipeline with max_obstacles = 3 starts tracks from the
// ground-truth boxes of frame 0 and processes the other frames, its memory read along the way.
#pragma once

#include <map>
#include <stdexcept>
#include <vector>

#include "memory_probe/process_memory.h"
#include "memory_probe/scene_frames.h"

namespace obstacle_tracker {
namespace memory_probe_tool {

// What was measured. Heap figures are bytes relative to heap_before, the heap in use just
// before the Pipeline was constructed; "after warm-up" is frame `warmup` (frame 1 when 0).
struct PipelineMemory {
  int started = 0;                  // tracks the pipeline reported after the startTrack calls
  long long heap_before = 0;
  long long heap_warm = 0, heap_end = 0;
  long long heap_peak = 0;          // largest reading after a frame
  long long heap_after = 0;         // after the Pipeline's destructor
  long long exact_peak = 0;         // peak of the wrappers' live bytes (heap_peak when not counted)
  ProcStatus status_before, status_warm, status_end;
  // Frames after the warm-up:
  int counted_frames = 0;
  std::map<int, int> alive_frames;  // tracks alive (tracking or re-detecting) -> frames
  int redetecting_frames = 0;       // frames with a track re-detecting
  long calls_total = 0, calls_max = 0;
  int frames_with_calls = 0;
  std::vector<int> alloc_frames;    // the first few frames that allocated
};

// The pipeline could not start the tracks asked for; main reports it and exits with 1.
struct ProbeFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Starts `start_count` tracks (1..3) from scene.start_boxes (which holds three) on frame 0 and
// processes the other frames; allocations are counted from frame warmup + 1 on. Throws
// ProbeFailure when startTrack throws or reports another number of tracks.
PipelineMemory measurePipeline(const RenderedScene& scene, int warmup, int start_count);

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
