// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// scene_boxes --scenario NAME --seed N [--frames N] [--size WxH] [--grey] [--init gt|auto]
// Tracks a generated flight scene rendered in memory (no image files, so it also runs where
// OpenCV has no image I/O: the ARM64 cross-build under qemu-user) and prints, per frame, the
// main obstacle's box and confidence with every float digit, then the OTB scores against the
// scene's ground truth. Two machines that print the same lines track identically; the last line
// (`# scores ...`) is what the cross-machine check compares within its tolerance.
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace oc = obstacle_tracker::core;
namespace os = obstacle_tracker::scene;
namespace ev = obstacle_tracker::eval;

namespace {

void usage(std::ostream& o) {
  o << "usage: scene_boxes --scenario NAME[+MODIFIER...] --seed N [--frames N] [--size WxH] [--grey]\n"
       "                   [--init gt|auto]\n";
}

struct Options {
  std::string scenario = "crossing";
  unsigned long long seed = 3;
  int frames = 150;
  cv::Size size{480, 360};
  bool grey = false;
  bool from_box = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
      return argv[++i];
    };
    if (a == "--scenario") {
      o.scenario = value();
    } else if (a == "--seed") {
      o.seed = std::stoull(value());
    } else if (a == "--frames") {
      o.frames = std::stoi(value());
    } else if (a == "--size") {
      const std::string v = value();
      const std::size_t x = v.find('x');
      if (x == std::string::npos) throw std::invalid_argument("--size wants WxH, got " + v);
      o.size = cv::Size(std::stoi(v.substr(0, x)), std::stoi(v.substr(x + 1)));
    } else if (a == "--grey") {
      o.grey = true;
    } else if (a == "--init") {
      const std::string v = value();
      if (v != "gt" && v != "auto") throw std::invalid_argument("--init wants gt or auto, got " + v);
      o.from_box = v == "gt";
    } else if (a == "-h" || a == "--help") {
      usage(std::cout);
      std::exit(0);
    } else {
      throw std::invalid_argument("unknown argument " + a);
    }
  }
  if (o.frames < 1) throw std::invalid_argument("--frames must be at least 1");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    os::SceneGenerator gen = os::makeScenario(o.scenario, o.seed, o.frames, o.size);
    oc::Pipeline pipeline;
    std::vector<cv::Rect2f> predicted, truth;
    bool started = !o.from_box;
    cv::Mat frame;
    for (int i = 0; i < gen.frameCount(); ++i) {
      os::FrameTruth t;
      gen.renderFrame(i, frame, &t);
      if (o.grey && frame.channels() == 3) cv::cvtColor(frame, frame, cv::COLOR_BGR2GRAY);
      const os::ObstacleTruth* main = t.find(1);
      const cv::Rect2f gt = (main != nullptr && main->visible) ? main->box : cv::Rect2f();
      const double stamp = i / gen.fps();
      const std::vector<oc::Obstacle>* out = nullptr;
      if (!started && gt.area() > 0) {
        out = &pipeline.startTrack(frame, stamp, gt);
        started = true;
      } else if (started) {
        out = &pipeline.process(frame, stamp);
      }
      cv::Rect2f box;
      float confidence = 0.0f;
      if (out != nullptr && !out->empty()) {
        box = out->front().box;
        confidence = out->front().confidence;
      }
      std::printf("%d %.9g %.9g %.9g %.9g %.9g\n", i, box.x, box.y, box.width, box.height, confidence);
      predicted.push_back(box);
      truth.push_back(gt);
    }
    const ev::OtbScores s = ev::otbScores(predicted, truth);
    std::printf("# scores precision20 %.4f auc %.4f\n", s.precision20, s.auc);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "scene_boxes: " << e.what() << "\n";
    usage(std::cerr);
    return 2;
  }
}
