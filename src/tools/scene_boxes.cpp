// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// scene_boxes --scenario NAME --seed N [--frames N] [--size WxH] [--grey] [--init gt|auto]
//             [--save FILE | --load FILE]
// Tracks a generated flight scene rendered in memory (no image files, so it also runs where
// OpenCV has no image I/O: the ARM64 cross-build under qemu-user) and prints, per frame, the
// main obstacle's box and confidence with every float digit, then the OTB scores against the
// scene's ground truth. Two machines that print the same lines track identically; the last line
// (`# scores ...`) is what the cross-machine check compares within its tolerance.
// The renderer is portable arithmetic (docs/scenes.md; SceneGenerator.KnownFrameHashes checks it
// on every build), yet the cross-machine check renders once and compares trackers on the very
// same bytes, so that a difference can only come from the tracker: --save writes the frames and
// their ground truth to FILE (raw bytes, this tool's own format), --load tracks them.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "command_line.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace oc = obstacle_tracker::core;
namespace os = obstacle_tracker::scene;
namespace ev = obstacle_tracker::eval;

namespace {

struct Options {
  std::string scenario = "crossing";
  unsigned long long seed = 3;
  int frames = 150;
  cv::Size size{480, 360};
  bool grey = false;
  bool from_box = false;
  std::string save, load;
};

struct Clip {
  std::vector<cv::Mat> frames;
  std::vector<cv::Rect2f> truth;  // empty box: target absent
  double fps = 30.0;
};

constexpr std::uint32_t kMagic = 0x4F54534Bu;  // file tag of --save / --load

Clip render(const Options& o) {
  os::SceneGenerator gen = os::makeScenario(o.scenario, o.seed, o.frames, o.size);
  Clip c;
  c.fps = gen.fps();
  for (int i = 0; i < gen.frameCount(); ++i) {
    cv::Mat frame;
    os::FrameTruth t;
    gen.renderFrame(i, frame, &t);
    if (o.grey && frame.channels() == 3) cv::cvtColor(frame, frame, cv::COLOR_BGR2GRAY);
    const os::ObstacleTruth* main = t.find(1);
    c.frames.push_back(frame);
    c.truth.push_back((main != nullptr && main->visible) ? main->box : cv::Rect2f());
  }
  return c;
}

template <typename T>
void put(std::ofstream& f, const T& v) {
  f.write(reinterpret_cast<const char*>(&v), sizeof(v));
}
template <typename T>
T get(std::ifstream& f) {
  T v{};
  if (!f.read(reinterpret_cast<char*>(&v), sizeof(v))) throw std::runtime_error("truncated clip file");
  return v;
}

// Little-endian hosts only (x86-64, aarch64): the file is the memory image of the values.
void saveClip(const Clip& c, const std::string& path) {
  std::ofstream f(path, std::ios::binary);
  put(f, kMagic);
  put(f, static_cast<std::uint32_t>(c.frames.size()));
  put(f, c.fps);
  for (std::size_t i = 0; i < c.frames.size(); ++i) {
    const cv::Mat m = c.frames[i].isContinuous() ? c.frames[i] : c.frames[i].clone();
    put(f, static_cast<std::int32_t>(m.rows));
    put(f, static_cast<std::int32_t>(m.cols));
    put(f, static_cast<std::int32_t>(m.type()));
    put(f, c.truth[i]);
    f.write(reinterpret_cast<const char*>(m.data), static_cast<std::streamsize>(m.total() * m.elemSize()));
  }
  if (!f) throw std::runtime_error("cannot write " + path);
}

Clip loadClip(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot open " + path);
  if (get<std::uint32_t>(f) != kMagic) throw std::runtime_error(path + " is not a scene_boxes --save file");
  const std::uint32_t n = get<std::uint32_t>(f);
  Clip c;
  c.fps = get<double>(f);
  for (std::uint32_t i = 0; i < n; ++i) {
    const int rows = get<std::int32_t>(f), cols = get<std::int32_t>(f), type = get<std::int32_t>(f);
    if (rows < 1 || cols < 1 || rows > 10000 || cols > 10000 || (type != CV_8UC1 && type != CV_8UC3)) {
      throw std::runtime_error(path + ": bad frame header");
    }
    c.truth.push_back(get<cv::Rect2f>(f));
    cv::Mat m(rows, cols, type);
    if (!f.read(reinterpret_cast<char*>(m.data), static_cast<std::streamsize>(m.total() * m.elemSize()))) {
      throw std::runtime_error("truncated clip file");
    }
    c.frames.push_back(m);
  }
  return c;
}

// Reads the command line into *o. Returns nothing when the tool is to run, otherwise the code to
// exit with (0 after --help, 2 after a usage error; both already printed).
std::optional<int> parse(int argc, char** argv, Options* o) {
  CLI::App app{
      "Tracks a generated flight scene rendered in memory and prints, per frame, the main obstacle's box "
      "and confidence, then the OTB scores against the scene's ground truth.",
      "scene_boxes"};
  obstacle_tracker::tools::setToolDefaults(app);
  std::string size, init = "auto";
  app.add_option("--scenario", o->scenario, "scenario, NAME[+MODIFIER...] (see generate_scene --list)")
      ->type_name("NAME")
      ->capture_default_str();
  app.add_option("--seed", o->seed, "scene seed")
      ->type_name("N")
      ->capture_default_str()
      ->check(obstacle_tracker::tools::decimalUnsigned64());
  app.add_option("--frames", o->frames, "frames rendered (at least 1)")->type_name("N")->capture_default_str();
  app.add_option("--size", size, "frame size (default 480x360)")->type_name("WxH");
  app.add_flag("--grey", o->grey, "track grey frames (converted from the rendered colour)");
  app.add_option("--init", init, "gt: start from the first ground-truth box; auto: the pipeline finds the obstacle")
      ->type_name("gt|auto")
      ->capture_default_str();
  app.add_option("--save", o->save, "write the frames and their ground truth to FILE (this tool's raw format)")
      ->type_name("FILE");
  app.add_option("--load", o->load, "track the frames of a --save FILE instead of rendering")->type_name("FILE");
  app.footer(
      "Output: one line per frame, `index x y w h confidence` with every float digit, then\n"
      "`# scores precision20 P auc A`.");
  if (const auto code = obstacle_tracker::tools::parseCommandLine(app, argc, argv)) return code;
  if (!size.empty() && !obstacle_tracker::tools::parseSize(size, "x", &o->size)) {
    return obstacle_tracker::tools::usageError(app, "--size wants WxH, got " + size);
  }
  if (init != "gt" && init != "auto") {
    return obstacle_tracker::tools::usageError(app, "--init wants gt or auto, got " + init);
  }
  o->from_box = init == "gt";
  if (o->frames < 1) return obstacle_tracker::tools::usageError(app, "--frames must be at least 1");
  if (!o->save.empty() && !o->load.empty()) {
    return obstacle_tracker::tools::usageError(app, "--save and --load exclude each other");
  }
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto code = parse(argc, argv, &o)) return *code;
  try {
    const Clip clip = o.load.empty() ? render(o) : loadClip(o.load);
    if (!o.save.empty()) saveClip(clip, o.save);
    oc::Pipeline pipeline;
    std::vector<cv::Rect2f> predicted;
    bool started = !o.from_box;
    for (std::size_t i = 0; i < clip.frames.size(); ++i) {
      const double stamp = static_cast<double>(i) / clip.fps;
      const std::vector<oc::Obstacle>* out = nullptr;
      if (!started && clip.truth[i].area() > 0) {
        out = &pipeline.startTrack(clip.frames[i], stamp, clip.truth[i]);
        started = true;
      } else if (started) {
        out = &pipeline.process(clip.frames[i], stamp);
      }
      cv::Rect2f box;
      float confidence = 0.0f;
      if (out != nullptr && !out->empty()) {
        box = out->front().box;
        confidence = out->front().confidence;
      }
      std::printf("%zu %.9g %.9g %.9g %.9g %.9g\n", i, box.x, box.y, box.width, box.height, confidence);
      predicted.push_back(box);
    }
    const std::vector<cv::Rect2f>& truth = clip.truth;
    const ev::OtbScores s = ev::otbScores(predicted, truth);
    std::printf("# scores precision20 %.4f auc %.4f\n", s.precision20, s.auc);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "scene_boxes: " << e.what() << "\n";
    return 2;
  }
}
