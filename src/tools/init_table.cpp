// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// init_table --data DIR [--frames N] [--fps F]
//
// Auto-initialisation on real sequences (OTB layout: DIR/NAME/img/0001.jpg..., groundtruth_rect.txt).
// Prints Markdown tables:
//  1. first frame, one-frame detectors: IoU and centre error of the best region against the
//     ground truth for our SaliencyDetector (FastMBD + Otsu + regions) and for OpenCV's spectral
//     residual saliency followed by the same Otsu / regions step;
//  2. AutoInitializer (defaults) over the first N frames: frame of the first confirmed box, its
//     centre error and IoU, and whether it came within 20 px inside the first second;
//  3. cue ablation on every sequence: the same, with each cue switched off or added.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <dirent.h>
#include <sys/stat.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/saliency.hpp>

#include "command_line.h"
#include "obstacle_tracker/core/saliency.h"
#include "obstacle_tracker/core/segmentation.h"
#include "obstacle_tracker/eval/metrics.h"

namespace oc = obstacle_tracker::core;

namespace {

struct Sequence {
  std::string name, dir;
  std::vector<cv::Rect2f> gt;
  std::vector<std::string> frames;
};

bool isDir(const std::string& p) {
  struct stat st;
  return stat(p.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

std::vector<cv::Rect2f> readGroundTruth(const std::string& path) {
  std::vector<cv::Rect2f> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    for (char& ch : line)
      if (ch == ',' || ch == '\t' || ch == ';') ch = ' ';
    std::istringstream ss(line);
    float x, y, w, h;
    if (ss >> x >> y >> w >> h) out.emplace_back(x, y, w, h);
  }
  return out;
}

std::vector<Sequence> listSequences(const std::string& root) {
  std::vector<Sequence> seqs;
  DIR* d = opendir(root.c_str());
  if (!d) return seqs;
  std::vector<std::string> names;
  while (dirent* e = readdir(d)) {
    const std::string n = e->d_name;
    if (n[0] != '.' && isDir(root + "/" + n + "/img")) names.push_back(n);
  }
  closedir(d);
  std::sort(names.begin(), names.end());
  for (const std::string& n : names) {
    Sequence s;
    s.name = n;
    s.dir = root + "/" + n;
    s.gt = readGroundTruth(s.dir + "/groundtruth_rect.txt");
    for (size_t i = 1; i <= s.gt.size(); ++i) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "/img/%04zu.jpg", i);
      s.frames.push_back(s.dir + buf);
    }
    if (!s.gt.empty()) seqs.push_back(s);
  }
  return seqs;
}

// The evaluation's own measures (metrics.h), as float for the tables.
float iou(const cv::Rect2f& a, const cv::Rect2f& b) { return static_cast<float>(obstacle_tracker::eval::iou(a, b)); }
float centreError(const cv::Rect2f& a, const cv::Rect2f& b) {
  return static_cast<float>(obstacle_tracker::eval::centreError(a, b));
}

bool isFlying(const std::string& n) { return n.rfind("antiuav", 0) == 0 || n.rfind("lasot_airplane", 0) == 0; }

cv::Mat load(const std::string& path) {
  // Frames as the core gets them: grey (CV_8UC1) when the file is grey, BGR otherwise.
  cv::Mat f = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (f.empty()) throw std::runtime_error("cannot read " + path);
  if (f.channels() == 4) cv::cvtColor(f, f, cv::COLOR_BGRA2BGR);
  if (f.channels() == 3) {
    // Thermal clips are stored as 3-channel JPEGs with equal channels: give the core grey.
    std::vector<cv::Mat> ch;
    cv::split(f, ch);
    if (cv::norm(ch[0], ch[1], cv::NORM_INF) <= 8 && cv::norm(ch[0], ch[2], cv::NORM_INF) <= 8)
      cv::cvtColor(f, f, cv::COLOR_BGR2GRAY);
  }
  return f;
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
      r.iou = iou(out[0].box, s.gt[i]);
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

}  // namespace

int main(int argc, char** argv) {
  std::string data;
  int max_frames = 30;
  double fps = 25.0;
  CLI::App app{"Auto-initialisation on real sequences (OTB layout: DIR/NAME/img/0001.jpg..., "
               "groundtruth_rect.txt): prints Markdown tables of the first-frame detectors, the "
               "AutoInitializer over the first N frames and a cue ablation.",
               "init_table"};
  obstacle_tracker::tools::setToolDefaults(app);
  app.add_option("--data", data, "folder of OTB-layout sequences")->type_name("DIR")->required();
  app.add_option("--frames", max_frames, "frames given to the AutoInitializer (at least 1)")->type_name("N")->capture_default_str();
  app.add_option("--fps", fps, "frame rate of the sequences (\"within the first second\")")
      ->type_name("F")
      ->capture_default_str();
  if (const auto code = obstacle_tracker::tools::parseCommandLine(app, argc, argv)) return *code;
  if (data.empty()) return obstacle_tracker::tools::usageError(app, "--data must not be empty");
  if (max_frames < 1) return obstacle_tracker::tools::usageError(app, "--frames must be at least 1");
  const std::vector<Sequence> seqs = listSequences(data);
  if (seqs.empty()) {
    std::fprintf(stderr, "no OTB-layout sequences under %s\n", data.c_str());
    return 1;
  }
  const int first_second = static_cast<int>(std::lround(fps));

  // Variants of the AutoInitializer for the cue ablation.
  struct Variant {
    const char* name;
    oc::Params p;
  };
  std::vector<Variant> variants;
  {
    oc::Params d;
    variants.push_back({"defaults (persistence + motion + local contrast)", d});
    oc::Params single = d;
    single.auto_init_frames = 1;
    single.auto_init_min_motion = 0.0;
    variants.push_back({"single frame (contrast x MBD, best peak)", single});
    oc::Params single_mbd = single;
    single_mbd.auto_init_local_contrast = false;
    variants.push_back({"single frame, MBD alone at native res", single_mbd});
    oc::Params persist = d;
    persist.auto_init_min_motion = 0.0;
    variants.push_back({"persistence + contrast, no motion", persist});
    oc::Params no_contrast = d;
    no_contrast.auto_init_local_contrast = false;
    variants.push_back({"persistence + motion, MBD alone (no contrast)", no_contrast});
    oc::Params text = d;
    text.auto_init_reject_text = !d.auto_init_reject_text;
    variants.push_back({text.auto_init_reject_text ? "defaults + text-row rejection" : "defaults, no text-row rejection",
                        text});
    oc::Params no_static = d;
    no_static.auto_init_reject_static = false;
    variants.push_back({"defaults, no still-pixel rejection", no_static});
    oc::Params shape = d;
    shape.auto_init_shape_filter = !d.auto_init_shape_filter;
    variants.push_back({shape.auto_init_shape_filter ? "defaults + line-shape filter" : "defaults, no line-shape filter",
                        shape});
    oc::Params horizon = d;
    horizon.auto_init_horizon_prior = true;
    variants.push_back({"defaults + horizon prior", horizon});
    oc::Params border = d;
    border.reject_border_regions = false;
    variants.push_back({"defaults, border regions kept", border});
    for (double m : {2.0, 6.0, 8.0}) {
      oc::Params mm = d;
      mm.auto_init_min_motion = m;
      static std::vector<std::string> names;  // keeps the variant names alive
      names.reserve(8);
      names.push_back("defaults, min motion " + std::to_string(static_cast<int>(m)) + " px");
      variants.push_back({names.back().c_str(), mm});
    }
    for (int n : {5, 8, 10, 12, 15}) {
      if (n == d.auto_init_frames) continue;
      oc::Params pn = d;
      pn.auto_init_frames = n;
      static std::vector<std::string> frame_names;  // keeps the variant names alive
      frame_names.reserve(8);
      frame_names.push_back("defaults, " + std::to_string(n) + " frames");
      variants.push_back({frame_names.back().c_str(), pn});
    }
  }

  std::printf("## First frame, one-frame detectors (best-ranked region)\n\n");
  std::printf("| sequence | size | MBD IoU | MBD centre err (px) | SR IoU | SR centre err (px) |\n|---|---|---|---|---|---|\n");
  std::vector<std::vector<cv::Mat>> all_frames;
  oc::SaliencyDetector det;
  auto sr = cv::saliency::StaticSaliencySpectralResidual::create();
  oc::RegionExtractor extractor;
  std::vector<oc::SalientRegion> sr_regions;
  oc::Params defaults;
  for (const Sequence& s : seqs) {
    std::vector<cv::Mat> frames;
    for (int i = 0; i < max_frames && i < static_cast<int>(s.frames.size()); ++i) frames.push_back(load(s.frames[i]));
    all_frames.push_back(frames);
    const cv::Mat& f0 = frames[0];
    const auto& ours = det.detect(f0);
    cv::Mat map_f, map_u8;
    sr->computeSaliency(f0, map_f);
    double mx = 0.0;
    cv::minMaxLoc(map_f, nullptr, &mx);
    map_f.convertTo(map_u8, CV_8U, mx > 0 ? 255.0 / mx : 0.0);
    oc::RegionExtractor::Geometry g;
    g.frame_area = static_cast<double>(f0.total());
    extractor.extract(map_u8, g, defaults, sr_regions);
    auto cell = [&](const std::vector<oc::SalientRegion>& r, bool err) {
      char buf[32];
      if (r.empty()) return std::string("none");
      std::snprintf(buf, sizeof buf, "%.2f", err ? centreError(r[0].box, s.gt[0]) : iou(r[0].box, s.gt[0]));
      if (err) std::snprintf(buf, sizeof buf, "%.0f", centreError(r[0].box, s.gt[0]));
      return std::string(buf);
    };
    std::printf("| %s | %dx%d%s | %s | %s | %s | %s |\n", s.name.c_str(), f0.cols, f0.rows,
                f0.channels() == 1 ? " grey" : "", cell(ours, false).c_str(), cell(ours, true).c_str(),
                cell(sr_regions, false).c_str(), cell(sr_regions, true).c_str());
  }

  // One-frame detector options (MB+ terms, median, map size): best region against the ground
  // truth on every 5th of the first frames of every sequence.
  {
    struct Option {
      const char* name;
      oc::Params p;
    };
    std::vector<Option> options;
    oc::Params d;
    options.push_back({"defaults (FastMBD, 300 px, no median, no MB+ terms)", d});
    oc::Params med = d;
    med.saliency_median = 5;
    options.push_back({"+ 5x5 median (MB+ reference)", med});
    oc::Params bg = d;
    bg.saliency_backgroundness = true;
    options.push_back({"+ backgroundness", bg});
    oc::Params pp = d;
    pp.saliency_postprocess = true;
    options.push_back({"+ smoothing and contrast stretch", pp});
    oc::Params mbplus = d;
    mbplus.saliency_median = 5;
    mbplus.saliency_backgroundness = true;
    mbplus.saliency_postprocess = true;
    options.push_back({"MB+ (median + backgroundness + post-processing)", mbplus});
    oc::Params big = d;
    big.saliency_max_side = 640;
    options.push_back({"max side 640 px", big});
    oc::Params border = d;
    border.reject_border_regions = false;
    options.push_back({"border regions kept", border});
    oc::Params by_area = d;
    by_area.saliency_rank_by_area = true;
    options.push_back({"ranked by area (the paper) instead of saliency mass", by_area});
    std::printf("\n## One-frame detector options: best-ranked region on frames 1, 6, 11, ... of the first %d\n\n",
                max_frames);
    std::printf("| option | mean IoU (all) | centre <= 20 px (all) | mean IoU (non-flying) | centre <= 20 px (flying) |\n");
    std::printf("|---|---|---|---|---|\n");
    for (const Option& o : options) {
      oc::SaliencyDetector od(o.p);
      double iou_all = 0.0, iou_nf = 0.0;
      int n_all = 0, n_nf = 0, hit_all = 0, hit_fly = 0, n_fly = 0;
      for (size_t k = 0; k < seqs.size(); ++k)
        for (size_t i = 0; i < all_frames[k].size(); i += 5) {
          const auto& r = od.detect(all_frames[k][i]);
          const float v = r.empty() ? 0.0f : iou(r[0].box, seqs[k].gt[i]);
          const bool hit = !r.empty() && centreError(r[0].box, seqs[k].gt[i]) <= 20.0f;
          iou_all += v;
          ++n_all;
          hit_all += hit;
          if (isFlying(seqs[k].name)) {
            ++n_fly;
            hit_fly += hit;
          } else {
            iou_nf += v;
            ++n_nf;
          }
        }
      std::printf("| %s | %.3f | %d/%d | %.3f | %d/%d |\n", o.name, n_all ? iou_all / n_all : 0.0, hit_all, n_all,
                  n_nf ? iou_nf / n_nf : 0.0, hit_fly, n_fly);
    }
  }

  std::printf("\n## AutoInitializer (defaults), first %d frames\n\n", max_frames);
  std::printf("| sequence | flying | first confirmed box | centre err (px) | IoU | frame | within 20 px in 1st second | ms/frame |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  int flying = 0, flying_ok = 0;
  for (size_t k = 0; k < seqs.size(); ++k) {
    const AutoResult r = runAuto(seqs[k], all_frames[k], variants[0].p);
    const bool ok = r.frame > 0 && r.frame <= first_second && r.error <= 20.0f;
    if (isFlying(seqs[k].name)) {
      ++flying;
      flying_ok += ok;
    }
    char err[32] = "-", io[32] = "-", fr[32] = "-";
    if (r.frame > 0) {
      std::snprintf(err, sizeof err, "%.1f", r.error);
      std::snprintf(io, sizeof io, "%.2f", r.iou);
      std::snprintf(fr, sizeof fr, "%d", r.frame);
    }
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %.2f |\n", seqs[k].name.c_str(),
                isFlying(seqs[k].name) ? "yes" : "no", r.frame > 0 ? "yes" : "none", err, io, fr,
                ok ? "**yes**" : "no", r.ms);
  }
  std::printf("\nFlying clips with a first box within 20 px inside the first %d frames: %d of %d\n",
              first_second, flying_ok, flying);

  std::printf("\n## Cue ablation: centre error of the first confirmed box @ its frame\n\n| variant |");
  for (const Sequence& s : seqs) std::printf(" %s |", s.name.c_str());
  std::printf(" flying ok |\n|---|");
  for (size_t k = 0; k <= seqs.size(); ++k) std::printf("---|");
  std::printf("\n");
  for (const Variant& v : variants) {
    std::printf("| %s |", v.name);
    int ok = 0;
    for (size_t k = 0; k < seqs.size(); ++k) {
      const AutoResult r = runAuto(seqs[k], all_frames[k], v.p);
      const bool good = r.frame > 0 && r.frame <= first_second && r.error <= 20.0f;
      if (isFlying(seqs[k].name)) ok += good;
      std::printf(" %s%s%s |", good ? "**" : "", fmtAuto(r).c_str(), good ? "**" : "");
    }
    std::printf(" %d/%d |\n", ok, flying);
  }
  return 0;
}
