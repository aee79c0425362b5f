// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The command line of memory_probe.
#pragma once

#include <optional>

#include "obstacle_tracker/scene/scene_generator.h"

namespace obstacle_tracker {
namespace memory_probe_tool {

struct ProbeOptions {
  scene::ScenarioConfig scene;  // --scenario, --seed, --frames, --size
  int warmup = 30;              // --warmup: frames after the start before allocations are counted
  int start_count = 3;          // --start: tracks started from the ground truth
  double budget_mib = 30.0;     // --budget-mib: core heap budget
};

// Either the options to run with, or the code main must exit with: 0 after --help, 2 after a
// usage error (already reported on stderr, with the usage).
struct ParsedCommandLine {
  ProbeOptions options;
  std::optional<int> exit_code;
};

ParsedCommandLine parseProbeOptions(int argc, const char* const* argv);

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
