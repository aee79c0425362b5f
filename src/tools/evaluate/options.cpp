// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/options.h"

#include <cstdlib>
#include <iostream>
#include <sstream>

#include "obstacle_tracker/eval/runner.h"

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

const char* kUsage =
    "usage: evaluate --data DIR|VIDEO --out DIR [--trackers a,b,...] [--jobs N] [--tre]\n"
    "                [--tre-segments N] [--params FILE] [--sequences a,b] [--gt FILE]\n"
    "                [--no-plots] [--plot-script FILE]\n";

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

ParsedCommandLine exitWith(int code) {
  ParsedCommandLine parsed;
  parsed.exit_code = code;
  return parsed;
}

}  // namespace

ParsedCommandLine parseEvaluateOptions(int argc, const char* const* argv) {
  ParsedCommandLine parsed;
  EvaluateOptions& o = parsed.options;
  o.command = "evaluate";
  for (int i = 1; i < argc; ++i) o.command += " " + std::string(argv[i]);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    const bool takes_value = a == "--data" || a == "--out" || a == "--trackers" || a == "--jobs" ||
                             a == "--tre-segments" || a == "--params" || a == "--sequences" ||
                             a == "--gt" || a == "--plot-script";
    if (takes_value && !has_value) {
      std::cerr << "evaluate: " << a << " needs a value\n" << kUsage;
      return exitWith(2);
    }
    if (a == "--data") o.data = argv[++i];
    else if (a == "--out") o.out = argv[++i];
    else if (a == "--trackers") o.trackers = splitList(argv[++i]);
    else if (a == "--jobs") o.jobs = std::atoi(argv[++i]);
    else if (a == "--tre") o.tre = true;
    else if (a == "--tre-segments") o.tre_segments = std::atoi(argv[++i]);
    else if (a == "--params") o.params_file = argv[++i];
    else if (a == "--sequences") o.sequences = splitList(argv[++i]);
    else if (a == "--gt") o.gt_path = argv[++i];
    else if (a == "--no-plots") o.plots = false;
    else if (a == "--plot-script") o.plot_script = argv[++i];
    else if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return exitWith(0);
    } else {
      std::cerr << "evaluate: unknown argument " << a << "\n" << kUsage;
      return exitWith(2);
    }
  }
  if (o.data.empty() || o.out.empty() || o.jobs < 1 || o.tre_segments < 1) {
    std::cerr << kUsage;
    return exitWith(2);
  }
  if (o.trackers.empty()) o.trackers = eval::knownTrackers();
  return parsed;
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
