// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// What memory_probe prints: the scene line, the summary of the measured run, and the targets
// checked against it.
#pragma once

#include <string>

#include "memory_probe/pipeline_run.h"
#include "memory_probe/scene_frames.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace obstacle_tracker {
namespace memory_probe_tool {

// "12.34 MiB"
std::string mib(long long bytes);

void printScene(const scene::ScenarioConfig& config, const RenderedScene& scene);

void printSummary(const PipelineMemory& m, const RenderedScene& scene, int warmup);

// Prints a FAIL line per missed target (core heap peak over budget_mib, three tracks alive in
// fewer than half of the frames after warm-up, allocations after warm-up when they are counted)
// and the verdict; true when all were met.
bool checkTargets(const PipelineMemory& m, double budget_mib);

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
