// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Sequence: opening a folder of images or a video (the files are found by sequence_files.cpp)
// and reading its frames one at a time.
#include "obstacle_tracker/eval/sequence.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "sequence_files.h"

namespace fs = std::filesystem;

namespace obstacle_tracker {
namespace eval {

struct Sequence::Video {
  cv::VideoCapture cap;
};

Sequence::Sequence(const std::string& path, const std::string& ground_truth_path) : path_(path) {
  std::error_code ec;
  const fs::path p(path);
  std::string gt_file = ground_truth_path;
  if (fs::is_directory(p, ec)) {
    name_ = sequenceFolderName(p);
    fs::path img_dir;
    files_ = listSequenceImages(p, &img_dir);
    if (gt_file.empty()) gt_file = folderGroundTruthFile(p);
    if (files_.empty()) {
      openFolderVideo(p, &gt_file);
    } else {
      kind_ = gt_file.empty() ? Kind::kImageFolder : Kind::kOtbFolder;
      frame_count_ = static_cast<int>(files_.size());
      const double f = sequenceFolderFps(p, img_dir);
      fps_ = f > 0.0 ? f : 30.0;
    }
  } else if (fs::is_regular_file(p, ec)) {
    if (hasImageExtension(path)) {
      throw std::runtime_error("'" + path +
                               "' is a single image; give the folder that holds the sequence");
    }
    name_ = p.stem().string();
    openVideo(path);
    if (gt_file.empty()) gt_file = videoGroundTruthFile(p);
  } else {
    throw std::runtime_error("'" + path + "' is neither a folder nor a file");
  }
  if (!gt_file.empty()) ground_truth_ = loadGroundTruth(gt_file);
}

void Sequence::openFolderVideo(const fs::path& folder, std::string* gt_file) {
  const std::vector<std::string> videos = listFolderVideos(folder);
  if (videos.empty()) throw std::runtime_error("no image or video files in '" + path_ + "'");
  if (videos.size() > 1) {
    throw std::runtime_error("'" + path_ + "' holds no image and " + std::to_string(videos.size()) +
                             " videos; give the video to read");
  }
  openVideo(videos.front());
  if (gt_file->empty()) *gt_file = videoGroundTruthFile(videos.front());
}

void Sequence::openVideo(const std::string& file) {
  kind_ = Kind::kVideo;
  video_path_ = file;
  video_ = std::make_unique<Video>();
  if (!video_->cap.open(file) || !video_->cap.isOpened()) {
    throw std::runtime_error("cannot open video '" + file + "'");
  }
  const double f = video_->cap.get(cv::CAP_PROP_FPS);
  const double scene_fps = videoSceneFps(fs::path(file));
  fps_ = (std::isfinite(f) && f > 0.0 && f < 1000.0) ? f : (scene_fps > 0.0 ? scene_fps : 30.0);
  const double n = video_->cap.get(cv::CAP_PROP_FRAME_COUNT);
  frame_count_ = (std::isfinite(n) && n > 0.0) ? static_cast<int>(n) : 0;
}

Sequence::~Sequence() = default;

cv::Rect2f Sequence::groundTruthAt(int index) const {
  if (index < 0 || index >= static_cast<int>(ground_truth_.size())) return cv::Rect2f();
  return ground_truth_[static_cast<std::size_t>(index)];
}

bool Sequence::read(cv::Mat& frame) {
  if (kind_ == Kind::kVideo) {
    if (!video_->cap.read(frame) || frame.empty()) return false;
    ++position_;
    return true;
  }
  if (position_ >= static_cast<int>(files_.size())) return false;
  const std::string& file = files_[static_cast<std::size_t>(position_)];
  frame = cv::imread(file, cv::IMREAD_UNCHANGED);
  if (frame.empty()) throw std::runtime_error("cannot decode image '" + file + "'");
  ++position_;
  return true;
}

void Sequence::seek(int index) {
  if (index < 0 || (frame_count_ > 0 && index > frame_count_)) {
    throw std::out_of_range("Sequence::seek: frame " + std::to_string(index) + " outside [0, " +
                            std::to_string(frame_count_) + "]");
  }
  if (kind_ != Kind::kVideo) {
    position_ = index;
    return;
  }
  if (index < position_) {
    video_->cap.release();
    if (!video_->cap.open(video_path_)) {
      throw std::runtime_error("cannot re-open video '" + video_path_ + "'");
    }
    position_ = 0;
  }
  while (position_ < index) {
    if (!video_->cap.grab()) break;
    ++position_;
  }
}

}  // namespace eval
}  // namespace obstacle_tracker
