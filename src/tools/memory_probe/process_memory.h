// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Readings of the process's memory: glibc's heap in use and /proc/self/status.
#pragma once

namespace obstacle_tracker {
namespace memory_probe_tool {

// glibc mallinfo2() in-use bytes: arena plus mmapped blocks.
long long heapInUse();

// VmRSS and VmHWM in KiB; -1 when not found.
struct ProcStatus {
  long long rss_kib = -1, hwm_kib = -1;
};

ProcStatus readProcStatus();

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
