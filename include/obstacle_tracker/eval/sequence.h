// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Reading image sequences with ground truth: an OTB-layout folder (img/ + groundtruth_rect.txt),
// a plain folder of images, or a video file (+ an optional ground-truth file). Frames are decoded
// one at a time; FrameConverter turns any decoded frame into what the core accepts (CV_8UC1 or
// CV_8UC3 BGR). Shared by track_sequence and the evaluation tool. Also the box files trackers
// write, read back with the ground truth's rules (score_boxes).
#pragma once

#include <filesystem>
#include <istream>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/core/box_geometry.h"

#include "obstacle_tracker/core/intensity_stretch.h"

namespace obstacle_tracker {
namespace eval {

// ---- Ground truth ------------------------------------------------------------------------------
// One box per frame, x,y,w,h (top-left corner, pixels). An absent target (a NaN anywhere, a
// non-positive width or height, `0,0,0,0`, or an empty line) is the zero box {0,0,0,0}.

// The one rule for a box being there (core::boxIsAbsent, also used by the metrics): a positive,
// finite size at a finite position.
inline bool isPresent(const cv::Rect2f& box) { return !core::boxIsAbsent(box); }

// Parses one line. Separators: commas, tabs, spaces, semicolons (any mix, repeated). 4 values are
// x,y,w,h; 8 values are a polygon x1,y1,...,x4,y4 (VOT), turned into its axis-aligned bounding
// box. Returns false (and leaves *box alone) when the line is not a box (wrong count or a token
// that is not a number); an empty line parses as absent.
bool parseGroundTruthLine(const std::string& line, cv::Rect2f* box);

// Parses a whole file's text: one box per line (CRLF accepted; trailing blank lines dropped; a
// first line that is not numeric is taken as a header and skipped). Throws std::runtime_error
// naming `source` and the line number for any other line that is not a box.
std::vector<cv::Rect2f> parseGroundTruth(std::istream& in, const std::string& source = "input");

// Reads a ground-truth file. Throws std::runtime_error when it cannot be opened or parsed.
std::vector<cv::Rect2f> loadGroundTruth(const std::string& path);

// ---- Tracker box files -------------------------------------------------------------------------
// What evaluate (OUT/boxes/SEQ/TRACKER.txt) and track_sequence write: one line per frame,
// x,y,w,h[,confidence[,time_to_contact]], the separators of a ground-truth line. A box that is
// absent (a NaN or an infinity, a non-positive width or height) is the zero box {0,0,0,0}, "no
// target", whatever its confidence; without a confidence it is 1.

struct TrackerBoxes {
  std::vector<cv::Rect2f> boxes;
  std::vector<float> confidence;  // same length
};

// Parses a whole box file's text (CRLF accepted; trailing blank lines dropped). Unlike a ground
// truth it has no header and no blank frame: a tracker writes a line for every frame. Throws
// std::runtime_error naming `source` and the line number for a line that is not 4 to 6 numbers,
// or whose confidence is not finite.
TrackerBoxes parseTrackerBoxes(std::istream& in, const std::string& source = "input");

// Reads a box file. Throws std::runtime_error when it cannot be opened or parsed.
TrackerBoxes loadTrackerBoxes(const std::string& path);

// ---- Frames for the core -----------------------------------------------------------------------

// Converts any decoded frame to CV_8UC1 or CV_8UC3 (BGR), the types core::Pipeline accepts.
// 8-bit 1- and 3-channel frames pass through without a copy; 4-channel -> BGR; 2-channel ->
// its first channel; 16-bit and float frames then go through core::IntensityStretch, the same
// stretch (and defaults) as the nodelet's. Buffers are reused between calls.
class FrameConverter {
 public:
  // Throws std::invalid_argument for settings core::IntensityStretch refuses.
  explicit FrameConverter(double low_percent = core::kStretchLowPercentile,
                          double high_percent = core::kStretchHighPercentile,
                          double smoothing = core::kStretchSmoothing);

  // Throws std::invalid_argument for an empty frame or more than 4 channels.
  // The result may share data with `in` (8-bit 1/3-channel) or with the converter's buffers:
  // it is valid until the next call.
  const cv::Mat& convert(const cv::Mat& in);

  // Forgets the smoothed range (e.g. at the start of a new sequence).
  void reset() { stretch_.reset(); }

  core::IntensityStretch& stretch() { return stretch_; }
  // The last stretch range applied to a non-8-bit frame (value mapped to 0 and to 255).
  double lastLow() const { return stretch_.lastLow(); }
  double lastHigh() const { return stretch_.lastHigh(); }

 private:
  core::IntensityStretch stretch_;
  cv::Mat work_, out_, stretched_;
};

// One-shot conversion with a per-frame stretch (same rules as FrameConverter).
cv::Mat toCoreFrame(const cv::Mat& in);

// ---- Sequences ---------------------------------------------------------------------------------

class Sequence {
 public:
  enum class Kind { kOtbFolder, kImageFolder, kVideo };

  // path: an OTB folder (an `img/` subfolder of images, or images directly, plus
  // groundtruth_rect.txt / groundtruth.txt), a folder of images (sorted by name, numbers in names
  // compared as numbers), a folder that holds one video instead of images (with the folder's
  // ground-truth file, else the video's as below), or a video file. ground_truth_path overrides
  // the ground-truth file; for a video without it, `<stem>_groundtruth_rect.txt` (generate_scene),
  // `<stem>.txt`, `<stem>_gt.txt` or `groundtruth_rect.txt` next to the video is used when
  // present. Throws std::runtime_error naming the path when it cannot be opened, holds neither
  // images nor one video, or the ground truth cannot be parsed.
  explicit Sequence(const std::string& path, const std::string& ground_truth_path = "");
  ~Sequence();
  Sequence(const Sequence&) = delete;
  Sequence& operator=(const Sequence&) = delete;

  Kind kind() const { return kind_; }
  const std::string& path() const { return path_; }
  // The video file read (for a folder holding a video, the video in it); empty for images.
  const std::string& videoPath() const { return video_path_; }
  const std::string& name() const { return name_; }  // folder name or video stem

  // Number of frames: the image count, or the video's frame count (as the container reports it;
  // read() may end earlier or later).
  int frameCount() const { return frame_count_; }

  // Frames per second: the video's (else a `fps` entry in `<stem>_scene.yaml` beside it), or a
  // `fps` entry in scene.yaml / scene.yml / scene.txt / fps.txt inside the folder (written by
  // generate_scene; fps.txt may hold a bare number), else 30 (the OTB convention).
  double fps() const { return fps_; }

  // Ground truth (empty when there is none). Boxes past its end count as absent.
  bool hasGroundTruth() const { return !ground_truth_.empty(); }
  const std::vector<cv::Rect2f>& groundTruth() const { return ground_truth_; }
  cv::Rect2f groundTruthAt(int index) const;

  // Decodes the next frame as stored (cv::IMREAD_UNCHANGED for images: 16-bit, 1-, 3- or
  // 4-channel frames come back as they are). Returns false at the end. Throws
  // std::runtime_error naming the file when an image file cannot be decoded.
  bool read(cv::Mat& frame);

  // Index of the frame the next read() returns.
  int position() const { return position_; }

  // Moves so that the next read() returns frame `index` (0-based; videos are re-opened and
  // skipped forward when going back). Throws std::out_of_range when index < 0 or > frameCount().
  void seek(int index);

  // The image files (folders only; empty for a video).
  const std::vector<std::string>& files() const { return files_; }

 private:
  void openFolderVideo(const std::filesystem::path& folder, std::string* gt_file);
  void openVideo(const std::string& file);

  Kind kind_ = Kind::kImageFolder;
  std::string path_, name_, video_path_;
  int frame_count_ = 0;
  double fps_ = 30.0;
  int position_ = 0;
  std::vector<std::string> files_;
  std::vector<cv::Rect2f> ground_truth_;
  struct Video;
  std::unique_ptr<Video> video_;
};

// True when `folder` is a sequence folder with a ground-truth file by Sequence's rules: it holds
// groundtruth_rect.txt, groundtruth.txt or groundtruth_rect.1.txt, or it holds no image and one
// video whose own ground-truth file (as for a video above) is beside it.
bool folderHasGroundTruth(const std::string& folder);

// The sequence folders directly under `root` (symlinks followed, hidden folders left out) for
// which folderHasGroundTruth holds, in name order, as root / name. The other folders are added
// to *skipped when it is given, also in name order. Empty when root is not a readable folder.
std::vector<std::string> listSequences(const std::string& root, std::vector<std::string>* skipped = nullptr);

// True when the path names a file with an image extension (jpg, jpeg, png, bmp, tif, tiff, pgm,
// ppm, pbm, webp, jp2, exr, hdr), case-insensitive.
bool hasImageExtension(const std::string& path);

// Reads `fps` from a small key/value text (YAML `fps: 25`, `fps=25`, `fps 25`); 0 when absent.
double parseFpsText(const std::string& text);

}  // namespace eval
}  // namespace obstacle_tracker
