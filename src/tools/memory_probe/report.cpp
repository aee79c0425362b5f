// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "memory_probe/report.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "memory_probe/allocation_counter.h"

namespace obstacle_tracker {
namespace memory_probe_tool {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

std::string kibAsMib(long long kib) { return kib < 0 ? std::string("n/a") : mib(kib * 1024); }

int framesWithThreeTracks(const PipelineMemory& m) {
  const auto three = m.alive_frames.find(3);
  return three != m.alive_frames.end() ? three->second : 0;
}

void printHeap(const PipelineMemory& m, const RenderedScene& scene) {
  std::cout << "heap (mallinfo2 in use, relative to just before the Pipeline):\n"
            << "  after warm-up          " << mib(m.heap_warm) << "\n"
            << "  at the end             " << mib(m.heap_end) << "\n"
            << "  peak after a frame     " << mib(m.heap_peak) << "\n"
            << "  after the destructor   " << mib(m.heap_after) << "\n";
  if (kCountsAllocations) {
    std::cout << "  peak inside frames     " << mib(m.exact_peak) << " (live bytes counted by the allocator wrappers)\n";
  }
  std::cout << "  frames (not the core)  " << mib(scene.frame_bytes) << " of pixels, heap in use before the Pipeline "
            << mib(m.heap_before) << "\n";
}

void printProcessMemory(const PipelineMemory& m) {
  const ProcStatus& st0 = m.status_before;
  const ProcStatus& st_warm = m.status_warm;
  const ProcStatus& st_end = m.status_end;
  std::cout << "process memory (/proc/self/status):\n"
            << "  VmRSS before " << kibAsMib(st0.rss_kib) << ", after warm-up " << kibAsMib(st_warm.rss_kib)
            << ", at the end " << kibAsMib(st_end.rss_kib) << "; delta " << kibAsMib(st_end.rss_kib - st0.rss_kib)
            << " (after warm-up " << kibAsMib(st_warm.rss_kib - st0.rss_kib) << ")\n"
            << "  VmHWM before " << kibAsMib(st0.hwm_kib) << ", at the end " << kibAsMib(st_end.hwm_kib)
            << "; delta " << kibAsMib(st_end.hwm_kib - st0.hwm_kib) << "\n";
}

void printAllocationCalls(const PipelineMemory& m) {
  if (!kCountsAllocations) {
    std::cout << "allocation calls: not counted (sanitizer build or no glibc: the sanitizer interposes malloc)\n";
    return;
  }
  std::cout << "allocation calls after warm-up (malloc, calloc, realloc, posix_memalign, aligned_alloc, memalign):\n"
            << "  " << m.calls_total << " in " << m.counted_frames << " frames = "
            << static_cast<double>(m.calls_total) / std::max(1, m.counted_frames) << " per frame; max "
            << m.calls_max << " in one frame; " << m.frames_with_calls << " frames allocated";
  if (!m.alloc_frames.empty()) {
    std::cout << " (first:";
    for (int f : m.alloc_frames) std::cout << " " << f;
    std::cout << ")";
  }
  std::cout << "\n";
}

void printTracks(const PipelineMemory& m) {
  std::cout << "tracks alive (tracking or re-detecting) after warm-up:";
  for (const auto& kv : m.alive_frames) std::cout << " " << kv.first << ": " << kv.second << " frames;";
  std::cout << " three tracks in " << framesWithThreeTracks(m) << " of " << m.counted_frames
            << " frames; a track re-detecting in " << m.redetecting_frames << " frames\n";
}

}  // namespace

std::string mib(long long bytes) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.2f MiB", static_cast<double>(bytes) / kMiB);
  return buf;
}

void printScene(const scene::ScenarioConfig& config, const RenderedScene& scene) {
  std::cout << "memory_probe: scene " << config.name << " seed " << config.seed << ", "
            << scene.frames.size() << " frames " << config.size.width << "x" << config.size.height
            << " CV_8UC3 rendered before measuring (" << mib(scene.frame_bytes)
            << " of frame pixels)\n";
}

void printSummary(const PipelineMemory& m, const RenderedScene& scene, int warmup) {
  std::cout << "pipeline: max_obstacles 3, " << m.started
            << " tracks started from the ground-truth boxes of frame 0, " << (scene.frames.size() - 1)
            << " frames processed, warm-up " << warmup << " frames\n";
  printHeap(m, scene);
  printProcessMemory(m);
  printAllocationCalls(m);
  printTracks(m);
}

bool checkTargets(const PipelineMemory& m, double budget_mib) {
  bool ok = true;
  const long long budget = static_cast<long long>(budget_mib * kMiB);
  if (std::max(m.heap_peak, m.exact_peak) > budget) {
    std::cout << "FAIL: core heap peak over the budget of " << budget_mib << " MiB\n";
    ok = false;
  }
  if (2 * framesWithThreeTracks(m) < m.counted_frames) {
    std::cout << "FAIL: three tracks alive in fewer than half of the frames after warm-up\n";
    ok = false;
  }
  if (kCountsAllocations && m.calls_total > 0) {
    std::cout << "FAIL: the pipeline allocates after warm-up\n";
    ok = false;
  }
  std::cout << (ok ? "OK: all memory targets met\n" : "memory targets missed\n");
  return ok;
}

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
