// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// results.md of the evaluate tool, the report a person reads: overall tables per subset, per
// sequence tables, sense and avoid, long-term scores and the runs that failed.
#pragma once

#include <ostream>

#include "evaluate/options.h"
#include "evaluate/scores.h"

namespace obstacle_tracker {
namespace evaluate_tool {

// Every section but the plots.
void writeResultsMarkdown(std::ostream& md, const EvaluateOptions& options, const EvaluationResults& res);

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
