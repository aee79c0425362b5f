// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/markdown_report.h"

#include <algorithm>
#include <ctime>
#include <string>
#include <vector>

#include "evaluate/machine.h"
#include "evaluate/number_format.h"
#include "obstacle_tracker/eval/metrics.h"

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

// Frames from the target's first frame in view within which a start counts (the
// auto-initialisation target), for both counts: any box within 20 px, and the first box.
constexpr int kStartWithinFrames = 30;

std::string nowUtc() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof(buf), "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buf;
}

// "| first | tracker... |" and its separator line; `columns` of "---|" before the trackers'.
void writeTrackerTableHead(std::ostream& md, const std::string& first, int columns,
                           const std::vector<std::string>& trackers) {
  md << first;
  for (const auto& t : trackers) md << " " << t << " |";
  md << "\n|";
  for (int i = 0; i < columns; ++i) md << "---|";
  for (size_t t = 0; t < trackers.size(); ++t) md << "---|";
  md << "\n";
}

int trackerIndex(const std::vector<std::string>& trackers, const std::string& name) {
  for (size_t t = 0; t < trackers.size(); ++t)
    if (trackers[t] == name) return static_cast<int>(t);
  return -1;
}

void writeHeader(std::ostream& md, const EvaluateOptions& options, const EvaluationResults& res) {
  md << "# Evaluation results\n\n"
     << "`" << options.command << "`  \n"
     << "Machine: " << machineDescription() << "  \n"
     << nowUtc() << "; " << res.seqs.size() << " sequences; " << options.jobs
     << " parallel job(s), each single-threaded; "
     << "OTB precision at 20 px / success AUC (21 IoU thresholds), means over sequences; fps = frames per "
        "second of the tracker's own per-frame call (decode excluded), geometric mean over sequences. "
        "OpenCV trackers start from the first ground-truth box and keep their last box after a failed "
        "update; ours-gt starts from the same box; ours-auto starts by itself.\n\n";
}

// One row of an overall table; OPE rows add the error, fps and the speed against KCF and CSRT.
void writeOverallRow(std::ostream& md, const EvaluationResults& res, bool ope, size_t t, int kcf, int csrt) {
  md << "| " << res.trackers[t] << " |";
  for (size_t u = 0; u < res.subsets.size(); ++u) {
    const eval::OtbScores& sc = ope ? res.summaries[u][t].ope : res.summaries[u][t].tre;
    md << " " << formatNumber(sc.precision20) << " / " << formatNumber(sc.auc) << " |";
  }
  if (ope) {
    const std::vector<SubsetSummary>& all = res.summaries[0];
    const SubsetSummary& a = all[t];
    md << " " << formatNumber(a.ope.mean_centre_error, 1) << " | " << formatFps(a.fps) << " |";
    if (kcf >= 0) md << " " << (all[kcf].fps > 0 ? formatNumber(a.fps / all[kcf].fps, 2) : "-") << " |";
    if (csrt >= 0) md << " " << (all[csrt].fps > 0 ? formatNumber(a.fps / all[csrt].fps, 2) : "-") << " |";
  }
  md << "\n";
}

// "## Overall" for OPE and, with --tre, for TRE.
void writeOverall(std::ostream& md, const EvaluateOptions& options, const EvaluationResults& res) {
  const int kcf = trackerIndex(res.trackers, "KCF"), csrt = trackerIndex(res.trackers, "CSRT");
  for (int mode = 0; mode < (res.tre ? 2 : 1); ++mode) {
    const bool ope = mode == 0;
    md << "## Overall (" << (ope ? "OPE" : "TRE, " + std::to_string(options.tre_segments) + " start frames, pooled")
       << ")\n\n| tracker |";
    for (const auto& sub : res.subsets) md << " " << sub.name << " (" << sub.seqs.size() << "): P@20 / AUC |";
    if (ope) {
      md << " mean centre error (px) | fps |";
      if (kcf >= 0) md << " x KCF |";
      if (csrt >= 0) md << " x CSRT |";
    }
    md << "\n|---|";
    for (size_t u = 0; u < res.subsets.size(); ++u) md << "---|";
    if (ope) md << "---|---|" << (kcf >= 0 ? "---|" : "") << (csrt >= 0 ? "---|" : "");
    md << "\n";
    for (size_t t = 0; t < res.trackers.size(); ++t) writeOverallRow(md, res, ope, t, kcf, csrt);
    md << "\n";
  }
}

// Per sequence: precision@20 / AUC, then fps with the slowest frame.
void writePerSequence(std::ostream& md, const EvaluationResults& res) {
  writeTrackerTableHead(md, "## Per sequence (OPE): precision@20 / AUC\n\n| sequence | frames |", 2, res.trackers);
  for (size_t s = 0; s < res.seqs.size(); ++s) {
    md << "| " << res.seqs[s].name << " | " << res.seqs[s].frames << " |";
    for (size_t t = 0; t < res.trackers.size(); ++t) {
      const ScoreCell& c = res.cells[s][t];
      md << " " << (c.done ? formatNumber(c.ope.precision20) + " / " + formatNumber(c.ope.auc) : "-") << " |";
    }
    md << "\n";
  }
  writeTrackerTableHead(md, "\n## Per sequence (OPE): fps (slowest frame, ms)\n\n| sequence |", 1, res.trackers);
  for (size_t s = 0; s < res.seqs.size(); ++s) {
    md << "| " << res.seqs[s].name << " |";
    for (size_t t = 0; t < res.trackers.size(); ++t)
      md << " " << formatFps(res.cells[s][t].fps) << " (" << formatNumber(res.cells[s][t].ms_max, 1) << ") |";
    md << "\n";
  }
  md << "\n";
}

// "error px @ frame" of the first box (sense and avoid table); "-" when there was none.
std::string firstBoxCell(const eval::SenseAvoidScores& sa) {
  if (sa.first_box_frame < 0) return "-";
  return formatDistance(sa.first_box_error, 1) + " px @ " + std::to_string(sa.first_box_frame);
}

// A subset's row of the sense and avoid table: means, clips started in time, worst false confident rate.
void writeSenseAvoidMeans(std::ostream& md, const EvaluationResults& res, const Subset& sub) {
  md << "| **mean: " << sub.name << "** (state acc. / started within " << kStartWithinFrames
     << " frames: a box, the first box / mean, worst false confident) |";
  for (size_t t = 0; t < res.trackers.size(); ++t) {
    double sa = 0.0, fcr = 0.0, worst = 0.0;
    int n = 0, started = 0, first_right = 0;
    for (size_t s : sub.seqs) {
      const ScoreCell& c = res.cells[s][t];
      if (!c.done) continue;
      ++n;
      sa += c.sa.state_accuracy;
      fcr += c.sa.false_confident_rate;
      worst = std::max(worst, c.sa.false_confident_rate);
      // Counted from the target's first frame in view (it may enter late).
      started += (c.sa.first_correct_frame >= 0 &&
                  c.sa.first_correct_frame - c.sa.first_present_frame < kStartWithinFrames) ? 1 : 0;
      first_right += eval::firstBoxCorrect(c.sa, kStartWithinFrames) ? 1 : 0;
    }
    if (n == 0) {
      md << " - |";
      continue;
    }
    md << " " << formatNumber(sa / n) << " / " << started << ", " << first_right << " of " << n << " / "
       << formatNumber(100.0 * fcr / n, 1) << " %, " << formatNumber(100.0 * worst, 1) << " % |";
  }
  md << "\n";
}

// The "Sense and avoid" section: per sequence and tracker the Anti-UAV state accuracy, the frame of
// the first correct box and the false confident rate (metrics.h); then a row per subset.
void writeSenseAvoid(std::ostream& md, const EvaluationResults& res) {
  writeTrackerTableHead(
      md,
      "## Sense and avoid (OPE): state accuracy / first correct frame / first box / false confident rate\n\n"
      "State accuracy as Anti-UAV (IoU where the target is present, 1 for no box where it is absent); first "
      "correct frame: the first frame with a box within 20 px of the target (- never); first box: the centre "
      "error @ frame of the first box reported at all (- never a box, inf: the target was not in view there), "
      "which a later correct box does not undo; false confident rate: frames with a box of confidence >= 0.5 and "
      "IoU 0 (or no target), over all frames.\n\n| sequence |",
      1, res.trackers);
  for (size_t s = 0; s < res.seqs.size(); ++s) {
    md << "| " << res.seqs[s].name << " |";
    for (size_t t = 0; t < res.trackers.size(); ++t) {
      const ScoreCell& c = res.cells[s][t];
      if (!c.done) {
        md << " - |";
        continue;
      }
      md << " " << formatNumber(c.sa.state_accuracy) << " / "
         << (c.sa.first_correct_frame < 0 ? std::string("-") : std::to_string(c.sa.first_correct_frame)) << " / "
         << firstBoxCell(c.sa) << " / "
         << formatNumber(100.0 * c.sa.false_confident_rate, 1) << " % |";
    }
    md << "\n";
  }
  for (const auto& sub : res.subsets) writeSenseAvoidMeans(md, res, sub);
  md << "\n";
}

// Only when some sequence has absent frames.
void writeLongTerm(std::ostream& md, const EvaluationResults& res) {
  const bool any_lt = std::any_of(res.seqs.begin(), res.seqs.end(),
                                  [](const SequenceInfo& s) { return s.absent_frames > 0; });
  if (!any_lt) return;
  writeTrackerTableHead(md,
                        "## Long-term (sequences with absent frames; VOT LT precision / recall / F at the best "
                        "confidence threshold)\n\n| sequence | absent frames |",
                        2, res.trackers);
  for (size_t s = 0; s < res.seqs.size(); ++s) {
    if (res.seqs[s].absent_frames == 0) continue;
    md << "| " << res.seqs[s].name << " | " << res.seqs[s].absent_frames << " |";
    for (size_t t = 0; t < res.trackers.size(); ++t) {
      const ScoreCell& c = res.cells[s][t];
      md << " "
         << (c.has_lt ? formatNumber(c.lt.precision) + " / " + formatNumber(c.lt.recall) + " / " +
                            formatNumber(c.lt.fscore)
                      : "-")
         << " |";
    }
    md << "\n";
  }
  md << "\n";
}

void writeErrors(std::ostream& md, const EvaluationResults& res) {
  if (res.errors == 0) return;
  md << "## Errors\n\n";
  for (size_t s = 0; s < res.seqs.size(); ++s)
    for (size_t t = 0; t < res.trackers.size(); ++t)
      if (!res.cells[s][t].error.empty())
        md << "- " << res.seqs[s].name << " / " << res.trackers[t] << ": " << res.cells[s][t].error << "\n";
  md << "\n";
}

}  // namespace

void writeResultsMarkdown(std::ostream& md, const EvaluateOptions& options, const EvaluationResults& res) {
  writeHeader(md, options, res);
  writeOverall(md, options, res);
  writePerSequence(md, res);
  writeSenseAvoid(md, res);
  writeLongTerm(md, res);
  writeErrors(md, res);
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
