// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// MatArena (mat_arena.h).
#include "obstacle_tracker/core/mat_arena.h"

namespace obstacle_tracker {
namespace core {

cv::Mat MatArena::get(int rows, int cols, int type) {
  const size_t bytes = static_cast<size_t>(rows) * cols * CV_ELEM_SIZE(type);
  if (memory_.size() < bytes) memory_.resize(bytes);
  return cv::Mat(rows, cols, type, memory_.data());
}

}  // namespace core
}  // namespace obstacle_tracker
