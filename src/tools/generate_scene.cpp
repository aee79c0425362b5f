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

#include "command_line.h"
#include "obstacle_tracker/scene/scene_generator.h"
#include "obstacle_tracker/scene/scene_io.h"

namespace os = obstacle_tracker::scene;

namespace {

bool endsWith(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  os::ScenarioConfig cfg;
  cfg.name = "demo";
  std::string out, format, size;
  bool quiet = false, list = false;
  CLI::App app{
      "Renders a reproducible flight scene with ground truth (docs/scenes.md): an OTB-layout folder\n"
      "(img/ + groundtruth_rect.txt + groundtruth_multi.csv + scene.yaml) or, when --out ends in\n"
      ".mp4/.avi, a video with the same side files next to it.",
      "generate_scene"};
  obstacle_tracker::tools::setToolDefaults(app);
  app.add_flag("--list", list, "name the base scenarios and the modifiers, and exit");
  app.add_option("--scenario", cfg.name, "scenario, NAME[+MODIFIER...] (see --list)")
      ->type_name("NAME")
      ->capture_default_str();
  app.add_option("--seed", cfg.seed, "scene seed")
      ->type_name("N")
      ->capture_default_str()
      ->check(obstacle_tracker::tools::decimalUnsigned64());
  app.add_option("--frames", cfg.frames, "frames (0: the scenario's default length)")
      ->type_name("N")
      ->capture_default_str();
  app.add_option("--size", size, "frame size (default 640x480)")->type_name("WxH");
  app.add_flag("--mono16", cfg.mono16, "16-bit thermal-like grey frames instead of 8-bit BGR (png only)");
  app.add_option("--fps", cfg.fps, "frame rate, in (0, 1000]")->type_name("F")->capture_default_str();
  app.add_option("--format", format, "image format of a folder (default jpg; png for --mono16)")
      ->type_name("jpg|png");
  app.add_flag("-q,--quiet", quiet, "no progress and no summary on standard error");
  app.add_option("--out", out, "the output: a folder, or a video when it ends in .mp4 or .avi (required)")
      ->type_name("DIR|VIDEO");
  if (const auto code = obstacle_tracker::tools::parseCommandLine(app, argc, argv)) return *code;
  if (list) {
    std::cout << "Base scenarios (combine with modifiers: BASE+MOD+MOD, e.g. approach+jitter+noise):\n";
    for (const auto& d : os::listScenarios())
      if (!d.modifier) std::cout << "  " << d.name << std::string(d.name.size() < 14 ? 14 - d.name.size() : 1, ' ') << d.description << "\n";
    std::cout << "Modifiers:\n";
    for (const auto& d : os::listScenarios())
      if (d.modifier) std::cout << "  " << d.name << std::string(d.name.size() < 14 ? 14 - d.name.size() : 1, ' ') << d.description << "\n";
    return obstacle_tracker::tools::finishStandardOutput("generate_scene");
  }
  if (!size.empty() && !obstacle_tracker::tools::parseSize(size, "xX", &cfg.size)) {
    return obstacle_tracker::tools::usageError(app, "--size wants WxH, got " + size);
  }
  if (out.empty()) return obstacle_tracker::tools::usageError(app, "--out DIR|VIDEO is required");
  try {
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
  } catch (const std::invalid_argument& e) {  // a bad scenario name, size, fps or format
    return obstacle_tracker::tools::usageError(app, e.what());
  } catch (const std::exception& e) {
    std::cerr << "generate_scene: " << e.what() << "\n";
    return 1;
  }
}
