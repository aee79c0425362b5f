// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// memory_probe [--frames N] [--size WxH] [--scenario NAME] [--seed N] [--warmup N]
//              [--start K] [--budget-mib M]
//
// Measures the memory of core::Pipeline with three tracks (the promise: "no allocation per frame once
// a track exists; the core's resident memory with three tracks on 1280x720 frames under 30 MiB").
// A generated scene (default "multi": three obstacles whose paths cross) is rendered into memory
// first and the generator destroyed, so that its memory is not counted; then a Pipeline with
// max_obstacles = 3 is prepared for the frame size (as the nodelet does), starts one track per
// ground-truth box of the first frame (startTrack) and processes the other frames. Reported:
//   heap   glibc mallinfo2() in-use bytes (arena + mmapped) relative to just before the Pipeline
//          is constructed: after warm-up, at the end, and the largest value seen after a frame;
//          plus the exact peak of the live bytes counted by this program's allocator wrappers
//          (which also sees peaks inside a frame, and prepare()'s).
//   RSS    VmRSS / VmHWM from /proc/self/status before the Pipeline, after warm-up and at the end.
//   calls  malloc/calloc/realloc/posix_memalign/aligned_alloc/memalign calls per frame after the
//          warm-up (wrappers in this program forward to the next definition, dlsym(RTLD_NEXT), so
//          heaptrack's own interposition still sees everything when run under heaptrack).
//   tracks how many tracks were alive (tracking or re-detecting) per frame.
// Exit codes: 0 all targets met, 1 a target missed (tracks not started / mostly not 3, heap over
// the budget, allocations per frame after warm-up), 2 usage or scene error.
// Under a sanitizer (which interposes malloc itself) the counting is skipped with a message.
//
// This file reads the command line and runs the steps; the parts are in src/tools/memory_probe/.
#include <exception>
#include <iostream>

#include "memory_probe/options.h"
#include "memory_probe/pipeline_run.h"
#include "memory_probe/report.h"
#include "memory_probe/scene_frames.h"

namespace mp = obstacle_tracker::memory_probe_tool;

int main(int argc, char** argv) {
  const mp::ParsedCommandLine parsed = mp::parseProbeOptions(argc, argv);
  if (parsed.exit_code) return *parsed.exit_code;
  const mp::ProbeOptions& options = parsed.options;

  // 1. The scene, rendered completely before anything is measured.
  mp::RenderedScene scene;
  try {
    scene = mp::renderScene(options.scene);
  } catch (const std::exception& e) {
    std::cerr << "memory_probe: scene " << options.scene.name << ": " << e.what() << "\n";
    return 2;
  }
  mp::printScene(options.scene, scene);
  if (scene.start_boxes.size() != 3) {
    std::cerr << "memory_probe: the first frame of " << options.scene.name << " has "
              << scene.start_boxes.size()
              << " visible target boxes; three are needed (try --scenario multi)\n";
    return 1;
  }

  // 2. The Pipeline's run, measured from just before it exists.
  mp::PipelineMemory measured;
  try {
    measured = mp::measurePipeline(scene, options.warmup, options.start_count);
  } catch (const mp::ProbeFailure& e) {
    std::cerr << "memory_probe: " << e.what() << "\n";
    return 1;
  }

  // 3. Summary.
  mp::printSummary(measured, scene, options.warmup);
  return mp::checkTargets(measured, options.budget_mib) ? 0 : 1;
}
