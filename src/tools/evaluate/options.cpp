// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/options.h"

#include <sstream>

#include "command_line.h"
#include "obstacle_tracker/eval/runner.h"

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

}  // namespace

ParsedCommandLine parseEvaluateOptions(int argc, const char* const* argv) {
  ParsedCommandLine parsed;
  EvaluateOptions& o = parsed.options;
  o.command = "evaluate";
  for (int i = 1; i < argc; ++i) o.command += " " + std::string(argv[i]);
  std::string trackers, sequences;
  bool no_plots = false;
  CLI::App app{"Runs our pipeline and OpenCV's trackers over sequences and scores them (OTB precision and "
               "success, long-term scores), writing boxes, CSV tables, a Markdown report and plots.",
               "evaluate"};
  tools::setToolDefaults(app);
  app.add_option("--data", o.data, "a folder of sequences, one sequence, or a video (required)")
      ->type_name("DIR|VIDEO");
  app.add_option("--out", o.out, "the output folder (required)")->type_name("DIR");
  app.add_option("--trackers", trackers, "trackers to run, comma-separated (default: every known tracker)")
      ->type_name("a,b,...");
  app.add_option("--jobs", o.jobs, "parallel runs (at least 1)")->type_name("N")->capture_default_str();
  app.add_flag("--tre", o.tre, "OTB's temporal robustness evaluation too");
  app.add_option("--tre-segments", o.tre_segments, "TRE start frames per sequence (at least 1)")
      ->type_name("N")
      ->capture_default_str();
  app.add_option("--params", o.params_file, "parameters of the ours-* trackers (YAML)")->type_name("FILE");
  app.add_option("--sequences", sequences, "only these sequences, by name, comma-separated (default: all)")
      ->type_name("a,b");
  app.add_option("--gt", o.gt_path, "ground truth of a single sequence or video")->type_name("FILE");
  app.add_flag("--no-plots", no_plots, "no PNG plots");
  app.add_option("--plot-script", o.plot_script, "plot_results.py, when it is not found by itself")
      ->type_name("FILE");
  parsed.exit_code = tools::parseCommandLine(app, argc, argv);
  if (parsed.exit_code) return parsed;
  o.trackers = splitList(trackers);
  o.sequences = splitList(sequences);
  o.plots = !no_plots;
  if (o.data.empty() || o.out.empty()) {
    parsed.exit_code = tools::usageError(app, "--data and --out are required");
  } else if (o.jobs < 1 || o.tre_segments < 1) {
    parsed.exit_code = tools::usageError(app, "--jobs and --tre-segments must be at least 1");
  }
  if (o.trackers.empty()) o.trackers = eval::knownTrackers();
  return parsed;
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
