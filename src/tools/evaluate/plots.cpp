// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/plots.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <vector>

namespace fs = std::filesystem;

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

std::string findPlotScript(const std::string& given, const char* argv0) {
  std::vector<fs::path> candidates;
  if (!given.empty()) candidates.emplace_back(given);
  if (const char* env = std::getenv("OT_PLOT_SCRIPT")) candidates.emplace_back(env);
  // This file is src/tools/evaluate/plots.cpp; CMake compiles it by absolute path.
  candidates.push_back(fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path() / "scripts" /
                       "plot_results.py");
  std::error_code ec;
  const fs::path exe = fs::canonical(fs::path(argv0), ec);
  if (!ec) {
    candidates.push_back(exe.parent_path() / "plot_results.py");
    candidates.push_back(exe.parent_path().parent_path().parent_path() / "share" / "obstacle_tracker" /
                         "scripts" / "plot_results.py");
  }
  for (const auto& c : candidates) {
    if (fs::is_regular_file(c)) return c.string();
  }
  return "";
}

std::string findPythonWithMatplotlib() {
  for (const char* py : {"/usr/bin/python3", "python3"}) {
    const std::string cmd = std::string(py) + " -c 'import matplotlib' > /dev/null 2>&1";
    if (std::system(cmd.c_str()) == 0) return py;
  }
  return "";
}

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The PNG files in `out`, by name, as markdown images.
void writePlotsSection(std::ostream& md, const std::string& out) {
  md << "## Plots\n\n";
  std::vector<std::string> pngs;
  for (const auto& e : fs::directory_iterator(out)) {
    if (e.path().extension() == ".png") pngs.push_back(e.path().filename().string());
  }
  std::sort(pngs.begin(), pngs.end());
  for (const auto& p : pngs) md << "![" << fs::path(p).stem().string() << "](" << p << ")\n";
  md << "\n";
}

}  // namespace

void makePlots(std::ostream& md, const std::string& out, const std::string& given_script, const char* argv0) {
  const std::string script = findPlotScript(given_script, argv0);
  const std::string py = script.empty() ? "" : findPythonWithMatplotlib();
  if (script.empty()) {
    std::cerr << "evaluate: plots skipped (scripts/plot_results.py not found; --plot-script FILE)\n";
    return;
  }
  if (py.empty()) {
    std::cerr << "evaluate: plots skipped (no python3 with matplotlib: apt-get install python3-matplotlib)\n";
    return;
  }
  const std::string cmd = py + " " + shellQuote(script) + " " + shellQuote((fs::path(out) / "curves.csv").string()) +
                          " --out " + shellQuote(out);
  if (std::system(cmd.c_str()) != 0) {
    std::cerr << "evaluate: the plot script failed: " << cmd << "\n";
    return;
  }
  writePlotsSection(md, out);
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
