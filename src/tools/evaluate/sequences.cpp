// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/sequences.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/eval/runner.h"
#include "obstacle_tracker/eval/sequence.h"

namespace fs = std::filesystem;
namespace ev = obstacle_tracker::eval;

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

// The sequences under --data: a video file, a folder that is itself a sequence (images or one
// video, with a ground-truth file), or a folder of sequence folders (eval::listSequences; those
// without a ground-truth file are skipped with a message).
std::vector<SequenceInfo> discover(const std::string& data, const std::string& gt_path) {
  std::vector<SequenceInfo> seqs;
  const fs::path root(data);
  if (!fs::exists(root)) throw std::runtime_error("--data " + data + " does not exist");
  if (fs::is_regular_file(root) || ev::folderHasGroundTruth(data) || !gt_path.empty()) {
    SequenceInfo one;
    one.path = data;
    one.gt_path = gt_path;  // when empty, Sequence finds the ground-truth file
    seqs.push_back(one);
    return seqs;
  }
  std::vector<std::string> skipped;
  for (const std::string& dir : ev::listSequences(data, &skipped)) {
    SequenceInfo one;
    one.path = dir;
    seqs.push_back(one);
  }
  for (const std::string& dir : skipped) std::cerr << "evaluate: skipping " << dir << " (no ground-truth file)\n";
  if (seqs.empty()) throw std::runtime_error("no sequence with ground truth under " + data);
  return seqs;
}

// Reads the frame count and the ground truth of `s`'s sequence: absent frames and, with TRE,
// the start frames.
void readFramesAndStarts(const ev::Sequence& seq, const EvaluateOptions& options, SequenceInfo* s) {
  s->frames = seq.frameCount();
  std::vector<cv::Rect2f> gt(s->frames);
  for (int f = 0; f < s->frames; ++f) {
    gt[f] = seq.groundTruthAt(f);
    if (ev::isAbsent(gt[f])) ++s->absent_frames;
  }
  s->starts = {0};
  if (options.tre) {
    // OTB's first TRE segment is the OPE run (from frame 0, or the first present box).
    const std::vector<int> t = ev::treStartFrames(gt, options.tre_segments);
    for (size_t k = 1; k < t.size(); ++k) s->starts.push_back(t[k]);
  }
}

}  // namespace

std::vector<SequenceInfo> selectSequences(const EvaluateOptions& options) {
  const std::vector<std::string>& only = options.sequences;
  std::vector<SequenceInfo> kept;
  for (SequenceInfo& s : discover(options.data, options.gt_path)) {
    ev::Sequence seq(s.path, s.gt_path);
    s.name = seq.name();
    if (!only.empty() && std::find(only.begin(), only.end(), s.name) == only.end()) continue;
    if (!seq.hasGroundTruth()) {
      std::cerr << "evaluate: skipping " << s.path << " (no ground truth)\n";
      continue;
    }
    readFramesAndStarts(seq, options, &s);
    kept.push_back(s);
  }
  return kept;
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
