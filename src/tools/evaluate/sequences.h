// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The sequences the evaluate tool runs: found under --data, narrowed by --sequences, each with
// its frame count, absent frames and run start frames.
#pragma once

#include <string>
#include <vector>

#include "evaluate/options.h"

namespace obstacle_tracker {
namespace evaluate_tool {

struct SequenceInfo {
  std::string name, path, gt_path;
  int frames = 0;
  int absent_frames = 0;
  std::vector<int> starts;  // run start frames: {0} (OPE) then the TRE starts
};

// The sequences under options.data (a video file, a folder that is itself a sequence, or a folder
// of sequence folders), in name order, those named by options.sequences only. Sequences without
// ground truth are skipped with a message on stderr. Throws std::runtime_error when --data does
// not exist, holds no sequence with ground truth, or a sequence cannot be read. May be empty.
std::vector<SequenceInfo> selectSequences(const EvaluateOptions& options);

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
