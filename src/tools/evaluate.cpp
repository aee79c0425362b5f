// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// evaluate --data DIR --out DIR [--trackers a,b,...] [--jobs N] [--tre] [--tre-segments N]
//          [--params FILE] [--sequences a,b] [--gt FILE] [--no-plots] [--plot-script FILE]
//
// Runs every sequence of DIR (each subfolder in OTB layout; DIR itself when it is one sequence;
// or a single video file, with --gt or a ground-truth file next to it) with every tracker, in
// parallel jobs over (sequence, tracker, start frame) tasks, each job single-threaded. Scores:
// OTB precision (0-50 px, @20) and success (21 IoU thresholds, AUC), mean centre error, OPE and
// with --tre OTB's TRE (restarts from evenly spaced frames, frames pooled); VOT long-term
// precision / recall / F for sequences with absent frames; frames per second of the tracker's own
// per-frame call (decode excluded). Writes OUT/results.csv, OUT/results.md, OUT/curves.csv,
// OUT/boxes/<sequence>/<tracker>.txt (x,y,w,h,confidence per frame, OPE) and, when python3 with
// matplotlib is there, precision/success plots (scripts/plot_results.py) as PNG.
//
// This file reads the command line and runs the steps; the parts are in src/tools/evaluate/.
#include <chrono>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "evaluate/csv_outputs.h"
#include "evaluate/markdown_report.h"
#include "evaluate/number_format.h"
#include "evaluate/options.h"
#include "evaluate/plots.h"
#include "evaluate/runs.h"
#include "evaluate/scores.h"
#include "evaluate/sequences.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/eval/runner.h"

namespace fs = std::filesystem;
namespace ev = obstacle_tracker::eval;
namespace et = obstacle_tracker::evaluate_tool;
using obstacle_tracker::core::Params;

namespace {

// The parameters of the ours-* trackers: --params FILE or the defaults. False (reported) when the
// file cannot be read.
bool loadParams(const std::string& params_file, Params* params) {
  if (params_file.empty()) return true;
  std::vector<std::string> messages;
  try {
    *params = obstacle_tracker::core::loadParamsFile(params_file, &messages);
  } catch (const std::exception& e) {
    std::cerr << "evaluate: " << e.what() << "\n";
    return false;
  }
  for (const auto& m : messages) std::cerr << "evaluate: " << m << "\n";
  return true;
}

// False (reported) when a tracker name is unknown, before any sequence is read.
bool checkTrackerNames(const std::vector<std::string>& trackers, const Params& params) {
  for (const auto& t : trackers) {
    try {
      ev::makeTracker(t, params);
    } catch (const std::exception& e) {
      std::cerr << "evaluate: " << e.what() << "\n";
      return false;
    }
  }
  return true;
}

void logPlan(const et::RunPlan& plan, const std::vector<et::SequenceInfo>& seqs, const et::EvaluateOptions& o) {
  std::cerr << "evaluate: " << seqs.size() << " sequences x " << o.trackers.size() << " trackers, "
            << plan.tasks.size() << " runs (" << plan.total_frames << " frames) on " << o.jobs << " jobs"
            << (o.tre ? ", OPE + TRE" : ", OPE") << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  const et::ParsedCommandLine parsed = et::parseEvaluateOptions(argc, argv);
  if (parsed.exit_code) return *parsed.exit_code;
  const et::EvaluateOptions& o = parsed.options;
  // One thread per job: OpenCV's own parallel loops would fight the job pool for the cores.
  cv::setNumThreads(1);

  Params params;
  if (!loadParams(o.params_file, &params)) return 1;
  if (!checkTrackerNames(o.trackers, params)) return 2;
  std::vector<et::SequenceInfo> seqs;
  try {
    seqs = et::selectSequences(o);
  } catch (const std::exception& e) {
    std::cerr << "evaluate: " << e.what() << "\n";
    return 1;
  }
  if (seqs.empty()) {
    std::cerr << "evaluate: no sequence selected\n";
    return 1;
  }
  fs::create_directories(o.out);

  const et::RunPlan plan = et::planRuns(seqs, o.trackers);
  logPlan(plan, seqs, o);
  const auto t_start = std::chrono::steady_clock::now();
  const std::vector<ev::RunResult> results = et::runAll(plan, seqs, o.trackers, params, o.jobs, t_start);
  const et::EvaluationResults res = et::scoreRuns(plan, results, seqs, o.trackers, o.tre);

  et::writeBoxFiles(o.out, plan, results, res);
  et::writeResultsCsv(o.out, res);
  et::writeCurvesCsv(o.out, res);
  std::ostringstream md;
  et::writeResultsMarkdown(md, o, res);
  if (o.plots) et::makePlots(md, o.out, o.plot_script, argv[0]);
  {
    std::ofstream f(fs::path(o.out) / "results.md");
    f << md.str();
  }
  std::cout << md.str();
  const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  std::cerr << "evaluate: wrote " << o.out << "/results.csv, results.md, curves.csv, boxes/ in "
            << et::formatNumber(el, 0) << " s"
            << (res.errors > 0 ? " (" + std::to_string(res.errors) + " runs had errors)" : "") << "\n";
  return res.errors > 0 ? 1 : 0;
}
