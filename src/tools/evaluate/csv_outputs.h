// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The machine-readable outputs of the evaluate tool: results.csv, curves.csv and the box files.
#pragma once

#include <string>
#include <vector>

#include "evaluate/runs.h"
#include "evaluate/scores.h"
#include "obstacle_tracker/eval/runner.h"

namespace obstacle_tracker {
namespace evaluate_tool {

// OUT/results.csv: one row per sequence, tracker and mode (OPE, TRE), then the subset means.
void writeResultsCsv(const std::string& out, const EvaluationResults& res);

// OUT/curves.csv, long format (one value per line): precision and success curves of the subset
// means, then of each sequence.
void writeCurvesCsv(const std::string& out, const EvaluationResults& res);

// OUT/boxes/<sequence>/<tracker>.txt: x,y,w,h,confidence per frame of every OPE run that gave
// boxes; 0,0,0,0 where the tracker reported no target.
void writeBoxFiles(const std::string& out, const RunPlan& plan, const std::vector<eval::RunResult>& results,
                   const EvaluationResults& res);

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
