// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// One line naming the machine a report's figures come from: CPU model, logical CPUs,
// architecture, OS and the OpenCV build. Speeds and even some scores differ between CPU kinds
// (OpenCV's dispatch), so a report without its machine cannot be compared with another.
#pragma once

#include <string>

namespace obstacle_tracker {
namespace evaluate_tool {

std::string machineDescription();

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
