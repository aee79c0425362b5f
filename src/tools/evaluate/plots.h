// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The precision / success plots of the evaluate tool: scripts/plot_results.py run on curves.csv
// when it and a python3 with matplotlib are found.
#pragma once

#include <ostream>
#include <string>

namespace obstacle_tracker {
namespace evaluate_tool {

// Writes the PNGs into `out` and, when that worked, a "## Plots" section linking them to `md`;
// otherwise says on stderr why there are none. `given_script` is --plot-script (may be empty);
// argv0 helps find an installed script.
void makePlots(std::ostream& md, const std::string& out, const std::string& given_script, const char* argv0);

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
