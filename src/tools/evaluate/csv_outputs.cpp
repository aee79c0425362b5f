// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "evaluate/csv_outputs.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

#include "evaluate/number_format.h"
#include "obstacle_tracker/eval/metrics.h"

namespace fs = std::filesystem;
namespace ev = obstacle_tracker::eval;

namespace obstacle_tracker {
namespace evaluate_tool {
namespace {

// The first box's centre error: "inf" when the target was not in view there, -1 when no box.
std::string firstBoxError(const ev::SenseAvoidScores& sa) {
  if (sa.first_box_frame < 0 && !std::isinf(sa.first_box_error)) return "-1";
  return formatDistance(sa.first_box_error, 2);
}

void writeResultsRow(std::ostream& f, const std::string& seq, const std::string& trk, const std::string& mode,
                     int frames, const ev::OtbScores& sc, double fps, const std::string& lt, const std::string& ms,
                     const std::string& sa = ",,,,") {
  f << seq << "," << trk << "," << mode << "," << frames << "," << sc.frames << "," << formatNumber(sc.precision20, 4)
    << "," << formatNumber(sc.auc, 4) << "," << formatNumber(sc.mean_centre_error, 2) << ","
    << formatNumber(sc.lost_fraction, 4) << "," << formatNumber(fps, 1) << "," << lt << "," << ms << "," << sa
    << "\n";
}

void writeSequenceRows(std::ostream& f, const EvaluationResults& res) {
  for (size_t s = 0; s < res.seqs.size(); ++s) {
    const SequenceInfo& seq = res.seqs[s];
    for (size_t t = 0; t < res.trackers.size(); ++t) {
      const ScoreCell& c = res.cells[s][t];
      if (!c.done) continue;
      const std::string lt = c.has_lt ? formatNumber(c.lt.precision, 4) + "," + formatNumber(c.lt.recall, 4) + "," +
                                            formatNumber(c.lt.fscore, 4) + "," + formatNumber(c.lt.threshold, 4)
                                      : ",,,";
      writeResultsRow(f, seq.name, res.trackers[t], "OPE", seq.frames, c.ope, c.fps, lt,
                      formatNumber(c.ms_p99, 2) + "," + formatNumber(c.ms_max, 2),
                      formatNumber(c.sa.state_accuracy, 4) + "," + std::to_string(c.sa.first_correct_frame) + "," +
                          formatNumber(c.sa.false_confident_rate, 4) + "," + std::to_string(c.sa.first_box_frame) +
                          "," + firstBoxError(c.sa));
      if (c.has_tre) {
        const double fps =
            c.pooled_update_seconds > 0 ? c.pooled_timed_frames / c.pooled_update_seconds : 0.0;
        writeResultsRow(f, seq.name, res.trackers[t], "TRE", seq.frames, c.tre, fps, ",,,", ",");
      }
    }
  }
}

void writeCurves(std::ostream& f, const std::string& mode, const std::string& seq, const std::string& trk,
                 const ev::OtbScores& sc) {
  for (size_t i = 0; i < sc.precision.size(); ++i)
    f << mode << "," << seq << "," << trk << ",precision," << ev::precisionThreshold(int(i)) << ","
      << formatNumber(sc.precision[i], 5) << "\n";
  for (size_t i = 0; i < sc.success.size(); ++i)
    f << mode << "," << seq << "," << trk << ",success," << formatNumber(ev::successThreshold(int(i)), 2) << ","
      << formatNumber(sc.success[i], 5) << "\n";
}

void writeBoxFile(const fs::path& path, const ev::RunResult& r) {
  std::ofstream bf(path);
  bf << std::fixed;
  for (size_t f = 0; f < r.boxes.size(); ++f) {
    const cv::Rect2f& b = r.boxes[f];
    if (ev::isAbsent(b)) {
      bf << "0,0,0,0," << std::setprecision(4) << r.confidence[f] << "\n";
    } else {
      // Four decimals: score_boxes must score the same boxes from the file (40-evaluate checks
      // it), and at 0.01 px a rounded box crosses an IoU threshold now and then.
      bf << std::setprecision(4) << b.x << "," << b.y << "," << b.width << "," << b.height << ","
         << std::setprecision(4) << r.confidence[f] << "\n";
    }
  }
}

}  // namespace

void writeResultsCsv(const std::string& out, const EvaluationResults& res) {
  std::ofstream f(fs::path(out) / "results.csv");
  f << "sequence,tracker,mode,frames,gt_frames,precision20,auc,mean_centre_error,lost_fraction,fps,"
       "lt_precision,lt_recall,lt_fscore,lt_threshold,frame_ms_p99,frame_ms_max,state_accuracy,"
       "first_correct_frame,false_confident_rate,first_box_frame,first_box_error\n";
  writeSequenceRows(f, res);
  for (size_t u = 0; u < res.subsets.size(); ++u) {
    const std::string name = "mean:" + res.subsets[u].name;
    for (size_t t = 0; t < res.trackers.size(); ++t) {
      const SubsetSummary& m = res.summaries[u][t];
      const std::string lt = m.lt_n > 0 ? formatNumber(m.lt_p, 4) + "," + formatNumber(m.lt_r, 4) + "," +
                                              formatNumber(m.lt_f, 4) + ","
                                        : ",,,";
      writeResultsRow(f, name, res.trackers[t], "OPE", 0, m.ope, m.fps, lt, ",");
      if (res.tre) writeResultsRow(f, name, res.trackers[t], "TRE", 0, m.tre, m.fps, ",,,", ",");
    }
  }
}

void writeCurvesCsv(const std::string& out, const EvaluationResults& res) {
  std::ofstream f(fs::path(out) / "curves.csv");
  f << "mode,sequence,tracker,curve,threshold,value\n";
  for (size_t u = 0; u < res.subsets.size(); ++u) {
    for (size_t t = 0; t < res.trackers.size(); ++t) {
      writeCurves(f, "OPE", "mean:" + res.subsets[u].name, res.trackers[t], res.summaries[u][t].ope);
      if (res.tre) writeCurves(f, "TRE", "mean:" + res.subsets[u].name, res.trackers[t], res.summaries[u][t].tre);
    }
  }
  for (size_t s = 0; s < res.seqs.size(); ++s) {
    for (size_t t = 0; t < res.trackers.size(); ++t) {
      const ScoreCell& c = res.cells[s][t];
      if (!c.done) continue;
      writeCurves(f, "OPE", res.seqs[s].name, res.trackers[t], c.ope);
      if (res.tre) writeCurves(f, "TRE", res.seqs[s].name, res.trackers[t], c.tre);
    }
  }
}

void writeBoxFiles(const std::string& out, const RunPlan& plan, const std::vector<ev::RunResult>& results,
                   const EvaluationResults& res) {
  const fs::path boxes_dir = fs::path(out) / "boxes";
  for (size_t k = 0; k < plan.tasks.size(); ++k) {
    const RunTask& task = plan.tasks[k];
    if (results[k].boxes.empty() || task.start != 0) continue;
    const fs::path d = boxes_dir / res.seqs[task.seq].name;
    fs::create_directories(d);
    writeBoxFile(d / (res.trackers[task.tracker] + ".txt"), results[k]);
  }
}

}  // namespace evaluate_tool
}  // namespace obstacle_tracker
