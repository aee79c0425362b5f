// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// evaluate --data DIR --out DIR [--trackers a,b,...] [--jobs N] [--tre] [--tre-segments N]
//          [--params FILE] [--sequences a,b] [--gt FILE] [--no-plots] [--plot-script FILE]
//
// Runs every sequence of DIR (each subfolder in OTB layout; DIR itself when it is one sequence;
// or a single video file, with --gt or a ground-truth file next to it) with every tracker, in
// parallel jobs over (sequence, tracker, start frame) tasks, each job single-threaded. Scores:
// OTB precision (0-50 px, @20) and success (21 IoU thresholds, AUC), mean centre error, OPE and
// with --tre OTB's TRE (restarts from evenly spaced frames, frames pooled); VOT long-term
// precision / recall / F for sequences with absent frames; frames per second of the tracker's own
// per-frame call (decode excluded). Writes OUT/results.csv, OUT/results.md, OUT/curves.csv,
// OUT/boxes/<sequence>/<tracker>.txt (x,y,w,h,confidence per frame, OPE) and, when python3 with
// matplotlib is there, precision/success plots (scripts/plot_results.py) as PNG.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/eval/runner.h"
#include "obstacle_tracker/eval/sequence.h"

namespace fs = std::filesystem;
namespace ev = obstacle_tracker::eval;
using obstacle_tracker::core::Params;

namespace {

const char* kUsage =
    "usage: evaluate --data DIR|VIDEO --out DIR [--trackers a,b,...] [--jobs N] [--tre]\n"
    "                [--tre-segments N] [--params FILE] [--sequences a,b] [--gt FILE]\n"
    "                [--no-plots] [--plot-script FILE]\n";

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

struct SequenceInfo {
  std::string name, path, gt_path;
  int frames = 0;
  int absent_frames = 0;
  std::vector<int> starts;  // run start frames: {0} (OPE) then the TRE starts
};

bool hasGroundTruthFile(const fs::path& dir) {
  return fs::exists(dir / "groundtruth_rect.txt") || fs::exists(dir / "groundtruth.txt");
}

// The sequences under --data: a video file, a folder that is itself a sequence, or a folder of
// sequence folders (those without ground truth are skipped with a message).
std::vector<SequenceInfo> discover(const std::string& data, const std::string& gt_path) {
  std::vector<SequenceInfo> seqs;
  const fs::path root(data);
  if (!fs::exists(root)) throw std::runtime_error("--data " + data + " does not exist");
  if (fs::is_regular_file(root) || hasGroundTruthFile(root) || !gt_path.empty()) {
    SequenceInfo one;
    one.path = data;
    one.gt_path = gt_path;
    // generate_scene writes a video's ground truth as <stem>_groundtruth_rect.txt beside it.
    const fs::path scene_gt = root.parent_path() / (root.stem().string() + "_groundtruth_rect.txt");
    if (one.gt_path.empty() && fs::is_regular_file(root) && fs::is_regular_file(scene_gt)) {
      one.gt_path = scene_gt.string();
    }
    seqs.push_back(one);
    return seqs;
  }
  std::vector<fs::path> dirs;
  for (const auto& e : fs::directory_iterator(root)) {
    if (e.is_directory()) dirs.push_back(e.path());
  }
  std::sort(dirs.begin(), dirs.end());
  for (const auto& d : dirs) {
    if (!hasGroundTruthFile(d)) {
      std::cerr << "evaluate: skipping " << d.string() << " (no groundtruth_rect.txt)\n";
      continue;
    }
    SequenceInfo one;
    one.path = d.string();
    seqs.push_back(one);
  }
  if (seqs.empty()) throw std::runtime_error("no sequence with ground truth under " + data);
  return seqs;
}

struct Task {
  size_t seq, tracker;
  int start;
  double cost;
};

// Relative per-frame cost, only to start the slow tasks first.
double trackerCost(const std::string& t) {
  if (t == "MIL") return 4.0;
  if (t == "CSRT") return 2.5;
  if (t == "MedianFlow") return 0.6;
  return 0.5;
}

std::string fmt(double v, int prec = 3) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream os;
  os << std::fixed << std::setprecision(prec) << v;
  return os.str();
}

std::string fmtFps(double v) {
  if (!(v > 0.0) || !std::isfinite(v)) return "-";
  return fmt(v, v >= 100.0 ? 0 : 1);
}

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

struct Cell {  // one (sequence, tracker)
  bool done = false;
  ev::OtbScores ope, tre;
  bool has_tre = false;
  double fps = 0.0;
  double ms_p99 = 0.0, ms_max = 0.0;  // per-frame time of the tracker's call
  bool has_lt = false;
  ev::LongTermScores lt;
  ev::SenseAvoidScores sa;
  std::string error;
};

// Frames within which a correct first box counts as a start (the auto-initialisation target).
constexpr int kStartWithinFrames = 30;

// The "Sense and avoid" section of results.md: per sequence and tracker the Anti-UAV state
// accuracy, the frame of the first correct box and the false confident rate (metrics.h); per
// subset the means, the worst false confident rate and the clips started within 30 frames.
void writeSenseAvoid(std::ostream& md, const std::vector<std::string>& seq_names,
                     const std::vector<std::string>& trackers, const std::vector<std::vector<Cell>>& cells,
                     const std::vector<std::pair<std::string, std::vector<size_t>>>& subsets) {
  md << "## Sense and avoid (OPE): state accuracy / first correct frame / false confident rate\n\n"
        "State accuracy as Anti-UAV (IoU where the target is present, 1 for no box where it is absent); first "
        "correct frame: the first box within 20 px of the target (- never); false confident rate: frames with a "
        "box of confidence >= 0.5 and IoU 0 (or no target), over all frames.\n\n| sequence |";
  for (const auto& t : trackers) md << " " << t << " |";
  md << "\n|---|";
  for (size_t t = 0; t < trackers.size(); ++t) md << "---|";
  md << "\n";
  for (size_t s = 0; s < seq_names.size(); ++s) {
    md << "| " << seq_names[s] << " |";
    for (size_t t = 0; t < trackers.size(); ++t) {
      const Cell& c = cells[s][t];
      if (!c.done) {
        md << " - |";
        continue;
      }
      md << " " << fmt(c.sa.state_accuracy) << " / "
         << (c.sa.first_correct_frame < 0 ? std::string("-") : std::to_string(c.sa.first_correct_frame)) << " / "
         << fmt(100.0 * c.sa.false_confident_rate, 1) << " % |";
    }
    md << "\n";
  }
  for (const auto& sub : subsets) {
    md << "| **mean: " << sub.first << "** (state acc. / started within " << kStartWithinFrames
       << " frames / mean, worst false confident) |";
    for (size_t t = 0; t < trackers.size(); ++t) {
      double sa = 0.0, fcr = 0.0, worst = 0.0;
      int n = 0, started = 0;
      for (size_t s : sub.second) {
        const Cell& c = cells[s][t];
        if (!c.done) continue;
        ++n;
        sa += c.sa.state_accuracy;
        fcr += c.sa.false_confident_rate;
        worst = std::max(worst, c.sa.false_confident_rate);
        // Counted from the target's first frame in view (it may enter late).
        started += (c.sa.first_correct_frame >= 0 &&
                    c.sa.first_correct_frame - c.sa.first_present_frame < kStartWithinFrames) ? 1 : 0;
      }
      if (n == 0) {
        md << " - |";
        continue;
      }
      md << " " << fmt(sa / n) << " / " << started << " of " << n << " / " << fmt(100.0 * fcr / n, 1) << " %, "
         << fmt(100.0 * worst, 1) << " % |";
    }
    md << "\n";
  }
  md << "\n";
}

std::string nowUtc() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof(buf), "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buf;
}

std::string findPlotScript(const std::string& given, const char* argv0) {
  std::vector<fs::path> candidates;
  if (!given.empty()) candidates.emplace_back(given);
  if (const char* env = std::getenv("OT_PLOT_SCRIPT")) candidates.emplace_back(env);
  // This file is src/tools/evaluate.cpp; CMake compiles it by absolute path.
  candidates.push_back(fs::path(__FILE__).parent_path().parent_path().parent_path() / "scripts" /
                       "plot_results.py");
  std::error_code ec;
  const fs::path exe = fs::canonical(fs::path(argv0), ec);
  if (!ec) {
    candidates.push_back(exe.parent_path() / "plot_results.py");
    candidates.push_back(exe.parent_path().parent_path().parent_path() / "share" / "obstacle_tracker" /
                         "scripts" / "plot_results.py");
  }
  for (const auto& c : candidates) {
    if (fs::is_regular_file(c)) return c.string();
  }
  return "";
}

std::string findPythonWithMatplotlib() {
  for (const char* py : {"/usr/bin/python3", "python3"}) {
    const std::string cmd = std::string(py) + " -c 'import matplotlib' > /dev/null 2>&1";
    if (std::system(cmd.c_str()) == 0) return py;
  }
  return "";
}

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

int main(int argc, char** argv) {
  std::string data, out, params_file, gt_path, plot_script;
  std::vector<std::string> trackers, only;
  int jobs = 1, tre_segments = 20;
  bool tre = false, plots = true;
  std::string command = "evaluate";
  for (int i = 1; i < argc; ++i) command += " " + std::string(argv[i]);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "evaluate: " << a << " needs a value\n" << kUsage;
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--data") data = next();
    else if (a == "--out") out = next();
    else if (a == "--trackers") trackers = splitList(next());
    else if (a == "--jobs") jobs = std::atoi(next().c_str());
    else if (a == "--tre") tre = true;
    else if (a == "--tre-segments") tre_segments = std::atoi(next().c_str());
    else if (a == "--params") params_file = next();
    else if (a == "--sequences") only = splitList(next());
    else if (a == "--gt") gt_path = next();
    else if (a == "--no-plots") plots = false;
    else if (a == "--plot-script") plot_script = next();
    else if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return 0;
    } else {
      std::cerr << "evaluate: unknown argument " << a << "\n" << kUsage;
      return 2;
    }
  }
  if (data.empty() || out.empty() || jobs < 1 || tre_segments < 1) {
    std::cerr << kUsage;
    return 2;
  }
  if (trackers.empty()) trackers = ev::knownTrackers();
  // One thread per job: OpenCV's own parallel loops would fight the job pool for the cores.
  cv::setNumThreads(1);

  Params params;
  if (!params_file.empty()) {
    std::vector<std::string> messages;
    try {
      params = obstacle_tracker::core::loadParamsFile(params_file, &messages);
    } catch (const std::exception& e) {
      std::cerr << "evaluate: " << e.what() << "\n";
      return 1;
    }
    for (const auto& m : messages) std::cerr << "evaluate: " << m << "\n";
  }
  for (const auto& t : trackers) {
    try {
      ev::makeTracker(t, params);
    } catch (const std::exception& e) {
      std::cerr << "evaluate: " << e.what() << "\n";
      return 2;
    }
  }

  std::vector<SequenceInfo> seqs;
  try {
    seqs = discover(data, gt_path);
    std::vector<SequenceInfo> kept;
    for (auto& s : seqs) {
      ev::Sequence seq(s.path, s.gt_path);
      s.name = seq.name();
      if (!only.empty() && std::find(only.begin(), only.end(), s.name) == only.end()) continue;
      if (!seq.hasGroundTruth()) {
        std::cerr << "evaluate: skipping " << s.path << " (no ground truth)\n";
        continue;
      }
      s.frames = seq.frameCount();
      std::vector<cv::Rect2f> gt(s.frames);
      for (int f = 0; f < s.frames; ++f) {
        gt[f] = seq.groundTruthAt(f);
        if (ev::isAbsent(gt[f])) ++s.absent_frames;
      }
      s.starts = {0};
      if (tre) {
        // OTB's first TRE segment is the OPE run (from frame 0, or the first present box).
        const std::vector<int> t = ev::treStartFrames(gt, tre_segments);
        for (size_t k = 1; k < t.size(); ++k) s.starts.push_back(t[k]);
      }
      kept.push_back(s);
    }
    seqs = kept;
  } catch (const std::exception& e) {
    std::cerr << "evaluate: " << e.what() << "\n";
    return 1;
  }
  if (seqs.empty()) {
    std::cerr << "evaluate: no sequence selected\n";
    return 1;
  }
  fs::create_directories(out);

  // Tasks, slowest first so that the pool ends together.
  std::vector<Task> tasks;
  long long total_frames = 0;
  for (size_t s = 0; s < seqs.size(); ++s) {
    for (size_t t = 0; t < trackers.size(); ++t) {
      for (int start : seqs[s].starts) {
        const int frames = seqs[s].frames - start;
        tasks.push_back({s, t, start, frames * trackerCost(trackers[t])});
        total_frames += frames;
      }
    }
  }
  std::stable_sort(tasks.begin(), tasks.end(), [](const Task& a, const Task& b) { return a.cost > b.cost; });
  std::cerr << "evaluate: " << seqs.size() << " sequences x " << trackers.size() << " trackers, "
            << tasks.size() << " runs (" << total_frames << " frames) on " << jobs << " jobs"
            << (tre ? ", OPE + TRE" : ", OPE") << "\n";

  std::vector<ev::RunResult> results(tasks.size());
  std::atomic<size_t> next_task{0};
  std::atomic<int> frames_done{0};
  std::atomic<size_t> tasks_done{0};
  std::mutex log_mutex;
  std::condition_variable finished_cv;
  const auto t_start = std::chrono::steady_clock::now();
  auto worker = [&]() {
    for (;;) {
      const size_t k = next_task.fetch_add(1);
      if (k >= tasks.size()) return;
      const Task& task = tasks[k];
      const SequenceInfo& si = seqs[task.seq];
      ev::RunResult r;
      try {
        r = ev::runTracker(si.path, trackers[task.tracker], params, task.start, &frames_done, si.gt_path);
      } catch (const std::exception& e) {
        r.sequence = si.name;
        r.tracker = trackers[task.tracker];
        r.start_frame = task.start;
        r.error = e.what();
      }
      results[k] = std::move(r);
      const size_t done = tasks_done.fetch_add(1) + 1;
      std::lock_guard<std::mutex> lock(log_mutex);
      const ev::RunResult& rr = results[k];
      std::cerr << "[" << done << "/" << tasks.size() << "] " << si.name << " " << trackers[task.tracker];
      if (task.start > 0) std::cerr << " (from frame " << task.start << ")";
      if (!rr.boxes.empty()) {
        const ev::OtbScores sc = ev::otbScores(rr.boxes, rr.gt);
        std::cerr << ": P@20 " << fmt(sc.precision20) << " AUC " << fmt(sc.auc) << " " << fmtFps(rr.fps())
                  << " fps";
      }
      if (!rr.error.empty()) std::cerr << "  ERROR: " << rr.error;
      std::cerr << "\n";
      finished_cv.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < std::min<int>(jobs, static_cast<int>(tasks.size())); ++j) pool.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(log_mutex);
    while (tasks_done.load() < tasks.size()) {
      finished_cv.wait_for(lock, std::chrono::seconds(15));
      if (tasks_done.load() < tasks.size()) {
        const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
        std::cerr << "evaluate: " << frames_done.load() << "/" << total_frames << " frames, "
                  << tasks_done.load() << "/" << tasks.size() << " runs, " << fmt(el, 0) << " s\n";
      }
    }
  }
  for (auto& th : pool) th.join();

  // ---- Scores -----------------------------------------------------------------------------------
  const size_t S = seqs.size(), T = trackers.size();
  std::vector<std::vector<Cell>> cells(S, std::vector<Cell>(T));
  std::vector<std::vector<ev::FrameErrors>> tre_pool(S, std::vector<ev::FrameErrors>(T));
  std::vector<std::vector<double>> tre_secs(S, std::vector<double>(T, 0.0));
  std::vector<std::vector<int>> tre_frames(S, std::vector<int>(T, 0));
  int errors = 0;
  const fs::path boxes_dir = fs::path(out) / "boxes";
  for (size_t k = 0; k < tasks.size(); ++k) {
    const Task& task = tasks[k];
    const ev::RunResult& r = results[k];
    Cell& c = cells[task.seq][task.tracker];
    if (!r.error.empty()) {
      ++errors;
      c.error = r.error;
    }
    if (r.boxes.empty()) continue;
    const ev::FrameErrors fe = ev::frameErrors(r.boxes, r.gt);
    tre_pool[task.seq][task.tracker].append(fe);
    tre_secs[task.seq][task.tracker] += r.update_seconds;
    tre_frames[task.seq][task.tracker] += r.timed_frames;
    if (task.start != 0) continue;
    c.done = true;
    c.ope = ev::otbScores(fe);
    c.fps = r.fps();
    c.ms_p99 = percentileOf(r.frame_ms, 99.0);
    c.ms_max = percentileOf(r.frame_ms, 100.0);
    c.sa = ev::senseAvoidScores(r.boxes, r.confidence, r.gt);
    if (seqs[task.seq].absent_frames > 0) {
      c.has_lt = true;
      c.lt = ev::longTermScores(r.boxes, r.confidence, r.gt);
    }
    const fs::path d = boxes_dir / seqs[task.seq].name;
    fs::create_directories(d);
    std::ofstream bf(d / (trackers[task.tracker] + ".txt"));
    bf << std::fixed;
    for (size_t f = 0; f < r.boxes.size(); ++f) {
      const cv::Rect2f& b = r.boxes[f];
      if (ev::isAbsent(b)) {
        bf << "0,0,0,0," << std::setprecision(4) << r.confidence[f] << "\n";
      } else {
        // Four decimals: other tools (scripts/score_bag.py --boxes) must score the same boxes, and
        // at 0.01 px a rounded box crosses an IoU threshold now and then.
        bf << std::setprecision(4) << b.x << "," << b.y << "," << b.width << "," << b.height << ","
           << std::setprecision(4) << r.confidence[f] << "\n";
      }
    }
  }
  if (tre) {
    for (size_t s = 0; s < S; ++s) {
      for (size_t t = 0; t < T; ++t) {
        cells[s][t].has_tre = true;
        cells[s][t].tre = ev::otbScores(tre_pool[s][t]);
      }
    }
  }

  // Subsets: all, and the flying clips when there are any (and not all of them are).
  struct Subset {
    std::string name;
    std::vector<size_t> seqs;
  };
  std::vector<Subset> subsets{{"all", {}}};
  Subset flying{"flying", {}};
  for (size_t s = 0; s < S; ++s) {
    subsets[0].seqs.push_back(s);
    if (ev::isFlyingSequence(seqs[s].name)) flying.seqs.push_back(s);
  }
  if (!flying.seqs.empty() && flying.seqs.size() < S) subsets.push_back(flying);

  struct Summary {
    ev::OtbScores ope, tre;
    double fps = 0.0;
    int lt_n = 0;
    double lt_p = 0, lt_r = 0, lt_f = 0;
  };
  auto summarise = [&](const Subset& sub, size_t t) {
    Summary m;
    std::vector<ev::OtbScores> o, r;
    std::vector<double> fps;
    for (size_t s : sub.seqs) {
      const Cell& c = cells[s][t];
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
  };
  std::vector<std::vector<Summary>> summary(subsets.size(), std::vector<Summary>(T));
  for (size_t u = 0; u < subsets.size(); ++u)
    for (size_t t = 0; t < T; ++t) summary[u][t] = summarise(subsets[u], t);

  // ---- results.csv ----------------------------------------------------------------------------
  {
    std::ofstream f(fs::path(out) / "results.csv");
    f << "sequence,tracker,mode,frames,gt_frames,precision20,auc,mean_centre_error,lost_fraction,fps,"
         "lt_precision,lt_recall,lt_fscore,lt_threshold,frame_ms_p99,frame_ms_max,state_accuracy,"
         "first_correct_frame,false_confident_rate\n";
    auto row = [&](const std::string& seq, const std::string& trk, const std::string& mode, int frames,
                   const ev::OtbScores& sc, double fps, const std::string& lt, const std::string& ms,
                   const std::string& sa = ",,") {
      f << seq << "," << trk << "," << mode << "," << frames << "," << sc.frames << "," << fmt(sc.precision20, 4)
        << "," << fmt(sc.auc, 4) << "," << fmt(sc.mean_centre_error, 2) << "," << fmt(sc.lost_fraction, 4) << ","
        << fmt(fps, 1) << "," << lt << "," << ms << "," << sa << "\n";
    };
    for (size_t s = 0; s < S; ++s) {
      for (size_t t = 0; t < T; ++t) {
        const Cell& c = cells[s][t];
        if (!c.done) continue;
        const std::string lt = c.has_lt ? fmt(c.lt.precision, 4) + "," + fmt(c.lt.recall, 4) + "," +
                                              fmt(c.lt.fscore, 4) + "," + fmt(c.lt.threshold, 4)
                                        : ",,,";
        row(seqs[s].name, trackers[t], "OPE", seqs[s].frames, c.ope, c.fps, lt,
            fmt(c.ms_p99, 2) + "," + fmt(c.ms_max, 2),
            fmt(c.sa.state_accuracy, 4) + "," + std::to_string(c.sa.first_correct_frame) + "," +
                fmt(c.sa.false_confident_rate, 4));
        if (c.has_tre) {
          const double fps = tre_secs[s][t] > 0 ? tre_frames[s][t] / tre_secs[s][t] : 0.0;
          row(seqs[s].name, trackers[t], "TRE", seqs[s].frames, c.tre, fps, ",,,", ",");
        }
      }
    }
    for (size_t u = 0; u < subsets.size(); ++u) {
      for (size_t t = 0; t < T; ++t) {
        const Summary& m = summary[u][t];
        const std::string lt = m.lt_n > 0 ? fmt(m.lt_p, 4) + "," + fmt(m.lt_r, 4) + "," + fmt(m.lt_f, 4) + ","
                                          : ",,,";
        row("mean:" + subsets[u].name, trackers[t], "OPE", 0, m.ope, m.fps, lt, ",");
        if (tre) row("mean:" + subsets[u].name, trackers[t], "TRE", 0, m.tre, m.fps, ",,,", ",");
      }
    }
  }

  // ---- curves.csv (long format: one value per line) ---------------------------------------------
  {
    std::ofstream f(fs::path(out) / "curves.csv");
    f << "mode,sequence,tracker,curve,threshold,value\n";
    auto curves = [&](const std::string& mode, const std::string& seq, const std::string& trk,
                      const ev::OtbScores& sc) {
      for (size_t i = 0; i < sc.precision.size(); ++i)
        f << mode << "," << seq << "," << trk << ",precision," << ev::precisionThreshold(int(i)) << ","
          << fmt(sc.precision[i], 5) << "\n";
      for (size_t i = 0; i < sc.success.size(); ++i)
        f << mode << "," << seq << "," << trk << ",success," << fmt(ev::successThreshold(int(i)), 2) << ","
          << fmt(sc.success[i], 5) << "\n";
    };
    for (size_t u = 0; u < subsets.size(); ++u) {
      for (size_t t = 0; t < T; ++t) {
        curves("OPE", "mean:" + subsets[u].name, trackers[t], summary[u][t].ope);
        if (tre) curves("TRE", "mean:" + subsets[u].name, trackers[t], summary[u][t].tre);
      }
    }
    for (size_t s = 0; s < S; ++s) {
      for (size_t t = 0; t < T; ++t) {
        if (!cells[s][t].done) continue;
        curves("OPE", seqs[s].name, trackers[t], cells[s][t].ope);
        if (tre) curves("TRE", seqs[s].name, trackers[t], cells[s][t].tre);
      }
    }
  }

  // ---- results.md -------------------------------------------------------------------------------
  std::ostringstream md;
  {
    auto idx = [&](const std::string& name) -> int {
      for (size_t t = 0; t < T; ++t)
        if (trackers[t] == name) return static_cast<int>(t);
      return -1;
    };
    const int kcf = idx("KCF"), csrt = idx("CSRT");
    md << "# Evaluation results\n\n"
       << "`" << command << "`  \n"
       << nowUtc() << "; " << S << " sequences; " << jobs << " parallel job(s), each single-threaded; "
       << "OTB precision at 20 px / success AUC (21 IoU thresholds), means over sequences; fps = frames per "
          "second of the tracker's own per-frame call (decode excluded), geometric mean over sequences. "
          "OpenCV trackers start from the first ground-truth box and keep their last box after a failed "
          "update; ours-gt starts from the same box; ours-auto starts by itself.\n\n";
    for (int mode = 0; mode < (tre ? 2 : 1); ++mode) {
      md << "## Overall (" << (mode == 0 ? "OPE" : "TRE, " + std::to_string(tre_segments) + " start frames, pooled")
         << ")\n\n| tracker |";
      for (const auto& sub : subsets) md << " " << sub.name << " (" << sub.seqs.size() << "): P@20 / AUC |";
      if (mode == 0) {
        md << " mean centre error (px) | fps |";
        if (kcf >= 0) md << " x KCF |";
        if (csrt >= 0) md << " x CSRT |";
      }
      md << "\n|---|";
      for (size_t u = 0; u < subsets.size(); ++u) md << "---|";
      if (mode == 0) md << "---|---|" << (kcf >= 0 ? "---|" : "") << (csrt >= 0 ? "---|" : "");
      md << "\n";
      for (size_t t = 0; t < T; ++t) {
        md << "| " << trackers[t] << " |";
        for (size_t u = 0; u < subsets.size(); ++u) {
          const ev::OtbScores& sc = mode == 0 ? summary[u][t].ope : summary[u][t].tre;
          md << " " << fmt(sc.precision20) << " / " << fmt(sc.auc) << " |";
        }
        if (mode == 0) {
          const Summary& a = summary[0][t];
          md << " " << fmt(a.ope.mean_centre_error, 1) << " | " << fmtFps(a.fps) << " |";
          if (kcf >= 0) md << " " << (summary[0][kcf].fps > 0 ? fmt(a.fps / summary[0][kcf].fps, 2) : "-") << " |";
          if (csrt >= 0) md << " " << (summary[0][csrt].fps > 0 ? fmt(a.fps / summary[0][csrt].fps, 2) : "-") << " |";
        }
        md << "\n";
      }
      md << "\n";
    }
    md << "## Per sequence (OPE): precision@20 / AUC\n\n| sequence | frames |";
    for (const auto& t : trackers) md << " " << t << " |";
    md << "\n|---|---|";
    for (size_t t = 0; t < T; ++t) md << "---|";
    md << "\n";
    for (size_t s = 0; s < S; ++s) {
      md << "| " << seqs[s].name << " | " << seqs[s].frames << " |";
      for (size_t t = 0; t < T; ++t) {
        const Cell& c = cells[s][t];
        md << " " << (c.done ? fmt(c.ope.precision20) + " / " + fmt(c.ope.auc) : "-") << " |";
      }
      md << "\n";
    }
    md << "\n## Per sequence (OPE): fps (slowest frame, ms)\n\n| sequence |";
    for (const auto& t : trackers) md << " " << t << " |";
    md << "\n|---|";
    for (size_t t = 0; t < T; ++t) md << "---|";
    md << "\n";
    for (size_t s = 0; s < S; ++s) {
      md << "| " << seqs[s].name << " |";
      for (size_t t = 0; t < T; ++t)
        md << " " << fmtFps(cells[s][t].fps) << " (" << fmt(cells[s][t].ms_max, 1) << ") |";
      md << "\n";
    }
    md << "\n";
    {
      std::vector<std::string> names;
      for (const auto& q : seqs) names.push_back(q.name);
      std::vector<std::pair<std::string, std::vector<size_t>>> subs;
      for (const auto& sub : subsets) subs.emplace_back(sub.name, sub.seqs);
      writeSenseAvoid(md, names, trackers, cells, subs);
    }
    bool any_lt = false;
    for (const auto& s : seqs) any_lt = any_lt || s.absent_frames > 0;
    if (any_lt) {
      md << "## Long-term (sequences with absent frames; VOT LT precision / recall / F at the best "
            "confidence threshold)\n\n| sequence | absent frames |";
      for (const auto& t : trackers) md << " " << t << " |";
      md << "\n|---|---|";
      for (size_t t = 0; t < T; ++t) md << "---|";
      md << "\n";
      for (size_t s = 0; s < S; ++s) {
        if (seqs[s].absent_frames == 0) continue;
        md << "| " << seqs[s].name << " | " << seqs[s].absent_frames << " |";
        for (size_t t = 0; t < T; ++t) {
          const Cell& c = cells[s][t];
          md << " " << (c.has_lt ? fmt(c.lt.precision) + " / " + fmt(c.lt.recall) + " / " + fmt(c.lt.fscore) : "-")
             << " |";
        }
        md << "\n";
      }
      md << "\n";
    }
    if (errors > 0) {
      md << "## Errors\n\n";
      for (size_t s = 0; s < S; ++s)
        for (size_t t = 0; t < T; ++t)
          if (!cells[s][t].error.empty())
            md << "- " << seqs[s].name << " / " << trackers[t] << ": " << cells[s][t].error << "\n";
      md << "\n";
    }
  }

  // ---- plots --------------------------------------------------------------------------------------
  if (plots) {
    const std::string script = findPlotScript(plot_script, argv[0]);
    const std::string py = script.empty() ? "" : findPythonWithMatplotlib();
    if (script.empty()) {
      std::cerr << "evaluate: plots skipped (scripts/plot_results.py not found; --plot-script FILE)\n";
    } else if (py.empty()) {
      std::cerr << "evaluate: plots skipped (no python3 with matplotlib: apt-get install python3-matplotlib)\n";
    } else {
      const std::string cmd = py + " " + shellQuote(script) + " " + shellQuote((fs::path(out) / "curves.csv").string()) +
                              " --out " + shellQuote(out);
      if (std::system(cmd.c_str()) != 0) {
        std::cerr << "evaluate: the plot script failed: " << cmd << "\n";
      } else {
        md << "## Plots\n\n";
        std::vector<std::string> pngs;
        for (const auto& e : fs::directory_iterator(out)) {
          if (e.path().extension() == ".png") pngs.push_back(e.path().filename().string());
        }
        std::sort(pngs.begin(), pngs.end());
        for (const auto& p : pngs) md << "![" << fs::path(p).stem().string() << "](" << p << ")\n";
        md << "\n";
      }
    }
  }
  {
    std::ofstream f(fs::path(out) / "results.md");
    f << md.str();
  }
  std::cout << md.str();
  const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  std::cerr << "evaluate: wrote " << out << "/results.csv, results.md, curves.csv, boxes/ in " << fmt(el, 0)
            << " s" << (errors > 0 ? " (" + std::to_string(errors) + " runs had errors)" : "") << "\n";
  return errors > 0 ? 1 : 0;
}
