// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The scores of the evaluate tool: per sequence and tracker (OPE, pooled TRE, long-term, sense and
// avoid, timing) and their means over subsets of the sequences.
#pragma once

#include <string>
#include <vector>

#include "evaluate/runs.h"
#include "evaluate/sequences.h"
#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/eval/runner.h"

namespace obstacle_tracker {
namespace evaluate_tool {

// One tracker on one sequence.
struct ScoreCell {
  bool done = false;  // the OPE run gave boxes
  eval::OtbScores ope, tre;
  bool has_tre = false;
  double fps = 0.0;
  double ms_p99 = 0.0, ms_max = 0.0;  // per-frame time of the tracker's call
  bool has_lt = false;
  eval::LongTermScores lt;
  eval::SenseAvoidScores sa;
  std::string error;
  // Every run (OPE and TRE starts) pooled, for the TRE frames per second.
  double pooled_update_seconds = 0.0;
  int pooled_timed_frames = 0;
};

struct Subset {
  std::string name;
  std::vector<size_t> seqs;
};

// Means over a subset's sequences for one tracker.
struct SubsetSummary {
  eval::OtbScores ope, tre;
  double fps = 0.0;  // geometric mean
  int lt_n = 0;      // sequences with long-term scores
  double lt_p = 0, lt_r = 0, lt_f = 0;
};

// Everything the output files are written from.
struct EvaluationResults {
  std::vector<SequenceInfo> seqs;
  std::vector<std::string> trackers;
  bool tre = false;
  std::vector<std::vector<ScoreCell>> cells;            // [sequence][tracker]
  std::vector<Subset> subsets;                          // "all", then "flying" when it is a real subset
  std::vector<std::vector<SubsetSummary>> summaries;    // [subset][tracker]
  int errors = 0;                                       // runs that stopped with an error
};

// Scores the runs (results[k] of plan.tasks[k]) and sums them up over the subsets.
EvaluationResults scoreRuns(const RunPlan& plan, const std::vector<eval::RunResult>& results,
                            const std::vector<SequenceInfo>& seqs, const std::vector<std::string>& trackers,
                            bool tre);

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
