// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// init_table --data DIR [--frames N] [--fps F]
//
// Auto-initialisation on real sequences: the sequence folders under DIR, read as evaluate reads
// them (eval::Sequence, eval::FrameConverter).
// Prints Markdown tables:
//  1. first frame, one-frame detectors: IoU and centre error of the best region against the
//     ground truth for our SaliencyDetector (FastMBD + Otsu + regions) and for OpenCV's spectral
//     residual saliency followed by the same Otsu / regions step;
//  2. AutoInitializer (defaults) over the first N frames: frame of the first confirmed box, its
//     centre error and IoU, and whether it came within the precision score's threshold
//     (eval::kPrecisionSummaryPx) inside the first second;
//  3. cue ablation on every sequence: the same, with each cue switched off or added.
// The parameter variants under test are in src/tools/init_table/variants.cpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/saliency.hpp>

#include "command_line.h"
#include "init_table/variants.h"
#include "obstacle_tracker/core/auto_init.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/region_extractor.h"
#include "obstacle_tracker/core/saliency.h"
#include "obstacle_tracker/core/salient_region.h"
#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/eval/runner.h"
#include "obstacle_tracker/eval/sequence.h"

namespace oc = obstacle_tracker::core;
namespace ev = obstacle_tracker::eval;
using obstacle_tracker::init_table_tool::ablationVariants;
using obstacle_tracker::init_table_tool::detectorOptions;
using obstacle_tracker::init_table_tool::Variant;

namespace {

// A sequence folder with a ground truth. Its reader is the one openSequences opened to find the
// ground truth, kept until loadFirstFrames has taken the frames the tables use: opening it again
// would parse the ground truth and, for a video, set up a decoder a second time.
struct Sequence {
  std::string name, dir;
  std::vector<cv::Rect2f> gt;
  std::unique_ptr<ev::Sequence> reader;
};

// The sequence folders under root that evaluate finds (eval::listSequences), in name order, each
// opened; the others, and those that cannot be read or have an empty ground truth, are skipped
// with a message, as evaluate skips them.
std::vector<Sequence> openSequences(const std::string& root) {
  std::vector<std::string> skipped;
  const std::vector<std::string> dirs = ev::listSequences(root, &skipped);
  for (const std::string& dir : skipped) {
    std::fprintf(stderr, "init_table: skipping %s (no ground-truth file)\n", dir.c_str());
  }
  std::vector<Sequence> seqs;
  for (const std::string& dir : dirs) {
    try {
      auto reader = std::make_unique<ev::Sequence>(dir);
      if (!reader->hasGroundTruth()) throw std::runtime_error("no ground truth");
      Sequence s{reader->name(), dir, reader->groundTruth(), nullptr};
      s.reader = std::move(reader);
      seqs.push_back(std::move(s));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "init_table: skipping %s (%s)\n", dir.c_str(), e.what());
    }
  }
  return seqs;
}

// The evaluation's own measures (metrics.h: IoU in double precision), as float for the tables.
float overlap(const cv::Rect2f& a, const cv::Rect2f& b) { return static_cast<float>(oc::boxIou<double>(a, b)); }
float centreError(const cv::Rect2f& a, const cv::Rect2f& b) {
  return static_cast<float>(obstacle_tracker::eval::centreError(a, b));
}

struct AutoResult {
  int frame = -1;  // 1-based, -1 = none
  float error = -1.0f, iou = 0.0f;
  double ms = 0.0;
};

AutoResult runAuto(const Sequence& s, const std::vector<cv::Mat>& frames, const oc::Params& p) {
  oc::AutoInitializer init(p);
  AutoResult r;
  double total = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto& out = init.update(frames[i], static_cast<double>(i) / 25.0);
    total += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ++n;
    if (!out.empty()) {
      r.frame = static_cast<int>(i) + 1;
      r.error = centreError(out[0].box, s.gt[i]);
      r.iou = overlap(out[0].box, s.gt[i]);
      break;
    }
  }
  r.ms = n ? total / n : 0.0;
  return r;
}

std::string fmtAuto(const AutoResult& r) {
  char buf[64];
  if (r.frame < 0) return "none";
  std::snprintf(buf, sizeof buf, "%.1f px @ %d", r.error, r.frame);
  return buf;
}

struct Options {
  std::string data;
  int max_frames = 30;
  double fps = 25.0;
};

// Reads the command line into *o. Returns nothing when the tool is to run, otherwise the code to
// exit with (0 after --help, 2 after a usage error; both already printed).
std::optional<int> parseArgs(int argc, char** argv, Options* o) {
  CLI::App app{"Auto-initialisation on real sequences (the sequence folders under DIR, read as evaluate "
               "reads them: img/ or a video, and a ground truth): prints Markdown tables of the "
               "first-frame detectors, the AutoInitializer over the first N frames and a cue ablation.",
               "init_table"};
  obstacle_tracker::tools::setToolDefaults(app);
  app.add_option("--data", o->data, "folder of sequence folders")->type_name("DIR")->required();
  app.add_option("--frames", o->max_frames, "frames given to the AutoInitializer (at least 1)")
      ->type_name("N")
      ->capture_default_str();
  app.add_option("--fps", o->fps, "frame rate of the sequences (\"within the first second\")")
      ->type_name("F")
      ->capture_default_str();
  if (const auto code = obstacle_tracker::tools::parseCommandLine(app, argc, argv)) return code;
  if (o->data.empty()) return obstacle_tracker::tools::usageError(app, "--data must not be empty");
  if (o->max_frames < 1) return obstacle_tracker::tools::usageError(app, "--frames must be at least 1");
  return std::nullopt;
}

// The first frames of a sequence (at most one per ground-truth box) as evaluate gives them to
// the core (eval::FrameConverter); its reader is closed afterwards.
std::vector<cv::Mat> loadFirstFrames(Sequence& s, int max_frames) {
  ev::FrameConverter converter;
  std::vector<cv::Mat> frames;
  cv::Mat raw;
  const int n = std::min(max_frames, static_cast<int>(s.gt.size()));
  while (static_cast<int>(frames.size()) < n && s.reader->read(raw)) frames.push_back(converter.convert(raw).clone());
  s.reader.reset();
  if (frames.empty()) throw std::runtime_error("cannot read a frame of '" + s.dir + "'");
  return frames;
}

// The two one-frame detectors of the first table, kept across sequences.
struct FirstFrameDetectors {
  oc::SaliencyDetector mbd;
  cv::Ptr<cv::saliency::StaticSaliencySpectralResidual> spectral_residual =
      cv::saliency::StaticSaliencySpectralResidual::create();
  oc::RegionExtractor extractor;
  std::vector<oc::SalientRegion> sr_regions;
  oc::Params defaults;

  // OpenCV's spectral residual saliency, then the same Otsu / regions step as ours.
  const std::vector<oc::SalientRegion>& detectSpectralResidual(const cv::Mat& frame) {
    cv::Mat map_f, map_u8;
    spectral_residual->computeSaliency(frame, map_f);
    double mx = 0.0;
    cv::minMaxLoc(map_f, nullptr, &mx);
    map_f.convertTo(map_u8, CV_8U, mx > 0 ? 255.0 / mx : 0.0);
    oc::RegionExtractor::Geometry g;
    g.frame_area = static_cast<double>(frame.total());
    extractor.extract(map_u8, g, defaults, sr_regions);
    return sr_regions;
  }
};

// A table cell for the best-ranked region: its IoU, or its centre error when `err`.
std::string bestRegionCell(const std::vector<oc::SalientRegion>& r, const cv::Rect2f& gt, bool err) {
  char buf[32];
  if (r.empty()) return std::string("none");
  if (err) {
    std::snprintf(buf, sizeof buf, "%.0f", centreError(r[0].box, gt));
  } else {
    std::snprintf(buf, sizeof buf, "%.2f", overlap(r[0].box, gt));
  }
  return std::string(buf);
}

// The first-frame table. Loads the first frames of every sequence on the way (returned, one
// list per sequence), so the rows of the sequences read so far are out when a frame cannot be read.
std::vector<std::vector<cv::Mat>> printFirstFrameTable(std::vector<Sequence>& seqs, int max_frames) {
  std::printf("## First frame, one-frame detectors (best-ranked region)\n\n");
  std::printf("| sequence | size | MBD IoU | MBD centre err (px) | SR IoU | SR centre err (px) |\n|---|---|---|---|---|---|\n");
  std::vector<std::vector<cv::Mat>> all_frames;
  FirstFrameDetectors detectors;
  for (Sequence& s : seqs) {
    all_frames.push_back(loadFirstFrames(s, max_frames));
    const cv::Mat& f0 = all_frames.back()[0];
    const auto& ours = detectors.mbd.detect(f0);
    const auto& sr = detectors.detectSpectralResidual(f0);
    std::printf("| %s | %dx%d%s | %s | %s | %s | %s |\n", s.name.c_str(), f0.cols, f0.rows,
                f0.channels() == 1 ? " grey" : "", bestRegionCell(ours, s.gt[0], false).c_str(),
                bestRegionCell(ours, s.gt[0], true).c_str(), bestRegionCell(sr, s.gt[0], false).c_str(),
                bestRegionCell(sr, s.gt[0], true).c_str());
  }
  return all_frames;
}

// One row of the detector-options table: the best-ranked region against the ground truth on every 5th frame.
void printDetectorOptionRow(const Variant& o, const std::vector<Sequence>& seqs,
                            const std::vector<std::vector<cv::Mat>>& all_frames) {
  oc::SaliencyDetector od(o.p);
  double iou_all = 0.0, iou_nf = 0.0;
  int n_all = 0, n_nf = 0, hit_all = 0, hit_fly = 0, n_fly = 0;
  for (size_t k = 0; k < seqs.size(); ++k)
    for (size_t i = 0; i < all_frames[k].size(); i += 5) {
      const auto& r = od.detect(all_frames[k][i]);
      const float v = r.empty() ? 0.0f : overlap(r[0].box, seqs[k].gt[i]);
      const bool hit = !r.empty() && centreError(r[0].box, seqs[k].gt[i]) <= ev::kPrecisionSummaryPx;
      iou_all += v;
      ++n_all;
      hit_all += hit;
      if (ev::isFlyingSequence(seqs[k].name)) {
        ++n_fly;
        hit_fly += hit;
      } else {
        iou_nf += v;
        ++n_nf;
      }
    }
  std::printf("| %s | %.3f | %d/%d | %.3f | %d/%d |\n", o.name.c_str(), n_all ? iou_all / n_all : 0.0, hit_all, n_all,
              n_nf ? iou_nf / n_nf : 0.0, hit_fly, n_fly);
}

// The detector-options table: each option on frames 1, 6, 11, ... of every sequence.
void printDetectorOptionsTable(const std::vector<Sequence>& seqs,
                               const std::vector<std::vector<cv::Mat>>& all_frames, int max_frames) {
  const std::vector<Variant> options = detectorOptions();
  std::printf("\n## One-frame detector options: best-ranked region on frames 1, 6, 11, ... of the first %d\n\n",
              max_frames);
  std::printf("| option | mean IoU (all) | centre <= %.0f px (all) | mean IoU (non-flying) | centre <= %.0f px (flying) |\n",
              ev::kPrecisionSummaryPx, ev::kPrecisionSummaryPx);
  std::printf("|---|---|---|---|---|\n");
  for (const Variant& o : options) printDetectorOptionRow(o, seqs, all_frames);
}

// A first box within kPrecisionSummaryPx inside the first second.
bool isEarlyHit(const AutoResult& r, int first_second) {
  return r.frame > 0 && r.frame <= first_second && r.error <= ev::kPrecisionSummaryPx;
}

int countFlying(const std::vector<Sequence>& seqs) {
  int flying = 0;
  for (const Sequence& s : seqs) flying += ev::isFlyingSequence(s.name);
  return flying;
}

// The AutoInitializer table: the given (default) parameters on every sequence.
void printAutoInitTable(const std::vector<Sequence>& seqs, const std::vector<std::vector<cv::Mat>>& all_frames,
                        const oc::Params& p, int max_frames, int first_second) {
  std::printf("\n## AutoInitializer (defaults), first %d frames\n\n", max_frames);
  std::printf("| sequence | flying | first confirmed box | centre err (px) | IoU | frame | within %.0f px in 1st second | ms/frame |\n",
              ev::kPrecisionSummaryPx);
  std::printf("|---|---|---|---|---|---|---|---|\n");
  int flying_ok = 0;
  for (size_t k = 0; k < seqs.size(); ++k) {
    const AutoResult r = runAuto(seqs[k], all_frames[k], p);
    const bool ok = isEarlyHit(r, first_second);
    if (ev::isFlyingSequence(seqs[k].name)) flying_ok += ok;
    char err[32] = "-", io[32] = "-", fr[32] = "-";
    if (r.frame > 0) {
      std::snprintf(err, sizeof err, "%.1f", r.error);
      std::snprintf(io, sizeof io, "%.2f", r.iou);
      std::snprintf(fr, sizeof fr, "%d", r.frame);
    }
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %.2f |\n", seqs[k].name.c_str(),
                ev::isFlyingSequence(seqs[k].name) ? "yes" : "no", r.frame > 0 ? "yes" : "none", err, io, fr,
                ok ? "**yes**" : "no", r.ms);
  }
  std::printf("\nFlying clips with a first box within %.0f px inside the first %d frames: %d of %d\n",
              ev::kPrecisionSummaryPx, first_second, flying_ok, countFlying(seqs));
}

// The cue-ablation table: every variant on every sequence, and how many flying clips it gets early.
void printCueAblationTable(const std::vector<Sequence>& seqs, const std::vector<std::vector<cv::Mat>>& all_frames,
                           const std::vector<Variant>& variants, int first_second) {
  std::printf("\n## Cue ablation: centre error of the first confirmed box @ its frame\n\n| variant |");
  for (const Sequence& s : seqs) std::printf(" %s |", s.name.c_str());
  std::printf(" flying ok |\n|---|");
  for (size_t k = 0; k <= seqs.size(); ++k) std::printf("---|");
  std::printf("\n");
  const int flying = countFlying(seqs);
  for (const Variant& v : variants) {
    std::printf("| %s |", v.name.c_str());
    int ok = 0;
    for (size_t k = 0; k < seqs.size(); ++k) {
      const AutoResult r = runAuto(seqs[k], all_frames[k], v.p);
      const bool good = isEarlyHit(r, first_second);
      if (ev::isFlyingSequence(seqs[k].name)) ok += good;
      std::printf(" %s%s%s |", good ? "**" : "", fmtAuto(r).c_str(), good ? "**" : "");
    }
    std::printf(" %d/%d |\n", ok, flying);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  if (const auto code = parseArgs(argc, argv, &opt)) return *code;
  std::vector<Sequence> seqs = openSequences(opt.data);
  if (seqs.empty()) {
    std::fprintf(stderr, "no sequence with ground truth under %s\n", opt.data.c_str());
    return 1;
  }
  const int first_second = static_cast<int>(std::lround(opt.fps));
  const std::vector<Variant> variants = ablationVariants();
  try {
    const std::vector<std::vector<cv::Mat>> all_frames = printFirstFrameTable(seqs, opt.max_frames);
    printDetectorOptionsTable(seqs, all_frames, opt.max_frames);
    printAutoInitTable(seqs, all_frames, variants[0].p, opt.max_frames, first_second);
    printCueAblationTable(seqs, all_frames, variants, first_second);
  } catch (const std::exception& e) {
    std::fflush(stdout);  // the rows printed so far stay
    std::fprintf(stderr, "init_table: error: %s\n", e.what());
    return 1;
  }
  return obstacle_tracker::tools::finishStandardOutput("init_table");
}
