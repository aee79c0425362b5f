// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/machine.h"

#include <sys/utsname.h>

#include <fstream>
#include <sstream>
#include <thread>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

// The value of the first "key ... : value" line of a /proc or /etc file, "" when there is none.
std::string firstValue(const char* path, const std::string& key, char separator) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size(), key) != 0) continue;
    const size_t at = line.find(separator);
    if (at == std::string::npos) continue;
    std::string value = line.substr(at + 1);
    value.erase(0, value.find_first_not_of(" \t\""));
    while (!value.empty() && (value.back() == '"' || value.back() == ' ')) value.pop_back();
    return value;
  }
  return "";
}

}  // namespace

std::string machineDescription() {
  std::ostringstream out;
  // x86 names its model; arm64's /proc/cpuinfo has no "model name", only part numbers.
  std::string cpu = firstValue("/proc/cpuinfo", "model name", ':');
  if (cpu.empty()) cpu = "CPU part " + firstValue("/proc/cpuinfo", "CPU part", ':');
  struct utsname names {};
  const std::string arch = uname(&names) == 0 ? names.machine : "unknown architecture";
  const std::string os = firstValue("/etc/os-release", "PRETTY_NAME", '=');
  out << cpu << ", " << std::thread::hardware_concurrency() << " logical CPUs, " << arch;
  if (!os.empty()) out << ", " << os;
  out << ", OpenCV " << CV_VERSION;
  return out.str();
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
