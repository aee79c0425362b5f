// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/runs.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <iostream>
#include <mutex>
#include <thread>

#include "evaluate/number_format.h"
#include "obstacle_tracker/eval/metrics.h"

namespace ev = obstacle_tracker::eval;

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

// Relative per-frame cost, only to start the slow tasks first.
double trackerCost(const std::string& t) {
  if (t == "MIL") return 4.0;
  if (t == "CSRT") return 2.5;
  if (t == "MedianFlow") return 0.6;
  return 0.5;
}

// What the jobs share: the next task to take, the counters and the log.
struct JobPool {
  std::atomic<size_t> next_task{0};
  std::atomic<int> frames_done{0};
  std::atomic<size_t> tasks_done{0};
  std::mutex log_mutex;
  std::condition_variable finished_cv;
};

ev::RunResult runTask(const RunTask& task, const SequenceInfo& si, const std::string& tracker,
                      const core::Params& params, std::atomic<int>* frames_done) {
  ev::RunResult r;
  try {
    r = ev::runTracker(si.path, tracker, params, task.start, frames_done, si.gt_path);
  } catch (const std::exception& e) {
    r.sequence = si.name;
    r.tracker = tracker;
    r.start_frame = task.start;
    r.error = e.what();
  }
  return r;
}

// One line per finished run; the caller holds the log mutex.
void logRunDone(size_t done, size_t total, const RunTask& task, const std::string& sequence,
                const std::string& tracker, const ev::RunResult& rr) {
  std::cerr << "[" << done << "/" << total << "] " << sequence << " " << tracker;
  if (task.start > 0) std::cerr << " (from frame " << task.start << ")";
  if (!rr.boxes.empty()) {
    const ev::OtbScores sc = ev::otbScores(rr.boxes, rr.gt);
    std::cerr << ": P@20 " << formatNumber(sc.precision20) << " AUC " << formatNumber(sc.auc) << " "
              << formatFps(rr.fps()) << " fps";
  }
  if (!rr.error.empty()) std::cerr << "  ERROR: " << rr.error;
  std::cerr << "\n";
}

// Until every task is done: a progress line whenever 15 s pass without a run finishing.
void waitAndReportProgress(JobPool& pool, const RunPlan& plan, std::chrono::steady_clock::time_point started) {
  const size_t total = plan.tasks.size();
  std::unique_lock<std::mutex> lock(pool.log_mutex);
  while (pool.tasks_done.load() < total) {
    pool.finished_cv.wait_for(lock, std::chrono::seconds(15));
    if (pool.tasks_done.load() < total) {
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      std::cerr << "evaluate: " << pool.frames_done.load() << "/" << plan.total_frames << " frames, "
                << pool.tasks_done.load() << "/" << total << " runs, " << formatNumber(el, 0) << " s\n";
    }
  }
}

}  // namespace

RunPlan planRuns(const std::vector<SequenceInfo>& seqs, const std::vector<std::string>& trackers) {
  RunPlan plan;
  for (size_t s = 0; s < seqs.size(); ++s) {
    for (size_t t = 0; t < trackers.size(); ++t) {
      for (int start : seqs[s].starts) {
        const int frames = seqs[s].frames - start;
        plan.tasks.push_back({s, t, start, frames * trackerCost(trackers[t])});
        plan.total_frames += frames;
      }
    }
  }
  std::stable_sort(plan.tasks.begin(), plan.tasks.end(),
                   [](const RunTask& a, const RunTask& b) { return a.cost > b.cost; });
  return plan;
}

std::vector<ev::RunResult> runAll(const RunPlan& plan, const std::vector<SequenceInfo>& seqs,
                                  const std::vector<std::string>& trackers, const core::Params& params,
                                  int jobs, std::chrono::steady_clock::time_point started) {
  const std::vector<RunTask>& tasks = plan.tasks;
  std::vector<ev::RunResult> results(tasks.size());
  JobPool pool;
  auto worker = [&]() {
    for (;;) {
      const size_t k = pool.next_task.fetch_add(1);
      if (k >= tasks.size()) return;
      const RunTask& task = tasks[k];
      const SequenceInfo& si = seqs[task.seq];
      results[k] = runTask(task, si, trackers[task.tracker], params, &pool.frames_done);
      const size_t done = pool.tasks_done.fetch_add(1) + 1;
      std::lock_guard<std::mutex> lock(pool.log_mutex);
      logRunDone(done, tasks.size(), task, si.name, trackers[task.tracker], results[k]);
      pool.finished_cv.notify_all();
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < std::min<int>(jobs, static_cast<int>(tasks.size())); ++j) threads.emplace_back(worker);
  waitAndReportProgress(pool, plan, started);
  for (auto& th : threads) th.join();
  return results;
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
