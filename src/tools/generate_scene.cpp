// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// generate_scene --scenario NAME --seed N [--frames N] [--size WxH] [--mono16] [--fps F]
//                [--format jpg|png] [--quiet] --out DIR|VIDEO
// generate_scene --list
// Renders a reproducible flight scene with ground truth (docs/scenes.md): an OTB-layout folder
// (img/ + groundtruth_rect.txt + groundtruth_multi.csv + scene.yaml) or, when --out ends in
// .mp4/.avi, a video with the same side files next to it.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>

#include "obstacle_tracker/scene/scene_generator.h"
#include "obstacle_tracker/scene/scene_io.h"

namespace os = obstacle_tracker::scene;

namespace {

void usage(std::ostream& o) {
  o << "usage: generate_scene --scenario NAME[+MODIFIER...] --seed N [--frames N] [--size WxH] [--mono16]\n"
       "                      [--fps F] [--format jpg|png] [--quiet] --out DIR|VIDEO.mp4|VIDEO.avi\n"
       "       generate_scene --list\n";
}

bool endsWith(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  os::ScenarioConfig cfg;
  cfg.name = "demo";
  std::string out, format;
  bool quiet = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
        return argv[++i];
      };
      if (a == "--list") {
        std::cout << "Base scenarios (combine with modifiers: BASE+MOD+MOD, e.g. approach+jitter+noise):\n";
        for (const auto& d : os::listScenarios())
          if (!d.modifier) std::cout << "  " << d.name << std::string(d.name.size() < 14 ? 14 - d.name.size() : 1, ' ') << d.description << "\n";
        std::cout << "Modifiers:\n";
        for (const auto& d : os::listScenarios())
          if (d.modifier) std::cout << "  " << d.name << std::string(d.name.size() < 14 ? 14 - d.name.size() : 1, ' ') << d.description << "\n";
        return 0;
      } else if (a == "--scenario") {
        cfg.name = value();
      } else if (a == "--seed") {
        cfg.seed = std::stoull(value());
      } else if (a == "--frames") {
        cfg.frames = std::stoi(value());
      } else if (a == "--size") {
        const std::string v = value();
        const auto x = v.find_first_of("xX");
        if (x == std::string::npos) throw std::invalid_argument("--size wants WxH, got " + v);
        cfg.size = cv::Size(std::stoi(v.substr(0, x)), std::stoi(v.substr(x + 1)));
      } else if (a == "--mono16") {
        cfg.mono16 = true;
      } else if (a == "--fps") {
        cfg.fps = std::stod(value());
      } else if (a == "--format") {
        format = value();
      } else if (a == "--out") {
        out = value();
      } else if (a == "--quiet" || a == "-q") {
        quiet = true;
      } else if (a == "--help" || a == "-h") {
        usage(std::cout);
        return 0;
      } else {
        throw std::invalid_argument("unknown argument " + a);
      }
    }
    if (out.empty()) throw std::invalid_argument("--out DIR|VIDEO is required");
    os::SceneGenerator gen(cfg);
    os::WriteOptions wo;
    wo.image_format = format;
    if (!quiet)
      wo.progress = [](int f, int n) {
        if (f == n || f % 25 == 0) std::fprintf(stderr, "\rgenerate_scene: frame %d/%d", f, n);
        if (f == n) std::fprintf(stderr, "\n");
      };
    const bool video = endsWith(out, ".mp4") || endsWith(out, ".avi") || endsWith(out, ".MP4") || endsWith(out, ".AVI");
    if (video)
      os::writeVideo(gen, out, wo);
    else
      os::writeOtbSequence(gen, out, wo);
    if (!quiet)
      std::fprintf(stderr, "generate_scene: %s seed %llu, %d frames %dx%d%s -> %s\n", cfg.name.c_str(),
                   static_cast<unsigned long long>(cfg.seed), gen.frameCount(), gen.size().width, gen.size().height,
                   cfg.mono16 ? " mono16" : "", out.c_str());
    return 0;
  } catch (const std::invalid_argument& e) {
    std::cerr << "generate_scene: " << e.what() << "\n";
    usage(std::cerr);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "generate_scene: " << e.what() << "\n";
    return 1;
  }
}
