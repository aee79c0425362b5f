// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// A memory block that hands out cv::Mat views; it grows only when a larger view is asked for,
// so a sequence of calls with varying sizes stops allocating once the largest size was seen.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

class MatArena {
 public:
  // A view of rows x cols of `type` on the arena's memory; valid until the next get().
  cv::Mat get(int rows, int cols, int type);

 private:
  std::vector<std::uint8_t> memory_;
};

}  // namespace core
}  // namespace obstacle_tracker
