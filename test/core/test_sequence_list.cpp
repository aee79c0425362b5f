// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// eval::listSequences and eval::folderHasGroundTruth: which folders under a root evaluate and
// init_table take as sequences. Only names on disk are looked at (no file is decoded), so the
// images and videos here are empty files.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "obstacle_tracker/eval/sequence.h"

namespace fs = std::filesystem;
using obstacle_tracker::eval::folderHasGroundTruth;
using obstacle_tracker::eval::listSequences;

namespace {

void touch(const fs::path& file) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << "1,2,3,4\n";
}

fs::path tempRoot() {
  const fs::path d = fs::temp_directory_path() / ("ot_test_sequence_list_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST(SequenceList, FoldersWithAGroundTruthFileInNameOrder) {
  const fs::path root = tempRoot();
  touch(root / "otb" / "img" / "0001.jpg");  // OTB layout
  touch(root / "otb" / "groundtruth_rect.txt");
  touch(root / "plain" / "0001.png");  // images directly in the folder, VOT-style ground truth
  touch(root / "plain" / "groundtruth.txt");
  touch(root / "first_object" / "img" / "0001.jpg");  // OTB's first of several targets
  touch(root / "first_object" / "groundtruth_rect.1.txt");
  touch(root / "clip" / "video.mp4");  // a video with the folder's ground truth
  touch(root / "clip" / "groundtruth_rect.txt");
  touch(root / "recorded" / "flight.avi");  // a video with its own ground truth beside it
  touch(root / "recorded" / "flight_groundtruth_rect.txt");
  touch(root / "images_only" / "img" / "0001.jpg");
  touch(root / "images_and_video_truth" / "0001.jpg");  // Sequence reads the images, not the video
  touch(root / "images_and_video_truth" / "flight.avi");
  touch(root / "images_and_video_truth" / "flight_groundtruth_rect.txt");
  touch(root / "two_videos" / "a.mp4");
  touch(root / "two_videos" / "b.mp4");
  touch(root / "two_videos" / "a_groundtruth_rect.txt");
  touch(root / ".hidden" / "img" / "0001.jpg");
  touch(root / ".hidden" / "groundtruth_rect.txt");
  touch(root / "groundtruth_rect.txt");  // a file, not a folder
  fs::create_directory_symlink(root / "otb", root / "linked");
  fs::create_directory_symlink(root / "no_such_folder", root / "broken_link");

  std::vector<std::string> skipped;
  const std::vector<std::string> found = listSequences(root.string(), &skipped);
  auto under = [&](std::vector<std::string> names) {
    for (std::string& n : names) n = (root / n).string();
    return names;
  };
  EXPECT_EQ(found, under({"clip", "first_object", "linked", "otb", "plain", "recorded"}));
  EXPECT_EQ(skipped, under({"images_and_video_truth", "images_only", "two_videos"}));
  EXPECT_EQ(listSequences(root.string()), found);
  fs::remove_all(root);
}

TEST(SequenceList, FolderHasGroundTruthAndMissingRoot) {
  const fs::path root = tempRoot();
  touch(root / "img" / "0001.jpg");
  EXPECT_FALSE(folderHasGroundTruth(root.string()));
  touch(root / "groundtruth_rect.txt");
  EXPECT_TRUE(folderHasGroundTruth(root.string()));
  EXPECT_TRUE(listSequences((root / "missing").string()).empty());
  fs::remove_all(root);
}
