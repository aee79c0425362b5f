// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Finding a sequence's files on disk: its images, its frame rate from a scene or fps file, and its
// ground-truth file. Used by sequence.cpp (Sequence's constructor); private to the evaluation
// library. The lookup rules are the ones sequence.h documents for Sequence.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace obstacle_tracker {
namespace eval {

// The folder's name; for a path ending in "/" or "/." the name of the folder it means.
std::string sequenceFolderName(const std::filesystem::path& folder);

// The image files of a sequence folder in natural name order: those in its img/ subfolder when
// there are any, else those directly in it. *image_folder is set to the folder they were taken from.
std::vector<std::string> listSequenceImages(const std::filesystem::path& folder,
                                            std::filesystem::path* image_folder);

// The video files directly in a folder (extension mp4, avi, mkv, mov, webm, m4v, mpg, mpeg, wmv
// or ts, case-insensitive), in natural name order: a sequence folder may hold its frames as one
// video instead of images.
std::vector<std::string> listFolderVideos(const std::filesystem::path& folder);

// The frame rate a scene or fps file in the folder gives, else one in image_folder; 0 when none.
double sequenceFolderFps(const std::filesystem::path& folder,
                         const std::filesystem::path& image_folder);

// The frame rate a `<stem>_scene.yaml` beside the video gives, else a scene or fps file in its
// folder; 0 when none.
double videoSceneFps(const std::filesystem::path& video);

// The ground-truth file found in a sequence folder / beside a video; empty when there is none.
std::string folderGroundTruthFile(const std::filesystem::path& folder);
std::string videoGroundTruthFile(const std::filesystem::path& video);

}  // namespace eval
}  // namespace obstacle_tracker
