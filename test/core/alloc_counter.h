// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Heap-allocation counting for the "no allocation" tests (test_extent, test_intensity_stretch,
// test_kcf_alloc, test_pipeline_memory, test_region_labels, test_target_contrast, and
// test/ros/test_image_conversion). Include it in exactly one translation unit of a test program: it
// replaces malloc, calloc, realloc, memalign, aligned_alloc and posix_memalign (glibc exports the
// real ones as __libc_*) with versions that count calls, and the largest block asked for, while
// g_counting is set. Under a sanitizer (which interposes the allocator itself) or without glibc,
// OT_COUNT_ALLOCATIONS stays undefined, nothing is replaced and the tests skip with a message
// (OT_SKIP_UNLESS_COUNTING_ALLOCATIONS). (memory_probe has its own wrappers that forward to the
// next allocator, so that heaptrack still sees every call.)
#pragma once

#include <atomic>
#include <cstddef>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "obstacle_tracker/core/allocation_counting.h"

// The counters exist in every build, so that a test body compiles in all of them; they only move
// where OT_COUNT_ALLOCATIONS is defined, and elsewhere the test skips before it reads them.
namespace {
[[maybe_unused]] std::atomic<long> g_allocations{0};
[[maybe_unused]] std::atomic<std::size_t> g_largest{0};  // largest block requested while counting
[[maybe_unused]] std::atomic<bool> g_counting{false};

// Allocations the counter saw while OpenCV made a 64x64 matrix: more than none, or the counter
// misses allocations made inside OpenCV and a test's zero would mean nothing.
// Use: ASSERT_GT(probeOpenCvAllocations(), 0);
[[maybe_unused]] long probeOpenCvAllocations() {
  g_allocations = 0;
  g_counting = true;
  { cv::Mat probe(64, 64, CV_32F); }
  g_counting = false;
  return g_allocations.load();
}
}  // namespace

// First statement of an allocation test: skips the test, with the reason, in a build that cannot
// count allocations (OT_COUNT_ALLOCATIONS undefined); does nothing in one that can. A macro, not a
// function, because GTEST_SKIP() returns from the function it stands in: it must be in the test
// body itself.
#ifdef OT_COUNT_ALLOCATIONS
#define OT_SKIP_UNLESS_COUNTING_ALLOCATIONS() static_cast<void>(0)
#else
#define OT_SKIP_UNLESS_COUNTING_ALLOCATIONS() \
  GTEST_SKIP() << "allocation counting needs glibc and no sanitizer (which interposes malloc)"
#endif

#ifdef OT_COUNT_ALLOCATIONS
#include <malloc.h>  // declared before they are replaced (also mallinfo2 for the tests)
namespace {
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
