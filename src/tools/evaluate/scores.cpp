// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/scores.h"

#include <algorithm>
#include <cmath>

namespace ev = obstacle_tracker::eval;

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

double percentileOf(std::vector<float> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double k = (v.size() - 1) * q / 100.0;
  const size_t lo = static_cast<size_t>(std::floor(k)), hi = static_cast<size_t>(std::ceil(k));
  return v[lo] + (v[hi] - v[lo]) * (k - lo);
}

double geometricMean(const std::vector<double>& v) {
  double s = 0.0;
  int n = 0;
  for (double x : v) {
    if (x > 0.0 && std::isfinite(x)) {
      s += std::log(x);
      ++n;
    }
  }
  return n > 0 ? std::exp(s / n) : 0.0;
}

// The OPE scores of a run from frame 0.
void scoreOpeRun(const ev::RunResult& r, const ev::FrameErrors& fe, bool has_absent_frames, ScoreCell* c) {
  c->done = true;
  c->ope = ev::otbScores(fe);
  c->fps = r.fps();
  c->ms_p99 = percentileOf(r.frame_ms, 99.0);
  c->ms_max = percentileOf(r.frame_ms, 100.0);
  c->sa = ev::senseAvoidScores(r.boxes, r.confidence, r.gt);
  if (has_absent_frames) {
    c->has_lt = true;
    c->lt = ev::longTermScores(r.boxes, r.confidence, r.gt);
  }
}

// Fills res->cells and res->errors from the runs.
void scoreCells(const RunPlan& plan, const std::vector<ev::RunResult>& results, EvaluationResults* res) {
  const size_t S = res->seqs.size(), T = res->trackers.size();
  res->cells.assign(S, std::vector<ScoreCell>(T));
  std::vector<std::vector<ev::FrameErrors>> tre_pool(S, std::vector<ev::FrameErrors>(T));
  for (size_t k = 0; k < plan.tasks.size(); ++k) {
    const RunTask& task = plan.tasks[k];
    const ev::RunResult& r = results[k];
    ScoreCell& c = res->cells[task.seq][task.tracker];
    if (!r.error.empty()) {
      ++res->errors;
      c.error = r.error;
    }
    if (r.boxes.empty()) continue;
    const ev::FrameErrors fe = ev::frameErrors(r.boxes, r.gt);
    tre_pool[task.seq][task.tracker].append(fe);
    c.pooled_update_seconds += r.update_seconds;
    c.pooled_timed_frames += r.timed_frames;
    if (task.start == 0) scoreOpeRun(r, fe, res->seqs[task.seq].absent_frames > 0, &c);
  }
  if (!res->tre) return;
  for (size_t s = 0; s < S; ++s) {
    for (size_t t = 0; t < T; ++t) {
      res->cells[s][t].has_tre = true;
      res->cells[s][t].tre = ev::otbScores(tre_pool[s][t]);
    }
  }
}

// Subsets: all, and the flying clips when there are any (and not all of them are).
std::vector<Subset> makeSubsets(const std::vector<SequenceInfo>& seqs) {
  std::vector<Subset> subsets{{"all", {}}};
  Subset flying{"flying", {}};
  for (size_t s = 0; s < seqs.size(); ++s) {
    subsets[0].seqs.push_back(s);
    if (ev::isFlyingSequence(seqs[s].name)) flying.seqs.push_back(s);
  }
  if (!flying.seqs.empty() && flying.seqs.size() < seqs.size()) subsets.push_back(flying);
  return subsets;
}

SubsetSummary summarise(const EvaluationResults& res, const Subset& sub, size_t t) {
  SubsetSummary m;
  std::vector<ev::OtbScores> o, r;
  std::vector<double> fps;
  for (size_t s : sub.seqs) {
    const ScoreCell& c = res.cells[s][t];
    if (!c.done) continue;
    o.push_back(c.ope);
    if (c.has_tre) r.push_back(c.tre);
    fps.push_back(c.fps);
    if (c.has_lt) {
      ++m.lt_n;
      m.lt_p += c.lt.precision;
      m.lt_r += c.lt.recall;
      m.lt_f += c.lt.fscore;
    }
  }
  m.ope = ev::meanOtbScores(o);
  m.tre = ev::meanOtbScores(r);
  m.fps = geometricMean(fps);
  if (m.lt_n > 0) {
    m.lt_p /= m.lt_n;
    m.lt_r /= m.lt_n;
    m.lt_f /= m.lt_n;
  }
  return m;
}

}  // namespace

EvaluationResults scoreRuns(const RunPlan& plan, const std::vector<ev::RunResult>& results,
                            const std::vector<SequenceInfo>& seqs, const std::vector<std::string>& trackers,
                            bool tre) {
  EvaluationResults res;
  res.seqs = seqs;
  res.trackers = trackers;
  res.tre = tre;
  scoreCells(plan, results, &res);
  res.subsets = makeSubsets(seqs);
  res.summaries.assign(res.subsets.size(), std::vector<SubsetSummary>(trackers.size()));
  for (size_t u = 0; u < res.subsets.size(); ++u)
    for (size_t t = 0; t < trackers.size(); ++t) res.summaries[u][t] = summarise(res, res.subsets[u], t);
  return res;
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
