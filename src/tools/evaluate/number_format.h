// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// How the evaluate tool prints numbers in its tables, CSV files and log.
#pragma once

#include <string>

namespace obstacle_tracker {
namespace evaluate_tool {

// Fixed-point with `decimals` digits; "-" for NaN and infinities.
std::string formatNumber(double value, int decimals = 3);

// A distance that may be infinite (the first box's centre error when the target was not in
// view): "inf" for an infinity, otherwise formatNumber.
std::string formatDistance(double px, int decimals);

// Frames per second: whole numbers from 100 up, one decimal below; "-" when not positive.
std::string formatFps(double fps);

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
