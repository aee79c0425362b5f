// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The parameter variants init_table compares.
#pragma once

#include <string>
#include <vector>

#include "obstacle_tracker/core/params.h"

namespace obstacle_tracker {
namespace init_table_tool {

// A set of parameters under test, with the name its table row shows.
struct Variant {
  std::string name;
  core::Params p;
};

// Variants of the AutoInitializer for the cue ablation; the first is the defaults.
std::vector<Variant> ablationVariants();

// Options of the one-frame detector (MB+ terms, median, map size, ranking).
std::vector<Variant> detectorOptions();

}  // namespace init_table_tool
}  // namespace obstacle_tracker
