// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "memory_probe/process_memory.h"

#include <malloc.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace obstacle_tracker {
namespace memory_probe_tool {

long long heapInUse() {
  const struct mallinfo2 mi = mallinfo2();
  return static_cast<long long>(mi.uordblks + mi.hblkhd);
}

ProcStatus readProcStatus() {
  ProcStatus s;
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("VmRSS:", 0) == 0) s.rss_kib = std::atoll(line.c_str() + 6);
    if (line.rfind("VmHWM:", 0) == 0) s.hwm_kib = std::atoll(line.c_str() + 6);
  }
  return s;
}

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
