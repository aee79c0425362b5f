// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The allocator wrappers of memory_probe and their counters (allocation_counter.h).
#include "memory_probe/allocation_counter.h"

#ifdef OT_COUNT_ALLOCATIONS
#include <dlfcn.h>
#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdio>
#include <cstring>

namespace {

std::atomic<long> g_calls{0};          // allocation calls while g_counting
std::atomic<bool> g_counting{false};
std::atomic<long long> g_live{0};      // usable bytes of the live blocks allocated through us
std::atomic<long long> g_peak{0};      // maximum of g_live since the last resetPeakLiveBytes()

using MallocFn = void* (*)(size_t);
using CallocFn = void* (*)(size_t, size_t);
using ReallocFn = void* (*)(void*, size_t);
using FreeFn = void (*)(void*);
using PosixMemalignFn = int (*)(void**, size_t, size_t);
using AlignedFn = void* (*)(size_t, size_t);

MallocFn real_malloc = nullptr;
CallocFn real_calloc = nullptr;
ReallocFn real_realloc = nullptr;
FreeFn real_free = nullptr;
PosixMemalignFn real_posix_memalign = nullptr;
AlignedFn real_aligned_alloc = nullptr;
AlignedFn real_memalign = nullptr;
bool g_resolving = false;

// dlsym may allocate while the real functions are being looked up: those few blocks come from a
// static buffer and are never freed.
alignas(64) unsigned char g_boot[16384];
std::size_t g_boot_used = 0;
bool inBoot(const void* p) {
  const auto* c = static_cast<const unsigned char*>(p);
  return c >= g_boot && c < g_boot + sizeof(g_boot);
}
void* bootAlloc(std::size_t n) {
  const std::size_t need = (n + 63) & ~static_cast<std::size_t>(63);
  if (g_boot_used + need > sizeof(g_boot)) return nullptr;
  void* p = g_boot + g_boot_used;
  g_boot_used += need;
  return p;
}

void resolve() {
  if (real_malloc != nullptr || g_resolving) return;
  g_resolving = true;
  real_calloc = reinterpret_cast<CallocFn>(dlsym(RTLD_NEXT, "calloc"));
  real_realloc = reinterpret_cast<ReallocFn>(dlsym(RTLD_NEXT, "realloc"));
  real_free = reinterpret_cast<FreeFn>(dlsym(RTLD_NEXT, "free"));
  real_posix_memalign = reinterpret_cast<PosixMemalignFn>(dlsym(RTLD_NEXT, "posix_memalign"));
  real_aligned_alloc = reinterpret_cast<AlignedFn>(dlsym(RTLD_NEXT, "aligned_alloc"));
  real_memalign = reinterpret_cast<AlignedFn>(dlsym(RTLD_NEXT, "memalign"));
  MallocFn m = reinterpret_cast<MallocFn>(dlsym(RTLD_NEXT, "malloc"));
  if (m == nullptr || real_calloc == nullptr || real_realloc == nullptr || real_free == nullptr ||
      real_posix_memalign == nullptr || real_aligned_alloc == nullptr || real_memalign == nullptr) {
    static const char msg[] = "memory_probe: cannot resolve the allocator functions\n";
    fwrite(msg, 1, sizeof(msg) - 1, stderr);
    abort();
  }
  real_malloc = m;
  g_resolving = false;
}

void noteCall() {
  if (g_counting.load(std::memory_order_relaxed)) g_calls.fetch_add(1, std::memory_order_relaxed);
}
void addLive(void* p) {
  if (p == nullptr) return;
  const auto n = static_cast<long long>(malloc_usable_size(p));
  const long long now = g_live.fetch_add(n, std::memory_order_relaxed) + n;
  long long peak = g_peak.load(std::memory_order_relaxed);
  while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
}
void subLive(void* p) {
  if (p != nullptr) g_live.fetch_sub(static_cast<long long>(malloc_usable_size(p)), std::memory_order_relaxed);
}

}  // namespace

extern "C" {
void* malloc(size_t n) {
  if (real_malloc == nullptr) {
    if (g_resolving) return bootAlloc(n);
    resolve();
  }
  noteCall();
  void* p = real_malloc(n);
  addLive(p);
  return p;
}
void* calloc(size_t n, size_t s) {
  if (real_malloc == nullptr) {
    if (g_resolving) {
      if (s != 0 && n > sizeof(g_boot) / s) return nullptr;
      return bootAlloc(n * s);  // static storage: already zero
    }
    resolve();
  }
  noteCall();
  void* p = real_calloc(n, s);
  addLive(p);
  return p;
}
void* realloc(void* old, size_t n) {
  if (real_malloc == nullptr) resolve();
  noteCall();
  if (old != nullptr && inBoot(old)) {
    // Old size unknown: copy what is left of the boot buffer after it, at most n bytes.
    const std::size_t avail = static_cast<std::size_t>(g_boot + sizeof(g_boot) - static_cast<unsigned char*>(old));
    void* p = real_malloc(n);
    if (p != nullptr) std::memcpy(p, old, std::min(avail, n));
    addLive(p);
    return p;
  }
  subLive(old);
  void* p = real_realloc(old, n);
  if (p != nullptr) {
    addLive(p);
  } else if (old != nullptr && n != 0) {
    addLive(old);  // failed: the old block is still there
  }
  return p;
}
void free(void* p) {
  if (p == nullptr || inBoot(p)) return;
  if (real_free == nullptr) resolve();
  subLive(p);
  real_free(p);
}
int posix_memalign(void** out, size_t align, size_t n) {
  if (real_malloc == nullptr) resolve();
  noteCall();
  const int r = real_posix_memalign(out, align, n);
  if (r == 0) addLive(*out);
  return r;
}
void* aligned_alloc(size_t align, size_t n) {
  if (real_malloc == nullptr) resolve();
  noteCall();
  void* p = real_aligned_alloc(align, n);
  addLive(p);
  return p;
}
void* memalign(size_t align, size_t n) {
  if (real_malloc == nullptr) resolve();
  noteCall();
  void* p = real_memalign(align, n);
  addLive(p);
  return p;
}
}  // extern "C"

namespace obstacle_tracker {
namespace memory_probe_tool {

long allocationCalls() { return g_calls.load(); }
void setCountingAllocations(bool on) { g_counting.store(on); }
long long liveBytes() { return g_live.load(); }
long long peakLiveBytes() { return g_peak.load(); }
void resetPeakLiveBytes(long long start) { g_peak.store(start); }

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker

#else  // no wrappers: nothing is counted

namespace obstacle_tracker {
namespace memory_probe_tool {

long allocationCalls() { return 0; }
void setCountingAllocations(bool) {}
long long liveBytes() { return 0; }
long long peakLiveBytes() { return 0; }
void resetPeakLiveBytes(long long) {}

}  // namespace memory_probe_tool
}  // namespace obstacle_tracker

#endif  // OT_COUNT_ALLOCATIONS
