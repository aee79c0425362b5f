// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Writing generated scenes: an OTB-layout folder (img/0001.jpg|png ... + groundtruth_rect.txt),
// or a video file, each with the multi-obstacle ground truth (groundtruth_multi.csv) and the
// scene description (scene.yaml). Formats in docs/scenes.md.
#pragma once

#include <functional>
#include <ostream>
#include <string>

#include "obstacle_tracker/scene/scene_generator.h"

namespace obstacle_tracker {
namespace scene {

struct WriteOptions {
  std::string image_format;  // "jpg" or "png"; empty: jpg for colour, png for mono16 (16 bits kept)
  int jpeg_quality = 95;
  // Called after each frame (progress); may be empty.
  std::function<void(int frame, int frames)> progress;
};

// One groundtruth_rect.txt line for the main obstacle: "x,y,w,h" with two decimals, or
// "0,0,0,0" when it is absent (not visible, see kVisibleThreshold).
std::string groundTruthLine(const ObstacleTruth* main_obstacle);

// Header and one row per obstacle of groundtruth_multi.csv.
std::string groundTruthMultiHeader();
std::string groundTruthMultiRow(const FrameTruth& truth, const ObstacleTruth& o);

// scene.yaml text (scenario, seed, size, fps, encoding, focal length, obstacles with time to
// contact at the start and closing speed, file names).
std::string sceneYaml(const SceneGenerator& gen, const std::string& image_format, const std::string& files_prefix);

// Writes DIR/img/NNNN.ext, DIR/groundtruth_rect.txt, DIR/groundtruth_multi.csv, DIR/scene.yaml.
// Creates DIR; throws std::runtime_error when a file cannot be written.
void writeOtbSequence(SceneGenerator& gen, const std::string& dir, const WriteOptions& options = WriteOptions());

// Writes the video (".mp4": mp4v, ".avi": MJPG) and, next to it, STEM_groundtruth_rect.txt,
// STEM_groundtruth_multi.csv and STEM_scene.yaml. Mono16 scenes are mapped to 8 bits with
// SceneGenerator::thermalDisplayRange, the fixed band scene.yaml states, so that a video's values
// stay one known linear function of the counts. This is not the trackers' 16-bit rule
// (core::IntensityStretch): that one estimates the band of a camera's unknown counts from every
// frame, and the tools apply it when they read the 16-bit PNG frames of writeOtbSequence.
// Throws std::runtime_error when the writer fails.
void writeVideo(SceneGenerator& gen, const std::string& path, const WriteOptions& options = WriteOptions());

}  // namespace scene
}  // namespace obstacle_tracker
