// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Whether this build can count heap allocations by replacing malloc & co.: with glibc, and not
// under a sanitizer (which interposes the allocator itself, so a second replacement would break
// its bookkeeping). Defines OT_COUNT_ALLOCATIONS when it can. Shared by the allocation-counting
// tests (test/core/alloc_counter.h) and memory_probe's wrappers, so that both decide the same way.
#pragma once

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || \
    __has_feature(thread_sanitizer)
#define OT_SANITIZED_BUILD 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define OT_SANITIZED_BUILD 1
#endif

#if defined(__GLIBC__) && !defined(OT_SANITIZED_BUILD)
#define OT_COUNT_ALLOCATIONS 1
#endif
