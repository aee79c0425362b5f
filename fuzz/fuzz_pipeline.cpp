// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// libFuzzer target for the core Pipeline: random frame sizes (up to 255 x 255), CV_8UC1 and
// CV_8UC3, contents, stamps (duplicates, going backwards, NaN), parameter changes and startTrack
// boxes; the layout is in pipeline_input.h. Must never crash; std::invalid_argument only for a
// deliberately invalid call; every reported obstacle must be finite with confidence in [0, 1].
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include <opencv2/core/utility.hpp>

#include "pipeline_input.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // One thread: OpenCV's thread pool only slows the fuzzer down and hides nothing.
  cv::setNumThreads(0);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  obstacle_tracker::fuzz::PipelineRunResult r = obstacle_tracker::fuzz::runPipelineInput(data, size);
  if (!r.violation.empty()) {
    std::fprintf(stderr, "fuzz_pipeline: contract broken: %s\n", r.violation.c_str());
    std::abort();
  }
  return 0;
}
