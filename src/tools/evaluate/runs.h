// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The runs of the evaluate tool: every tracker on every sequence from every start frame, in
// parallel jobs, each job single-threaded, with progress on stderr.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "evaluate/sequences.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/eval/runner.h"

namespace obstacle_tracker {
namespace evaluate_tool {

// One run: tracker `tracker` on sequence `seq` (indices) from frame `start`.
struct RunTask {
  size_t seq, tracker;
  int start;
  double cost;  // relative, only to order the runs
};

struct RunPlan {
  std::vector<RunTask> tasks;  // slowest first, so that the jobs end together
  long long total_frames = 0;
};

RunPlan planRuns(const std::vector<SequenceInfo>& seqs, const std::vector<std::string>& trackers);

// Runs every task of `plan` on `jobs` threads; result k belongs to plan.tasks[k]. A run that
// throws gives a result with its error and no boxes. Progress times count from `started`.
std::vector<eval::RunResult> runAll(const RunPlan& plan, const std::vector<SequenceInfo>& seqs,
                                    const std::vector<std::string>& trackers, const core::Params& params,
                                    int jobs, std::chrono::steady_clock::time_point started);

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
