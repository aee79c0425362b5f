// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/number_format.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace obstacle_tracker {
namespace evaluate_tool {

std::string formatNumber(double value, int decimals) {
  if (!std::isfinite(value)) return "-";
  std::ostringstream os;
  os << std::fixed << std::setprecision(decimals) << value;
  return os.str();
}

std::string formatDistance(double px, int decimals) {
  return std::isinf(px) ? std::string("inf") : formatNumber(px, decimals);
}

std::string formatFps(double fps) {
  if (!(fps > 0.0) || !std::isfinite(fps)) return "-";
  return formatNumber(fps, fps >= 100.0 ? 0 : 1);
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
