// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// track_sequence INPUT [--output FILE] [--init auto|gt|x,y,w,h] [--params FILE] [--gt FILE]
//                [--overlay OUT] [--quiet]
//
// Runs core::Pipeline over an OTB folder, a folder of images or a video, and writes one line per
// frame, `x,y,w,h,confidence,time_to_contact` of the main obstacle (time to contact in seconds,
// `inf` when not closing; `0,0,0,0,0,inf` when none). Prints the core's
// frames per second at the end (only Pipeline::process / startTrack are timed; decoding,
// conversion, drawing and writing are not). Exit codes: 0 success, 1 input/output error,
// 2 usage error.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "command_line.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/eval/sequence.h"

namespace fs = std::filesystem;
namespace core = obstacle_tracker::core;
namespace eval = obstacle_tracker::eval;

namespace {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string input, output, init = "auto", params_file, gt_file, overlay;
  bool quiet = false;
  bool have_box = false;
  cv::Rect2f box;
};

// Reads the command line into *o. Returns nothing when the tool is to run, otherwise the code to
// exit with (0 after --help, 2 after a usage error; both already printed).
std::optional<int> parseArgs(int argc, char** argv, Options* o) {
  CLI::App app{"Runs the obstacle tracker's pipeline over an OTB folder, a folder of images or a video.",
               "track_sequence"};
  obstacle_tracker::tools::setToolDefaults(app);
  app.add_option("INPUT", o->input, "an OTB folder (img/ + groundtruth_rect.txt), a folder of images, or a video")
      ->required();
  app.add_option("-o,--output", o->output, "where the per-frame lines go (default: standard output)")
      ->type_name("FILE");
  app.add_option("--init", o->init,
                 "auto (default): the pipeline finds the obstacle itself;\n"
                 "gt: start from the first ground-truth box; x,y,w,h: start from this box")
      ->type_name("MODE");
  app.add_option("--params", o->params_file, "YAML parameters on top of the defaults (see print_params --yaml)")
      ->type_name("FILE");
  app.add_option("--gt", o->gt_file, "ground-truth file (overrides the one found next to INPUT)")->type_name("FILE");
  app.add_option("--overlay", o->overlay,
                 "draw boxes, ids, confidence and state: a video (.mp4, .avi, .mkv) or a folder")
      ->type_name("OUT");
  app.add_flag("-q,--quiet", o->quiet, "no progress bar and no summary on standard error");
  app.footer(
      "Output: one line per frame, x,y,w,h,confidence,time_to_contact of the main obstacle\n"
      "        (time to contact in s, inf when not closing; 0,0,0,0,0,inf when none).\n"
      "Exit codes: 0 success, 1 input/output error, 2 usage error.");
  if (const auto code = obstacle_tracker::tools::parseCommandLine(app, argc, argv)) return code;
  if (o->init != "auto" && o->init != "gt") {
    cv::Rect2f b;
    if (!eval::parseGroundTruthLine(o->init, &b) || !eval::isPresent(b)) {
      return obstacle_tracker::tools::usageError(
          app, "--init must be auto, gt or x,y,w,h with w,h > 0 (got '" + o->init + "')");
    }
    o->have_box = true;
    o->box = b;
  }
  return std::nullopt;
}

bool isVideoPath(const std::string& p) {
  std::string ext = fs::path(p).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".mp4" || ext == ".avi" || ext == ".mkv" || ext == ".mov";
}

cv::Scalar stateColour(core::TrackState s) {
  switch (s) {
    case core::TrackState::kTracking:
      return {0, 220, 0};
    case core::TrackState::kRedetecting:
      return {0, 200, 255};
    case core::TrackState::kLost:
      return {0, 0, 255};
    default:
      return {200, 200, 200};
  }
}

void drawOverlay(cv::Mat& img, const std::vector<core::Obstacle>& obs, const cv::Rect2f& gt, int index) {
  if (eval::isPresent(gt)) cv::rectangle(img, gt, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  for (const auto& o : obs) {
    const cv::Scalar c = stateColour(o.state);
    cv::rectangle(img, o.box, c, 2, cv::LINE_AA);
    char label[128];
    if (std::isfinite(o.time_to_contact)) {
      std::snprintf(label, sizeof(label), "#%d %.2f %s ttc %.1fs", o.id, o.confidence, core::toString(o.state),
                    o.time_to_contact);
    } else {
      std::snprintf(label, sizeof(label), "#%d %.2f %s", o.id, o.confidence, core::toString(o.state));
    }
    const cv::Point org(static_cast<int>(o.box.x), std::max(12, static_cast<int>(o.box.y) - 4));
    cv::putText(img, label, org, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
    cv::putText(img, label, org, cv::FONT_HERSHEY_SIMPLEX, 0.4, c, 1, cv::LINE_AA);
  }
  char text[64];
  std::snprintf(text, sizeof(text), "frame %d  %s", index + 1, obs.empty() ? "searching" : "");
  cv::putText(img, text, cv::Point(6, img.rows - 8), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(img, text, cv::Point(6, img.rows - 8), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
}

void progress(int done, int total, double core_seconds) {
  const int width = 30;
  const double frac = total > 0 ? std::min(1.0, static_cast<double>(done) / total) : 0.0;
  const int filled = static_cast<int>(frac * width);
  std::string bar(static_cast<std::size_t>(filled), '=');
  if (filled < width) bar += '>';
  bar.resize(width, ' ');
  const double fps = core_seconds > 0.0 ? done / core_seconds : 0.0;
  if (total > 0) {
    std::fprintf(stderr, "\r[%s] %d/%d  core %.0f fps ", bar.c_str(), done, total, fps);
  } else {
    std::fprintf(stderr, "\r%d frames  core %.0f fps ", done, fps);
  }
  std::fflush(stderr);
}

int run(const Options& opt) {
  core::Params params;
  if (!opt.params_file.empty()) {
    std::vector<std::string> messages;
    params = core::loadParamsFile(opt.params_file, &messages);  // throws runtime_error
    for (const auto& m : messages) std::cerr << "track_sequence: " << opt.params_file << ": " << m << "\n";
  }
  eval::Sequence seq(opt.input, opt.gt_file);
  if (opt.init == "gt" && !seq.hasGroundTruth()) {
    throw UsageError("--init gt but '" + opt.input + "' has no ground truth (give --gt FILE)");
  }

  std::ofstream file;
  std::ostream* out = &std::cout;
  if (!opt.output.empty()) {
    const fs::path parent = fs::path(opt.output).parent_path();
    std::error_code ec;
    if (!parent.empty()) fs::create_directories(parent, ec);
    file.open(opt.output);
    if (!file) throw std::runtime_error("cannot write '" + opt.output + "'");
    out = &file;
  }

  cv::VideoWriter writer;
  const bool overlay_video = !opt.overlay.empty() && isVideoPath(opt.overlay);
  if (!opt.overlay.empty() && !overlay_video) {
    std::error_code ec;
    fs::create_directories(opt.overlay, ec);
    if (!fs::is_directory(opt.overlay)) throw std::runtime_error("cannot create overlay folder '" + opt.overlay + "'");
  }

  core::Pipeline pipeline(params);
  eval::FrameConverter converter;  // the nodelet's stretch for 16-bit frames
  const bool show_progress = !opt.quiet && isatty(fileno(stderr));
  const int total = seq.frameCount();
  const double fps = seq.fps();

  cv::Mat raw, canvas;
  double core_seconds = 0.0;
  int index = 0, core_frames = 0;
  bool started = opt.init == "auto";
  char line[160];
  using Clock = std::chrono::steady_clock;
  auto last_progress = Clock::now();
  while (seq.read(raw)) {
    const cv::Mat& frame = converter.convert(raw);
    const double stamp = index / fps;
    const std::vector<core::Obstacle>* obs = nullptr;
    const auto t0 = Clock::now();
    if (!started) {
      cv::Rect2f box;
      if (opt.have_box) {
        box = opt.box;
      } else {
        box = seq.groundTruthAt(index);
      }
      if (eval::isPresent(box)) {
        obs = &pipeline.startTrack(frame, stamp, box);
        started = true;
      }
    } else {
      obs = &pipeline.process(frame, stamp);
    }
    const auto t1 = Clock::now();
    if (obs != nullptr) {
      core_seconds += std::chrono::duration<double>(t1 - t0).count();
      ++core_frames;
    }

    const core::Obstacle* main = nullptr;
    if (obs != nullptr) {
      for (const auto& o : *obs) {
        if (o.state == core::TrackState::kTracking || o.state == core::TrackState::kRedetecting) {
          main = &o;
          break;
        }
      }
    }
    if (main != nullptr) {
      char ttc[32] = "inf";
      if (std::isfinite(main->time_to_contact)) std::snprintf(ttc, sizeof(ttc), "%.3f", main->time_to_contact);
      std::snprintf(line, sizeof(line), "%.2f,%.2f,%.2f,%.2f,%.3f,%s\n", main->box.x, main->box.y, main->box.width,
                    main->box.height, main->confidence, ttc);
    } else {
      std::snprintf(line, sizeof(line), "0,0,0,0,0,inf\n");
    }
    *out << line;
    if (!*out) throw std::runtime_error("write error on '" + (opt.output.empty() ? "stdout" : opt.output) + "'");

    if (!opt.overlay.empty()) {
      if (frame.channels() == 1) {
        cv::cvtColor(frame, canvas, cv::COLOR_GRAY2BGR);
      } else {
        frame.copyTo(canvas);
      }
      static const std::vector<core::Obstacle> kNone;
      drawOverlay(canvas, obs != nullptr ? *obs : kNone, seq.groundTruthAt(index), index);
      if (overlay_video) {
        if (!writer.isOpened()) {
          const std::string ext = fs::path(opt.overlay).extension().string();
          const int fourcc = (ext == ".avi" || ext == ".AVI") ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G')
                                                              : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
          if (!writer.open(opt.overlay, fourcc, fps, canvas.size())) {
            throw std::runtime_error("cannot write overlay video '" + opt.overlay + "'");
          }
        }
        writer.write(canvas);
      } else {
        char name[32];
        std::snprintf(name, sizeof(name), "%06d.jpg", index + 1);
        const std::string path = (fs::path(opt.overlay) / name).string();
        if (!cv::imwrite(path, canvas)) throw std::runtime_error("cannot write '" + path + "'");
      }
    }
    ++index;
    if (show_progress && (Clock::now() - last_progress > std::chrono::milliseconds(100))) {
      progress(index, total, core_seconds);
      last_progress = Clock::now();
    }
  }
  if (show_progress) {
    progress(index, total, core_seconds);
    std::fprintf(stderr, "\n");
  }
  if (index == 0) throw std::runtime_error("no frame could be read from '" + opt.input + "'");
  if (opt.init != "auto" && !started) {
    std::cerr << "track_sequence: warning: the start box was never present; nothing was tracked\n";
  }
  if (!opt.quiet) {
    const double core_fps = core_seconds > 0.0 ? core_frames / core_seconds : 0.0;
    std::fprintf(stderr, "track_sequence: %s: %d frames, core %.1f fps (%.2f ms/frame, decoding excluded)\n",
                 seq.name().c_str(), index, core_fps, core_frames > 0 ? 1000.0 * core_seconds / core_frames : 0.0);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  if (const auto code = parseArgs(argc, argv, &opt)) return *code;
  try {
    return run(opt);
  } catch (const UsageError& e) {
    std::cerr << "track_sequence: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "track_sequence: error: " << e.what() << "\n";
    return 1;
  }
}
