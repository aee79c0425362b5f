// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Counting this program's heap allocations. allocation_counter.cpp defines malloc, calloc,
// realloc, free, posix_memalign, aligned_alloc and memalign; they forward to the next definition
// (dlsym(RTLD_NEXT)), so heaptrack's own interposition still sees everything when the probe runs
// under heaptrack. Under a sanitizer (which interposes malloc itself) or without glibc nothing is
// wrapped: kCountsAllocations is false and the functions below return 0.
#pragma once

#include "obstacle_tracker/core/allocation_counting.h"

namespace obstacle_tracker {
namespace memory_probe_tool {

#ifdef OT_COUNT_ALLOCATIONS
constexpr bool kCountsAllocations = true;
#else
constexpr bool kCountsAllocations = false;
#endif

// Allocation calls (all the wrapped functions but free) made while counting was on.
long allocationCalls();
void setCountingAllocations(bool on);

// Usable bytes of the live blocks allocated through the wrappers.
long long liveBytes();

// The largest liveBytes() seen since resetPeakLiveBytes(start), which sets it to `start`. Unlike
// a reading after each frame, it also sees the peaks inside a frame.
long long peakLiveBytes();
void resetPeakLiveBytes(long long start);

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker
