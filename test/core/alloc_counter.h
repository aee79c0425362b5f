// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Heap-allocation counting for the "no allocation per frame" tests (test_kcf_alloc,
// test_region_labels, test_pipeline_memory). Include it in exactly one translation unit of a
// test program: it replaces malloc, calloc, realloc, memalign, aligned_alloc and posix_memalign
// (glibc exports the real ones as __libc_*) with versions that count calls, and the largest
// block asked for, while g_counting is set. Under a sanitizer (which interposes the allocator
// itself) or without glibc, OT_COUNT_ALLOCATIONS stays undefined and the tests skip with a
// message. (memory_probe has its own wrappers that forward to the next allocator, so that
// heaptrack still sees every call.)
#pragma once

#include <atomic>
#include <cstddef>

#include "obstacle_tracker/core/allocation_counting.h"

#ifdef OT_COUNT_ALLOCATIONS
#include <malloc.h>  // declared before they are replaced (also mallinfo2 for the tests)
namespace {
std::atomic<long> g_allocations{0};
std::atomic<std::size_t> g_largest{0};  // largest block requested while counting
std::atomic<bool> g_counting{false};
void noteAllocation(std::size_t n) {
  if (!g_counting.load(std::memory_order_relaxed)) return;
  g_allocations.fetch_add(1);
  std::size_t m = g_largest.load();
  while (n > m && !g_largest.compare_exchange_weak(m, n)) {
  }
}
}  // namespace
extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void* malloc(size_t n) {
  noteAllocation(n);
  return __libc_malloc(n);
}
void* calloc(size_t n, size_t s) {
  noteAllocation(n * s);
  return __libc_calloc(n, s);
}
void* realloc(void* p, size_t n) {
  noteAllocation(n);
  return __libc_realloc(p, n);
}
void* memalign(size_t a, size_t n) {
  noteAllocation(n);
  return __libc_memalign(a, n);
}
void* aligned_alloc(size_t a, size_t n) {
  noteAllocation(n);
  return __libc_memalign(a, n);
}
int posix_memalign(void** out, size_t a, size_t n) {
  if (a < sizeof(void*) || (a & (a - 1)) != 0) return 22;  // EINVAL
  noteAllocation(n);
  void* p = __libc_memalign(a, n);
  if (p == nullptr && n != 0) return 12;  // ENOMEM
  *out = p;
  return 0;
}
}  // extern "C"
#endif
