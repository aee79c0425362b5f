// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Our pipeline as an EvalTracker (see runner.h): "ours-auto" runs core::Pipeline::process on
// every frame from the first (it finds the target by itself); "ours-gt" starts a track on the
// first ground-truth box with Pipeline::startTrack. The reported box is the pipeline's best
// obstacle (the first of process()'s list) with its confidence; an empty list is "no target".
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/eval/runner.h"

namespace obstacle_tracker {
namespace eval {

// {"ours-auto", "ours-gt"}.
std::vector<std::string> pipelineTrackerNames();

// nullptr when `name` is not one of pipelineTrackerNames().
std::unique_ptr<EvalTracker> makePipelineTracker(const std::string& name, const core::Params& params);

}  // namespace eval
}  // namespace obstacle_tracker
