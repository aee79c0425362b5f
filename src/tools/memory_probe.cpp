// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// memory_probe [--frames N] [--size WxH] [--scenario NAME] [--seed N] [--warmup N]
//              [--start K] [--budget-mib M]
//
// Measures the memory of core::Pipeline with three tracks (the promise: "no allocation per frame once
// a track exists; the core's resident memory with three tracks on 1280x720 frames under 30 MiB").
// A generated scene (default "multi": three obstacles whose paths cross) is rendered into memory
// first and the generator destroyed, so that its memory is not counted; then a Pipeline with
// max_obstacles = 3 starts one track per ground-truth box of the first frame (startTrack) and
// processes the other frames. Reported:
//   heap   glibc mallinfo2() in-use bytes (arena + mmapped) relative to just before the Pipeline
//          is constructed: after warm-up, at the end, and the largest value seen after a frame;
//          plus the exact peak of the live bytes counted by this program's allocator wrappers
//          (which also sees peaks inside a frame).
//   RSS    VmRSS / VmHWM from /proc/self/status before the Pipeline, after warm-up and at the end.
//   calls  malloc/calloc/realloc/posix_memalign/aligned_alloc/memalign calls per frame after the
//          warm-up (wrappers in this program forward to the next definition, dlsym(RTLD_NEXT), so
//          heaptrack's own interposition still sees everything when run under heaptrack).
//   tracks how many tracks were alive (tracking or re-detecting) per frame.
// Exit codes: 0 all targets met, 1 a target missed (tracks not started / mostly not 3, heap over
// the budget, allocations per frame after warm-up), 2 usage or scene error.
// Under a sanitizer (which interposes malloc itself) the counting is skipped with a message.
#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/scene/scene_generator.h"

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
#include <dlfcn.h>

namespace {

std::atomic<long> g_calls{0};          // allocation calls while g_counting
std::atomic<bool> g_counting{false};
std::atomic<long long> g_live{0};      // usable bytes of the live blocks allocated through us
std::atomic<long long> g_peak{0};      // maximum of g_live since the last resetPeak()

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
#endif  // OT_COUNT_ALLOCATIONS

namespace core = obstacle_tracker::core;
namespace scene = obstacle_tracker::scene;

namespace {

const char* kUsage =
    "usage: memory_probe [--frames N] [--size WxH] [--scenario NAME] [--seed N] [--warmup N]\n"
    "                    [--start K] [--budget-mib M]\n"
    "  --frames N      frames processed (default 300; frame 0 starts the tracks)\n"
    "  --size WxH      frame size (default 1280x720)\n"
    "  --scenario S    generated scene with three obstacles (default multi; see generate_scene --list)\n"
    "  --seed N        scene seed (default 1)\n"
    "  --warmup N      frames after the start before allocations are counted (default 30)\n"
    "  --start K       start K of the three tracks from the ground truth (default 3; fewer leaves the\n"
    "                  others to auto-initialisation, which then searches every frame)\n"
    "  --budget-mib M  core heap budget in MiB (default 30)\n";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr double kMiB = 1024.0 * 1024.0;

long long heapInUse() {
  const struct mallinfo2 mi = mallinfo2();
  return static_cast<long long>(mi.uordblks + mi.hblkhd);
}

struct ProcStatus {
  long long rss_kib = -1, hwm_kib = -1;
};

ProcStatus readStatus() {
  ProcStatus s;
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("VmRSS:", 0) == 0) s.rss_kib = std::atoll(line.c_str() + 6);
    if (line.rfind("VmHWM:", 0) == 0) s.hwm_kib = std::atoll(line.c_str() + 6);
  }
  return s;
}

std::string mib(long long bytes) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.2f MiB", static_cast<double>(bytes) / kMiB);
  return buf;
}

std::string kibAsMib(long long kib) { return kib < 0 ? std::string("n/a") : mib(kib * 1024); }

int toInt(const std::string& what, const std::string& v) {
  std::size_t used = 0;
  int x = 0;
  try {
    x = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size()) throw UsageError(what + " wants an integer, got '" + v + "'");
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  scene::ScenarioConfig cfg;
  cfg.name = "multi";
  cfg.seed = 1;
  cfg.frames = 300;
  cfg.size = cv::Size(1280, 720);
  int warmup = 30;
  int start_count = 3;
  double budget_mib = 30.0;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw UsageError("missing value after " + a);
        return argv[++i];
      };
      if (a == "--frames") {
        cfg.frames = toInt(a, value());
      } else if (a == "--size") {
        const std::string v = value();
        const auto x = v.find_first_of("xX");
        if (x == std::string::npos) throw UsageError("--size wants WxH, got " + v);
        cfg.size = cv::Size(toInt(a, v.substr(0, x)), toInt(a, v.substr(x + 1)));
      } else if (a == "--scenario") {
        cfg.name = value();
      } else if (a == "--seed") {
        cfg.seed = static_cast<std::uint64_t>(toInt(a, value()));
      } else if (a == "--warmup") {
        warmup = toInt(a, value());
      } else if (a == "--start") {
        start_count = toInt(a, value());
        if (start_count < 1 || start_count > 3) throw UsageError("--start must be 1, 2 or 3");
      } else if (a == "--budget-mib") {
        budget_mib = std::stod(value());
      } else if (a == "--help" || a == "-h") {
        std::cout << kUsage;
        return 0;
      } else {
        throw UsageError("unknown argument " + a);
      }
    }
    if (cfg.frames < 2) throw UsageError("--frames must be at least 2");
    if (warmup < 0 || warmup >= cfg.frames - 1) throw UsageError("--warmup must be in [0, frames - 2]");
  } catch (const UsageError& e) {
    std::cerr << "memory_probe: " << e.what() << "\n" << kUsage;
    return 2;
  }

  // 1. The scene, rendered completely before anything is measured.
  std::vector<cv::Mat> frames;
  std::vector<cv::Rect2f> start_boxes;
  double fps = 30.0;
  long long frame_bytes = 0;
  try {
    scene::SceneGenerator gen(cfg);
    fps = gen.fps();
    frames.resize(static_cast<std::size_t>(gen.frameCount()));
    scene::FrameTruth truth0;
    for (int i = 0; i < gen.frameCount(); ++i) {
      gen.renderFrame(i, frames[static_cast<std::size_t>(i)], i == 0 ? &truth0 : nullptr);
      frame_bytes += static_cast<long long>(frames[static_cast<std::size_t>(i)].total() *
                                            frames[static_cast<std::size_t>(i)].elemSize());
    }
    for (const auto& o : truth0.obstacles) {
      if (!o.distractor && o.visible && o.box.area() >= 1.0f) start_boxes.push_back(o.box);
    }
  } catch (const std::exception& e) {
    std::cerr << "memory_probe: scene " << cfg.name << ": " << e.what() << "\n";
    return 2;
  }
  malloc_trim(0);  // the generator's freed memory back to the system before the baseline

  std::cout << "memory_probe: scene " << cfg.name << " seed " << cfg.seed << ", " << frames.size() << " frames "
            << cfg.size.width << "x" << cfg.size.height << " CV_8UC3 rendered before measuring ("
            << mib(frame_bytes) << " of frame pixels)\n";
  if (start_boxes.size() != 3) {
    std::cerr << "memory_probe: the first frame of " << cfg.name << " has " << start_boxes.size()
              << " visible target boxes; three are needed (try --scenario multi)\n";
    return 1;
  }

  // 2. Baseline just before the Pipeline exists.
  const ProcStatus st0 = readStatus();
  const long long heap0 = heapInUse();
#ifdef OT_COUNT_ALLOCATIONS
  const long long live0 = g_live.load();
  g_peak.store(live0);
#endif
  long long heap_peak = 0, heap_warm = 0, heap_end = 0;
  ProcStatus st_warm;
  std::map<int, int> alive_hist;        // alive tracks -> frames (after warm-up)
  long calls_total = 0, calls_max = 0;
  int frames_with_calls = 0, counted_frames = 0, redetecting_frames = 0;
  std::vector<int> alloc_frames;        // first few frames that allocated
  int started = 0;
  {
    core::Params params;
    params.max_obstacles = 3;
    core::Pipeline pipeline(params);
    try {
      for (int k = 0; k < start_count; ++k) {
        const auto& out = pipeline.startTrack(frames[0], 0.0, start_boxes[static_cast<std::size_t>(k)]);
        started = static_cast<int>(out.size());
      }
    } catch (const std::exception& e) {
      std::cerr << "memory_probe: startTrack failed: " << e.what() << "\n";
      return 1;
    }
    if (started != start_count) {
      std::cerr << "memory_probe: after " << start_count << " startTrack calls the pipeline reports "
                << started << " tracks\n";
      return 1;
    }
    heap_peak = std::max(heap_peak, heapInUse() - heap0);
    for (std::size_t i = 1; i < frames.size(); ++i) {
      const bool count = static_cast<int>(i) > warmup;
#ifdef OT_COUNT_ALLOCATIONS
      const long before = g_calls.load();
      g_counting.store(count);
#endif
      const auto& out = pipeline.process(frames[i], static_cast<double>(i) / fps);
#ifdef OT_COUNT_ALLOCATIONS
      g_counting.store(false);
      const long calls = g_calls.load() - before;
#else
      const long calls = 0;
#endif
      int alive = 0;
      bool redetecting = false;
      for (const auto& o : out) {
        alive += o.state != core::TrackState::kLost ? 1 : 0;
        redetecting = redetecting || o.state == core::TrackState::kRedetecting;
      }
      heap_peak = std::max(heap_peak, heapInUse() - heap0);
      if (count) {
        ++counted_frames;
        ++alive_hist[alive];
        redetecting_frames += redetecting ? 1 : 0;
        calls_total += calls;
        calls_max = std::max(calls_max, calls);
        if (calls > 0) {
          ++frames_with_calls;
          if (alloc_frames.size() < 10) alloc_frames.push_back(static_cast<int>(i));
        }
      }
      if (static_cast<int>(i) == warmup || (warmup == 0 && i == 1)) {
        heap_warm = heapInUse() - heap0;
        st_warm = readStatus();
      }
    }
    heap_end = heapInUse() - heap0;
  }
  const ProcStatus st_end = readStatus();
  const long long heap_after = heapInUse() - heap0;  // after the Pipeline is destroyed

  // 3. Summary.
  const int three = alive_hist.count(3) ? alive_hist[3] : 0;
  std::cout << "pipeline: max_obstacles 3, " << started << " tracks started from the ground-truth boxes of frame 0, "
            << (frames.size() - 1) << " frames processed, warm-up " << warmup << " frames\n";
  std::cout << "heap (mallinfo2 in use, relative to just before the Pipeline):\n"
            << "  after warm-up          " << mib(heap_warm) << "\n"
            << "  at the end             " << mib(heap_end) << "\n"
            << "  peak after a frame     " << mib(heap_peak) << "\n"
            << "  after the destructor   " << mib(heap_after) << "\n";
#ifdef OT_COUNT_ALLOCATIONS
  const long long exact_peak = g_peak.load() - live0;
  std::cout << "  peak inside frames     " << mib(exact_peak) << " (live bytes counted by the allocator wrappers)\n";
#else
  const long long exact_peak = heap_peak;
#endif
  std::cout << "  frames (not the core)  " << mib(frame_bytes) << " of pixels, heap in use before the Pipeline "
            << mib(heap0) << "\n";
  std::cout << "process memory (/proc/self/status):\n"
            << "  VmRSS before " << kibAsMib(st0.rss_kib) << ", after warm-up " << kibAsMib(st_warm.rss_kib)
            << ", at the end " << kibAsMib(st_end.rss_kib) << "; delta " << kibAsMib(st_end.rss_kib - st0.rss_kib)
            << " (after warm-up " << kibAsMib(st_warm.rss_kib - st0.rss_kib) << ")\n"
            << "  VmHWM before " << kibAsMib(st0.hwm_kib) << ", at the end " << kibAsMib(st_end.hwm_kib)
            << "; delta " << kibAsMib(st_end.hwm_kib - st0.hwm_kib) << "\n";
#ifdef OT_COUNT_ALLOCATIONS
  std::cout << "allocation calls after warm-up (malloc, calloc, realloc, posix_memalign, aligned_alloc, memalign):\n"
            << "  " << calls_total << " in " << counted_frames << " frames = "
            << static_cast<double>(calls_total) / std::max(1, counted_frames) << " per frame; max "
            << calls_max << " in one frame; " << frames_with_calls << " frames allocated";
  if (!alloc_frames.empty()) {
    std::cout << " (first:";
    for (int f : alloc_frames) std::cout << " " << f;
    std::cout << ")";
  }
  std::cout << "\n";
#else
  std::cout << "allocation calls: not counted (sanitizer build or no glibc: the sanitizer interposes malloc)\n";
#endif
  std::cout << "tracks alive (tracking or re-detecting) after warm-up:";
  for (const auto& kv : alive_hist) std::cout << " " << kv.first << ": " << kv.second << " frames;";
  std::cout << " three tracks in " << three << " of " << counted_frames << " frames; a track re-detecting in "
            << redetecting_frames << " frames\n";

  bool ok = true;
  const long long budget = static_cast<long long>(budget_mib * kMiB);
  if (std::max(heap_peak, exact_peak) > budget) {
    std::cout << "FAIL: core heap peak over the budget of " << budget_mib << " MiB\n";
    ok = false;
  }
  if (2 * three < counted_frames) {
    std::cout << "FAIL: three tracks alive in fewer than half of the frames after warm-up\n";
    ok = false;
  }
#ifdef OT_COUNT_ALLOCATIONS
  if (calls_total > 0) {
    std::cout << "FAIL: the pipeline allocates after warm-up\n";
    ok = false;
  }
#endif
  std::cout << (ok ? "OK: all memory targets met\n" : "memory targets missed\n");
  return ok ? 0 : 1;
}
