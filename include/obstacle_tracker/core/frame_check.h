// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The one check of an input frame every core entry point makes: not empty, CV_8UC1 (grey) or
// CV_8UC3 (BGR). Bad input gets a clear error, never a crash.
#pragma once

#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

// Throws std::invalid_argument naming `who` and what is wrong.
inline void requireFrame(const cv::Mat& frame, const char* who) {
  if (frame.empty()) throw std::invalid_argument(std::string(who) + ": empty frame");
  if (frame.type() != CV_8UC1 && frame.type() != CV_8UC3) {
    throw std::invalid_argument(std::string(who) + ": frame must be CV_8UC1 (grey) or CV_8UC3 (BGR), got type " +
                                std::to_string(frame.type()));
  }
}

}  // namespace core
}  // namespace obstacle_tracker
