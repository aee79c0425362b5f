// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// score_boxes BOXES --gt FILE
// score_boxes --gt FILE --print-gt
// score_boxes --describe SEQUENCE [--gt FILE]
//
// Scores a tracker's box file (what evaluate writes in OUT/boxes/ and track_sequence writes: one
// `x,y,w,h[,confidence[,time_to_contact]]` line per frame) against a ground-truth file with the
// metrics evaluate uses (eval/metrics.h), and prints them as `key=value` lines, so that scripts
// (scripts/score_bag.py) score with the one implementation instead of a copy. --print-gt prints
// the ground truth as the package reads it instead (`x,y,w,h` per frame, `0,0,0,0` where the
// target is absent), for scripts that need its boxes. --describe prints what the package finds in
// a sequence folder or video (eval::Sequence: its frame files in order, frame rate, ground truth),
// so that scripts/sequence_to_bag.py reads a sequence as evaluate and track_sequence do instead of
// searching for its files with rules of its own.
// Exit codes: 0 success, 1 input error (a file missing or malformed, box and ground-truth counts
// that differ), 2 usage error.
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "command_line.h"
#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/eval/sequence.h"

namespace ev = obstacle_tracker::eval;

namespace {

struct Options {
  std::string boxes, gt, describe;
  bool print_gt = false;
};

// Reads the command line into *o. Returns nothing when the tool is to run, otherwise the code to
// exit with (0 after --help, 2 after a usage error; both already printed).
std::optional<int> parse(int argc, char** argv, Options* o) {
  CLI::App app{"Scores a tracker's box file against a ground-truth file with the metrics of evaluate, or "
               "describes a sequence as the package reads it.",
               "score_boxes"};
  obstacle_tracker::tools::setToolDefaults(app);
  app.add_option("BOXES", o->boxes,
                 "the tracker's boxes, one x,y,w,h[,confidence[,time_to_contact]] line per frame "
                 "(0,0,0,0 where it reported nothing; confidence 1 when left out)");
  app.add_option("--gt", o->gt, "ground truth, one x,y,w,h (or 8 polygon corners) line per frame")
      ->type_name("FILE");
  app.add_flag("--print-gt", o->print_gt,
               "print the ground truth as read (x,y,w,h per frame, 0,0,0,0 where the target is absent) "
               "instead of scoring");
  app.add_option("--describe", o->describe,
                 "print what is found in a sequence folder or video instead of scoring: name, kind, "
                 "frame_count, fps, video or one file= line per frame, one gt= line per ground-truth "
                 "frame (--gt overrides the sequence's ground-truth file)")
      ->type_name("SEQUENCE");
  app.footer(
      "Output, one key=value per line: frames (all frames), gt_frames (frames with the target present),\n"
      "absent_frames, precision20, auc, mean_centre_error (px; nan when no box was reported where the\n"
      "target is), lost_fraction (OTB, over gt_frames), and when absent_frames > 0 the VOT long-term\n"
      "lt_precision, lt_recall, lt_fscore, lt_threshold. Exit codes: 0 success, 1 input error (a file\n"
      "missing or malformed, box and ground-truth counts that differ), 2 usage error.");
  if (const auto code = obstacle_tracker::tools::parseCommandLine(app, argc, argv)) return code;
  if (!o->describe.empty()) {
    if (o->print_gt || !o->boxes.empty()) {
      return obstacle_tracker::tools::usageError(app, "--describe takes neither BOXES nor --print-gt");
    }
    return std::nullopt;
  }
  if (o->gt.empty()) return obstacle_tracker::tools::usageError(app, "--gt is required");
  if (o->print_gt && !o->boxes.empty()) {
    return obstacle_tracker::tools::usageError(app, "--print-gt takes no BOXES");
  }
  if (!o->print_gt && o->boxes.empty()) return obstacle_tracker::tools::usageError(app, "BOXES is required");
  return std::nullopt;
}

// One box per line, each line prefixed by `prefix`.
void printGroundTruth(const std::vector<cv::Rect2f>& gt, const char* prefix = "") {
  for (const cv::Rect2f& b : gt) {
    if (ev::isAbsent(b)) {
      std::printf("%s0,0,0,0\n", prefix);
    } else {
      std::printf("%s%.9g,%.9g,%.9g,%.9g\n", prefix, b.x, b.y, b.width, b.height);
    }
  }
}

const char* kindName(ev::Sequence::Kind kind) {
  switch (kind) {
    case ev::Sequence::Kind::kOtbFolder: return "otb_folder";
    case ev::Sequence::Kind::kImageFolder: return "image_folder";
    case ev::Sequence::Kind::kVideo: return "video";
  }
  return "unknown";
}

void printValue(const char* key, double value) { std::printf("%s=%.10g\n", key, value); }

int flushOutput() { return obstacle_tracker::tools::finishStandardOutput("score_boxes"); }

int score(const Options& o, const std::vector<cv::Rect2f>& gt) {
  const ev::TrackerBoxes boxes = ev::loadTrackerBoxes(o.boxes);
  if (boxes.boxes.empty()) throw std::runtime_error("no box in '" + o.boxes + "'");
  if (boxes.boxes.size() != gt.size()) {
    throw std::runtime_error("'" + o.boxes + "' has " + std::to_string(boxes.boxes.size()) + " boxes for " +
                             std::to_string(gt.size()) + " ground-truth frames in '" + o.gt +
                             "' (one line per frame in each)");
  }
  const ev::FrameErrors errors = ev::frameErrors(boxes.boxes, gt);
  const ev::OtbScores otb = ev::otbScores(errors);
  std::printf("frames=%zu\ngt_frames=%d\nabsent_frames=%d\n", gt.size(), otb.frames, errors.absent_gt_frames);
  printValue("precision20", otb.precision20);
  printValue("auc", otb.auc);
  printValue("mean_centre_error", otb.mean_centre_error);
  printValue("lost_fraction", otb.lost_fraction);
  // Long-term scores only where the target leaves the view, as in evaluate's results.
  if (errors.absent_gt_frames > 0) {
    const ev::LongTermScores lt = ev::longTermScores(boxes.boxes, boxes.confidence, gt);
    printValue("lt_precision", lt.precision);
    printValue("lt_recall", lt.recall);
    printValue("lt_fscore", lt.fscore);
    printValue("lt_threshold", lt.threshold);
  }
  return flushOutput();
}

int describe(const Options& o) {
  const ev::Sequence sequence(o.describe, o.gt);
  std::printf("name=%s\nkind=%s\nframe_count=%d\n", sequence.name().c_str(), kindName(sequence.kind()),
              sequence.frameCount());
  printValue("fps", sequence.fps());
  if (sequence.kind() == ev::Sequence::Kind::kVideo) std::printf("video=%s\n", sequence.videoPath().c_str());
  for (const std::string& file : sequence.files()) std::printf("file=%s\n", file.c_str());
  printGroundTruth(sequence.groundTruth(), "gt=");
  return flushOutput();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto code = parse(argc, argv, &o)) return *code;
  try {
    if (!o.describe.empty()) return describe(o);
    const std::vector<cv::Rect2f> gt = ev::loadGroundTruth(o.gt);
    if (o.print_gt) {
      printGroundTruth(gt);
      return flushOutput();
    }
    return score(o, gt);
  } catch (const std::exception& e) {
    std::cerr << "score_boxes: error: " << e.what() << "\n";
    return 1;
  }
}
