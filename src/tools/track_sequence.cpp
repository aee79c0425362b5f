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
#include <opencv2/videoio.hpp>

#include "command_line.h"
#include "obstacle_tracker/core/overlay_drawing.h"
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

core::Params loadParams(const Options& opt) {
  core::Params params;
  if (!opt.params_file.empty()) {
    std::vector<std::string> messages;
    params = core::loadParamsFile(opt.params_file, &messages);  // throws runtime_error
    for (const auto& m : messages) std::cerr << "track_sequence: " << opt.params_file << ": " << m << "\n";
  }
  return params;
}

// Opens --output (creating its folder) into *file; standard output when none is given.
std::ostream& openOutput(const std::string& output, std::ofstream* file) {
  if (output.empty()) return std::cout;
  const fs::path parent = fs::path(output).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  file->open(output);
  if (!*file) throw std::runtime_error("cannot write '" + output + "'");
  return *file;
}

// --overlay: the frames with the boxes drawn, into a video or as numbered JPEGs in a folder.
class OverlayOutput {
 public:
  // Creates the folder now (a video is opened at the first frame, when its size is known).
  explicit OverlayOutput(const std::string& target) : target_(target), video_(isVideoPath(target)) {
    if (!video_) {
      std::error_code ec;
      fs::create_directories(target_, ec);
      if (!fs::is_directory(target_)) throw std::runtime_error("cannot create overlay folder '" + target_ + "'");
    }
  }

  // The overlay of ~debug_image, with the ground truth and a banner of the frame number and the
  // pipeline's state.
  void write(const cv::Mat& frame, const std::vector<core::Obstacle>* obs, core::TrackState state,
             const cv::Rect2f& gt, int index, double fps) {
    static const std::vector<core::Obstacle> kNone;
    const std::vector<core::Obstacle>& obstacles = obs != nullptr ? *obs : kNone;
    char status[96];
    std::snprintf(status, sizeof(status), "frame %d  %s  obstacles: %zu", index + 1, core::toString(state),
                  obstacles.size());
    core::OverlayExtras extras;
    extras.status = status;
    extras.ground_truth = gt;
    core::drawOverlay(frame, obstacles, extras, canvas_);
    if (video_) {
      if (!writer_.isOpened()) openVideo(fps);
      writer_.write(canvas_);
    } else {
      char name[32];
      std::snprintf(name, sizeof(name), "%06d.jpg", index + 1);
      const std::string path = (fs::path(target_) / name).string();
      if (!cv::imwrite(path, canvas_)) throw std::runtime_error("cannot write '" + path + "'");
    }
  }

 private:
  void openVideo(double fps) {
    const std::string ext = fs::path(target_).extension().string();
    const int fourcc = (ext == ".avi" || ext == ".AVI") ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G')
                                                        : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
    if (!writer_.open(target_, fourcc, fps, canvas_.size())) {
      throw std::runtime_error("cannot write overlay video '" + target_ + "'");
    }
  }

  std::string target_;
  bool video_;
  cv::VideoWriter writer_;
  cv::Mat canvas_;
};

// Runs the pipeline frame by frame and times only its calls (Pipeline::process / startTrack).
// With a start box (--init gt or x,y,w,h) nothing runs until the first frame where it is present.
class TimedTracker {
 public:
  TimedTracker(const core::Params& params, const Options& opt, const eval::Sequence& seq)
      : pipeline_(params), opt_(opt), seq_(seq), started_(opt.init == "auto") {}

  // The obstacles of this frame; nullptr while the start box has not been present yet.
  const std::vector<core::Obstacle>* track(const cv::Mat& frame, double stamp, int index) {
    const std::vector<core::Obstacle>* obs = nullptr;
    const auto t0 = Clock::now();
    if (!started_) {
      const cv::Rect2f box = opt_.have_box ? opt_.box : seq_.groundTruthAt(index);
      if (eval::isPresent(box)) {
        obs = &pipeline_.startTrack(frame, stamp, box);
        started_ = true;
      }
    } else {
      obs = &pipeline_.process(frame, stamp);
    }
    const auto t1 = Clock::now();
    if (obs != nullptr) {
      core_seconds_ += std::chrono::duration<double>(t1 - t0).count();
      ++core_frames_;
    }
    return obs;
  }

  bool started() const { return started_; }
  core::TrackState state() const { return pipeline_.state(); }
  double coreSeconds() const { return core_seconds_; }
  int coreFrames() const { return core_frames_; }

 private:
  using Clock = std::chrono::steady_clock;
  core::Pipeline pipeline_;
  const Options& opt_;
  const eval::Sequence& seq_;
  bool started_;
  double core_seconds_ = 0.0;
  int core_frames_ = 0;
};

// The first obstacle being tracked or re-detected; nullptr when there is none.
const core::Obstacle* mainObstacle(const std::vector<core::Obstacle>* obs) {
  if (obs == nullptr) return nullptr;
  for (const auto& o : *obs) {
    if (o.state == core::TrackState::kTracking || o.state == core::TrackState::kRedetecting) return &o;
  }
  return nullptr;
}

// One line per frame: x,y,w,h,confidence,time_to_contact of the main obstacle, or
// 0,0,0,0,0,inf when there is none.
void writeFrameLine(std::ostream& out, const core::Obstacle* obstacle, const std::string& output) {
  char line[160];
  if (obstacle != nullptr) {
    char ttc[32] = "inf";
    if (std::isfinite(obstacle->time_to_contact)) std::snprintf(ttc, sizeof(ttc), "%.3f", obstacle->time_to_contact);
    std::snprintf(line, sizeof(line), "%.2f,%.2f,%.2f,%.2f,%.3f,%s\n", obstacle->box.x, obstacle->box.y,
                  obstacle->box.width, obstacle->box.height, obstacle->confidence, ttc);
  } else {
    std::snprintf(line, sizeof(line), "0,0,0,0,0,inf\n");
  }
  out << line;
  if (!out) throw std::runtime_error("write error on '" + (output.empty() ? "stdout" : output) + "'");
}

// The progress bar on standard error, redrawn at most every 100 ms; off with --quiet or when
// standard error is not a terminal.
class ProgressBar {
 public:
  ProgressBar(bool enabled, int total) : enabled_(enabled), total_(total), last_(Clock::now()) {}

  void update(int done, double core_seconds) {
    if (enabled_ && (Clock::now() - last_ > std::chrono::milliseconds(100))) {
      progress(done, total_, core_seconds);
      last_ = Clock::now();
    }
  }

  void finish(int done, double core_seconds) {
    if (!enabled_) return;
    progress(done, total_, core_seconds);
    std::fprintf(stderr, "\n");
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  int total_;
  Clock::time_point last_;
};

void printSummary(const eval::Sequence& seq, int frames, const TimedTracker& tracker) {
  const double core_seconds = tracker.coreSeconds();
  const int core_frames = tracker.coreFrames();
  const double core_fps = core_seconds > 0.0 ? core_frames / core_seconds : 0.0;
  std::fprintf(stderr, "track_sequence: %s: %d frames, core %.1f fps (%.2f ms/frame, decoding excluded)\n",
               seq.name().c_str(), frames, core_fps, core_frames > 0 ? 1000.0 * core_seconds / core_frames : 0.0);
}

int run(const Options& opt) {
  const core::Params params = loadParams(opt);
  eval::Sequence seq(opt.input, opt.gt_file);
  if (opt.init == "gt" && !seq.hasGroundTruth()) {
    throw UsageError("--init gt but '" + opt.input + "' has no ground truth (give --gt FILE)");
  }
  std::ofstream file;
  std::ostream& out = openOutput(opt.output, &file);
  std::optional<OverlayOutput> overlay;
  if (!opt.overlay.empty()) overlay.emplace(opt.overlay);

  TimedTracker tracker(params, opt, seq);
  eval::FrameConverter converter;  // the nodelet's stretch for 16-bit frames
  ProgressBar progress_bar(!opt.quiet && isatty(fileno(stderr)), seq.frameCount());
  const double fps = seq.fps();
  cv::Mat raw;
  int index = 0;
  while (seq.read(raw)) {
    const cv::Mat& frame = converter.convert(raw);
    const std::vector<core::Obstacle>* obs = tracker.track(frame, index / fps, index);
    writeFrameLine(out, mainObstacle(obs), opt.output);
    if (overlay) overlay->write(frame, obs, tracker.state(), seq.groundTruthAt(index), index, fps);
    ++index;
    progress_bar.update(index, tracker.coreSeconds());
  }
  progress_bar.finish(index, tracker.coreSeconds());
  // Lines sit in the stream's buffer until here: a full disk or a closed pipe shows at the flush.
  out.flush();
  if (!out) throw std::runtime_error("write error on '" + (opt.output.empty() ? "stdout" : opt.output) + "'");
  if (index == 0) throw std::runtime_error("no frame could be read from '" + opt.input + "'");
  if (opt.init != "auto" && !tracker.started()) {
    std::cerr << "track_sequence: warning: the start box was never present; nothing was tracked\n";
  }
  if (!opt.quiet) printSummary(seq, index, tracker);
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
