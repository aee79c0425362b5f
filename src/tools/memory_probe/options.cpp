// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "memory_probe/options.h"

#include <cstdint>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

namespace obstacle_tracker {
namespace memory_probe_tool {
namespace {

const char* kUsage =
    "usage: memory_probe [--frames N] [--size WxH] [--scenario NAME] [--seed N] [--warmup N]\n"
    "                    [--start K] [--budget-mib M]\n"
    "  --frames N      frames processed (default 300; frame 0 starts the tracks)\n"
    "  --size WxH      frame size (default 1280x720)\n"
    "  --scenario S    generated scene with three obstacles (default multi; see generate_scene --list)\n"
    "  --seed N        scene seed (default 1)\n"
    "  --warmup N      frames after the start before allocations are counted (default 30)\n"
    "  --start K       start K of the three tracks from the ground truth (default 3; fewer leaves the\n"
    "                  others to auto-initialisation, which then searches every frame)\n"
    "  --budget-mib M  core heap budget in MiB (default 30)\n";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

int toInt(const std::string& what, const std::string& v) {
  std::size_t used = 0;
  int x = 0;
  try {
    x = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size()) throw UsageError(what + " wants an integer, got '" + v + "'");
  return x;
}

// Reads the options in order; true when --help came (the arguments after it are not read).
// Throws UsageError.
bool readArguments(int argc, const char* const* argv, ProbeOptions* options) {
  scene::ScenarioConfig& cfg = options->scene;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError("missing value after " + a);
      return argv[++i];
    };
    if (a == "--frames") {
      cfg.frames = toInt(a, value());
    } else if (a == "--size") {
      const std::string v = value();
      const auto x = v.find_first_of("xX");
      if (x == std::string::npos) throw UsageError("--size wants WxH, got " + v);
      cfg.size = cv::Size(toInt(a, v.substr(0, x)), toInt(a, v.substr(x + 1)));
    } else if (a == "--scenario") {
      cfg.name = value();
    } else if (a == "--seed") {
      cfg.seed = static_cast<std::uint64_t>(toInt(a, value()));
    } else if (a == "--warmup") {
      options->warmup = toInt(a, value());
    } else if (a == "--start") {
      options->start_count = toInt(a, value());
      if (options->start_count < 1 || options->start_count > 3) throw UsageError("--start must be 1, 2 or 3");
    } else if (a == "--budget-mib") {
      options->budget_mib = std::stod(value());
    } else if (a == "--help" || a == "-h") {
      return true;
    } else {
      throw UsageError("unknown argument " + a);
    }
  }
  return false;
}

}  // namespace

ParsedCommandLine parseProbeOptions(int argc, const char* const* argv) {
  ParsedCommandLine parsed;
  ProbeOptions& options = parsed.options;
  options.scene.name = "multi";
  options.scene.seed = 1;
  options.scene.frames = 300;
  options.scene.size = cv::Size(1280, 720);
  try {
    if (readArguments(argc, argv, &options)) {
      std::cout << kUsage;
      parsed.exit_code = 0;
      return parsed;
    }
    if (options.scene.frames < 2) throw UsageError("--frames must be at least 2");
    if (options.warmup < 0 || options.warmup >= options.scene.frames - 1) {
      throw UsageError("--warmup must be in [0, frames - 2]");
    }
  } catch (const UsageError& e) {
    std::cerr << "memory_probe: " << e.what() << "\n" << kUsage;
    parsed.exit_code = 2;
  }
  return parsed;
}

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
