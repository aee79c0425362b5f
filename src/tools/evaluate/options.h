// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The command line of the evaluate tool.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace obstacle_tracker {
namespace evaluate_tool {

struct EvaluateOptions {
  std::string data;                     // --data: a folder of sequences, one sequence, or a video
  std::string out;                      // --out: the output folder
  std::vector<std::string> trackers;    // --trackers; every known tracker when not given
  int jobs = 1;                         // --jobs: parallel runs
  bool tre = false;                     // --tre: OTB's temporal robustness evaluation too
  int tre_segments = 20;                // --tre-segments: TRE start frames per sequence
  std::string params_file;              // --params: parameters of the ours-* trackers
  std::vector<std::string> sequences;   // --sequences: only these (by name); empty: all
  std::string gt_path;                  // --gt: ground truth of a single sequence or video
  bool plots = true;                    // --no-plots turns the PNG plots off
  std::string plot_script;              // --plot-script: plot_results.py when not found by itself
  std::string command;                  // "evaluate ARGS...", quoted in results.md
};

// Either the options to run with, or the code main must exit with: 0 after --help, 2 after a
// usage error (already reported on stderr, with the usage).
struct ParsedCommandLine {
  EvaluateOptions options;
  std::optional<int> exit_code;
};

ParsedCommandLine parseEvaluateOptions(int argc, const char* const* argv);

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
