// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The evaluation runner (src/eval/runner.cpp): TRE start frames, the flying subset, and whole
// runs of OpenCV's and our trackers on a small synthetic OTB folder written to a temp dir.
#include <atomic>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/eval/metrics.h"
#include "obstacle_tracker/eval/runner.h"

namespace fs = std::filesystem;
namespace ev = obstacle_tracker::eval;
using cv::Rect2f;

namespace {

constexpr int kFrames = 40;
constexpr int kAbsentAtStart = 3;  // the target enters at frame 3
constexpr int kSide = 18;

Rect2f truth(int i) {
  if (i < kAbsentAtStart) return Rect2f();
  return Rect2f(30.0f + 2.0f * i, 40.0f + 1.0f * i, kSide, kSide);
}

// A textured dark square moving over a smooth bright gradient; frames 0..2 are empty sky.
fs::path writeSequence(const std::string& tag) {
  // Unique per process: two test runs at once (e.g. a sanitizer build's) must not share files.
  const fs::path dir =
      fs::temp_directory_path() / ("ot_test_eval_runner_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "img");
  std::mt19937 rng(11);
  cv::Mat patch(kSide, kSide, CV_8UC3);
  cv::randu(patch, cv::Scalar(0, 0, 0), cv::Scalar(90, 90, 90));
  std::ofstream gt(dir / "groundtruth_rect.txt");
  for (int i = 0; i < kFrames; ++i) {
    cv::Mat frame(120, 200, CV_8UC3);
    for (int y = 0; y < frame.rows; ++y)
      frame.row(y).setTo(cv::Scalar(200 + y / 4, 190 + y / 4, 170 + y / 4));
    const Rect2f b = truth(i);
    if (!ev::isAbsent(b)) patch.copyTo(frame(cv::Rect(b)));
    char name[32];
    std::snprintf(name, sizeof(name), "%04d.png", i + 1);
    cv::imwrite((dir / "img" / name).string(), frame);
    gt << b.x << "," << b.y << "," << b.width << "," << b.height << "\n";
  }
  return dir;
}

}  // namespace

TEST(EvalRunner, TreStartFrames) {
  std::vector<Rect2f> gt(100, Rect2f(1, 1, 5, 5));
  std::vector<int> s = ev::treStartFrames(gt, 20);
  ASSERT_EQ(s.size(), 20u);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(s[k], 5 * k);
  // Absent frames move a start forward; a start past the last present frame is dropped.
  gt[0] = Rect2f();
  gt[1] = Rect2f();
  gt[5] = Rect2f(0, 0, 0, 0);
  for (int i = 95; i < 100; ++i) gt[i] = Rect2f();
  s = ev::treStartFrames(gt, 20);
  ASSERT_EQ(s.size(), 19u);
  EXPECT_EQ(s[0], 2);
  EXPECT_EQ(s[1], 6);
  EXPECT_EQ(s.back(), 90);
  // Short sequences give fewer, distinct starts.
  s = ev::treStartFrames(std::vector<Rect2f>(7, Rect2f(1, 1, 5, 5)), 20);
  EXPECT_EQ(s, (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_THROW(ev::treStartFrames(gt, 0), std::invalid_argument);
}

TEST(EvalRunner, FlyingSubset) {
  EXPECT_TRUE(ev::isFlyingSequence("antiuav_ir_04"));
  EXPECT_TRUE(ev::isFlyingSequence("lasot_airplane-1"));
  EXPECT_FALSE(ev::isFlyingSequence("Dog"));
  EXPECT_FALSE(ev::isFlyingSequence("my_antiuav_ir"));
}

TEST(EvalRunner, KnownTrackers) {
  const std::vector<std::string> names = ev::knownTrackers();
  for (const char* n : {"ours-auto", "ours-gt", "KCF", "CSRT", "MOSSE", "MIL", "MedianFlow"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
    EXPECT_NE(ev::makeTracker(n), nullptr) << n;
  }
  EXPECT_THROW(ev::makeTracker("TLD"), std::invalid_argument);
}

TEST(EvalRunner, OpenCvTrackersFollowASquare) {
  const fs::path dir = writeSequence("opencv");
  for (const char* name : {"KCF", "CSRT", "MedianFlow"}) {
    std::atomic<int> progress{0};
    const ev::RunResult r = ev::runTracker(dir.string(), name, {}, 0, &progress);
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.sequence, dir.filename().string());
    ASSERT_EQ(r.boxes.size(), static_cast<size_t>(kFrames));
    ASSERT_EQ(r.gt.size(), r.boxes.size());
    EXPECT_EQ(progress.load(), kFrames);
    // Started on the first present box (not timed), then one timed update per frame.
    for (int i = 0; i < kAbsentAtStart; ++i) EXPECT_TRUE(ev::isAbsent(r.boxes[i])) << name << " " << i;
    EXPECT_EQ(r.boxes[kAbsentAtStart], truth(kAbsentAtStart));
    EXPECT_EQ(r.timed_frames, kFrames - kAbsentAtStart - 1);
    EXPECT_GT(r.fps(), 0.0);
    for (int i = 0; i < kFrames; ++i) EXPECT_EQ(r.gt[i], truth(i));
    const ev::OtbScores s = ev::otbScores(r.boxes, r.gt);
    EXPECT_EQ(s.frames, kFrames - kAbsentAtStart);
    EXPECT_GE(s.precision20, 0.95) << name;
    EXPECT_GE(s.auc, 0.5) << name;
  }
}

TEST(EvalRunner, StartFrameAndRestart) {
  const fs::path dir = writeSequence("restart");
  const ev::RunResult r = ev::runTracker(dir.string(), "KCF", {}, 20);
  EXPECT_EQ(r.start_frame, 20);
  ASSERT_EQ(r.boxes.size(), static_cast<size_t>(kFrames - 20));
  EXPECT_EQ(r.boxes[0], truth(20));
  EXPECT_EQ(r.gt.back(), truth(kFrames - 1));
  EXPECT_THROW(ev::runTracker(dir.string(), "KCF", {}, kFrames), std::out_of_range);
  EXPECT_THROW(ev::runTracker(dir.string(), "KCF", {}, -1), std::out_of_range);
}

TEST(EvalRunner, OursGtStartsOnTheBox) {
  const fs::path dir = writeSequence("ours_gt");
  const ev::RunResult r = ev::runTracker(dir.string(), "ours-gt", {}, 0);
  EXPECT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.boxes.size(), static_cast<size_t>(kFrames));
  for (int i = 0; i < kAbsentAtStart; ++i) EXPECT_TRUE(ev::isAbsent(r.boxes[i]));
  EXPECT_FALSE(ev::isAbsent(r.boxes[kAbsentAtStart]));
  EXPECT_LE(ev::centreError(r.boxes[kAbsentAtStart], truth(kAbsentAtStart)), 2.0);
  EXPECT_EQ(r.timed_frames, kFrames - kAbsentAtStart - 1);
  for (float c : r.confidence) {
    EXPECT_GE(c, 0.0f);
    EXPECT_LE(c, 1.0f);
  }
}

TEST(EvalRunner, OursAutoIsTimedFromTheFirstFrame) {
  const fs::path dir = writeSequence("ours_auto");
  const ev::RunResult r = ev::runTracker(dir.string(), "ours-auto", {}, 0);
  EXPECT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.boxes.size(), static_cast<size_t>(kFrames));
  EXPECT_EQ(r.timed_frames, kFrames);
  // Long-term scores are defined whatever it reported.
  const ev::LongTermScores lt = ev::longTermScores(r.boxes, r.confidence, r.gt);
  EXPECT_EQ(lt.present_frames, kFrames - kAbsentAtStart);
  EXPECT_GE(lt.fscore, 0.0);
  EXPECT_LE(lt.fscore, 1.0);
}

TEST(EvalRunner, MissingSequenceThrows) {
  EXPECT_THROW(ev::runTracker("/nonexistent/ot_sequence", "KCF", {}, 0), std::runtime_error);
}
