// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include <unistd.h>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "obstacle_tracker/eval/sequence.h"

namespace fs = std::filesystem;
using obstacle_tracker::eval::FrameConverter;
using obstacle_tracker::eval::isPresent;
using obstacle_tracker::eval::parseFpsText;
using obstacle_tracker::eval::parseGroundTruth;
using obstacle_tracker::eval::parseGroundTruthLine;
using obstacle_tracker::eval::parseTrackerBoxes;
using obstacle_tracker::eval::Sequence;

namespace {

cv::Rect2f parse(const std::string& s) {
  cv::Rect2f box(-1, -1, -1, -1);
  EXPECT_TRUE(parseGroundTruthLine(s, &box)) << s;
  return box;
}

void expectBox(const cv::Rect2f& b, float x, float y, float w, float h) {
  EXPECT_FLOAT_EQ(b.x, x);
  EXPECT_FLOAT_EQ(b.y, y);
  EXPECT_FLOAT_EQ(b.width, w);
  EXPECT_FLOAT_EQ(b.height, h);
}

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() /
                     ("ot_test_sequence_" + name + "_" + std::to_string(::getpid()));  // unique per process
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST(SequenceGroundTruth, SeparatorsCommasTabsSpaces) {
  expectBox(parse("1,2,3,4"), 1, 2, 3, 4);
  expectBox(parse("1\t2\t3\t4"), 1, 2, 3, 4);
  expectBox(parse("1 2  3   4"), 1, 2, 3, 4);
  expectBox(parse("1, 2,\t3 ,4\r"), 1, 2, 3, 4);
  expectBox(parse("227.16,185.16,13.68,6.01"), 227.16f, 185.16f, 13.68f, 6.01f);
  expectBox(parse("  5;6;7;8  "), 5, 6, 7, 8);
}

TEST(SequenceGroundTruth, AbsentBoxes) {
  EXPECT_FALSE(isPresent(parse("NaN,NaN,NaN,NaN")));
  EXPECT_FALSE(isPresent(parse("nan 3 4 5")));
  EXPECT_FALSE(isPresent(parse("0,0,0,0")));
  EXPECT_FALSE(isPresent(parse("10,10,0,5")));
  EXPECT_FALSE(isPresent(parse("10,10,-3,5")));
  EXPECT_FALSE(isPresent(parse("")));
  EXPECT_FALSE(isPresent(parse("   \r")));
  expectBox(parse("0,0,0,0"), 0, 0, 0, 0);
  EXPECT_TRUE(isPresent(parse("0,0,1,1")));
  // A position that is not finite is no box either, whatever its size.
  EXPECT_FALSE(isPresent(cv::Rect2f(std::numeric_limits<float>::infinity(), 10, 5, 5)));
  EXPECT_FALSE(isPresent(cv::Rect2f(10, -std::numeric_limits<float>::infinity(), 5, 5)));
}

TEST(SequenceGroundTruth, PolygonBecomesBoundingBox) {
  expectBox(parse("10,20,30,22,28,40,8,38"), 8, 20, 22, 20);
}

TEST(SequenceGroundTruth, NotABox) {
  cv::Rect2f box(1, 2, 3, 4);
  EXPECT_FALSE(parseGroundTruthLine("1,2,3", &box));
  EXPECT_FALSE(parseGroundTruthLine("1,2,3,4,5", &box));
  EXPECT_FALSE(parseGroundTruthLine("x,y,w,h", &box));
  EXPECT_FALSE(parseGroundTruthLine("1,2,3,4abc", &box));
  expectBox(box, 1, 2, 3, 4);  // untouched
}

TEST(SequenceGroundTruth, WholeFile) {
  std::istringstream in("x,y,w,h\r\n1,2,3,4\r\n\r\nNaN,NaN,NaN,NaN\r\n5\t6\t7\t8\r\n\r\n\r\n");
  const auto boxes = parseGroundTruth(in, "t");
  ASSERT_EQ(boxes.size(), 4u);  // header skipped, trailing blanks dropped
  expectBox(boxes[0], 1, 2, 3, 4);
  EXPECT_FALSE(isPresent(boxes[1]));
  EXPECT_FALSE(isPresent(boxes[2]));
  expectBox(boxes[3], 5, 6, 7, 8);
}

TEST(SequenceGroundTruth, NoNewlineAtEnd) {
  std::istringstream in("1,2,3,4\n5,6,7,8");
  EXPECT_EQ(parseGroundTruth(in).size(), 2u);
}

TEST(SequenceGroundTruth, BadLineNamesSourceAndLine) {
  std::istringstream in("1,2,3,4\n1,2,3,4\nbroken\n");
  try {
    parseGroundTruth(in, "gt.txt");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gt.txt:3"), std::string::npos) << e.what();
  }
}

// What evaluate and track_sequence write: 5 and 6 values; 4 values have confidence 1.
TEST(TrackerBoxFile, EvaluateAndTrackSequenceLines) {
  std::istringstream in("1.5,2,3,4,0.25\r\n0,0,0,0,0.7\n5 6 7 8\n9,10,11,12,0.500,inf\n0,0,0,0,0,inf\n\n");
  const auto r = parseTrackerBoxes(in, "t");
  ASSERT_EQ(r.boxes.size(), 5u);  // the trailing blank line dropped
  ASSERT_EQ(r.confidence.size(), 5u);
  expectBox(r.boxes[0], 1.5f, 2, 3, 4);
  EXPECT_FLOAT_EQ(r.confidence[0], 0.25f);
  EXPECT_FALSE(isPresent(r.boxes[1]));
  EXPECT_FLOAT_EQ(r.confidence[1], 0.7f);
  expectBox(r.boxes[2], 5, 6, 7, 8);
  EXPECT_FLOAT_EQ(r.confidence[2], 1.0f);
  expectBox(r.boxes[3], 9, 10, 11, 12);
  EXPECT_FLOAT_EQ(r.confidence[3], 0.5f);
  EXPECT_FALSE(isPresent(r.boxes[4]));
}

TEST(TrackerBoxFile, NonFiniteBoxIsTheZeroBox) {
  std::istringstream in("nan,2,3,4,0.5\n1,inf,3,4,0.5\n");
  const auto r = parseTrackerBoxes(in);
  ASSERT_EQ(r.boxes.size(), 2u);
  for (const cv::Rect2f& b : r.boxes) expectBox(b, 0, 0, 0, 0);
}

TEST(TrackerBoxFile, BadLinesNameSourceAndLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"1,2,3,4\n1,2,3\n", "b.txt:2: not a tracker box"},
      {"1,2,3,4\n1,2,3,4,5,6,7\n", "b.txt:2: not a tracker box"},
      {"x,y,w,h,c\n1,2,3,4\n", "b.txt:1: not a tracker box"},
      {"1,2,3,4,abc\n", "b.txt:1: not a tracker box"},
      {"1,2,3,4\n1,2,3,4,nan\n", "b.txt:2: the confidence is not a finite number"},
      {"1,2,3,4\n\n\n1,2,3,4\n", "b.txt:2: blank line"},
  };
  for (const auto& c : cases) {
    std::istringstream in(c.first);
    try {
      parseTrackerBoxes(in, "b.txt");
      ADD_FAILURE() << "no exception for " << c.first;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(c.second), std::string::npos) << e.what();
    }
  }
}

TEST(SequenceFps, ParsesKeyValueText) {
  EXPECT_DOUBLE_EQ(parseFpsText("scenario: crossing\nfps: 25\n"), 25.0);
  EXPECT_DOUBLE_EQ(parseFpsText("fps=12.5"), 12.5);
  EXPECT_DOUBLE_EQ(parseFpsText("  FPS 60"), 60.0);
  EXPECT_DOUBLE_EQ(parseFpsText("fps_max: 90\nframes: 3"), 0.0);
  EXPECT_DOUBLE_EQ(parseFpsText(""), 0.0);
}

TEST(FrameConverterTest, EightBitPassesThrough) {
  FrameConverter conv;
  cv::Mat grey(8, 9, CV_8UC1, cv::Scalar(7));
  cv::Mat bgr(8, 9, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_EQ(conv.convert(grey).data, grey.data);
  EXPECT_EQ(conv.convert(bgr).data, bgr.data);
  EXPECT_EQ(conv.convert(bgr).type(), CV_8UC3);
}

TEST(FrameConverterTest, FourChannelsBecomeBgr) {
  FrameConverter conv;
  cv::Mat bgra(4, 5, CV_8UC4, cv::Scalar(10, 20, 30, 40));
  const cv::Mat& out = conv.convert(bgra);
  ASSERT_EQ(out.type(), CV_8UC3);
  EXPECT_EQ(out.at<cv::Vec3b>(2, 3), cv::Vec3b(10, 20, 30));
  cv::Mat two(4, 5, CV_8UC2, cv::Scalar(9, 99));
  const cv::Mat& o2 = conv.convert(two);
  ASSERT_EQ(o2.type(), CV_8UC1);
  EXPECT_EQ(o2.at<std::uint8_t>(1, 1), 9);
}

TEST(FrameConverterTest, DeepFramesGoThroughTheCoreStretch) {
  // The stretch itself is tested in test_intensity_stretch; here: channel layout first, then the
  // core's stretch with its defaults (the nodelet's too).
  FrameConverter conv;
  EXPECT_EQ(conv.stretch().lowPercentile(), obstacle_tracker::core::kStretchLowPercentile);
  EXPECT_EQ(conv.stretch().highPercentile(), obstacle_tracker::core::kStretchHighPercentile);
  EXPECT_EQ(conv.stretch().smoothing(), obstacle_tracker::core::kStretchSmoothing);
  cv::Mat img(4, 4, CV_16UC3, cv::Scalar(100, 200, 300));
  img.at<cv::Vec3w>(0, 0) = cv::Vec3w(0, 0, 0);
  const cv::Mat& out = conv.convert(img);
  ASSERT_EQ(out.type(), CV_8UC3);
  EXPECT_EQ(out.at<cv::Vec3b>(3, 3)[2], 255);
  cv::Mat bgra16(4, 4, CV_16UC4, cv::Scalar(1000, 2000, 5000, 65535));
  FrameConverter per_frame(0.0, 100.0, 1.0);
  const cv::Mat& o4 = per_frame.convert(bgra16);
  ASSERT_EQ(o4.type(), CV_8UC3);  // alpha dropped before the stretch: it sets no range
  EXPECT_EQ(o4.at<cv::Vec3b>(1, 1), cv::Vec3b(0, 64, 255));
  EXPECT_EQ(per_frame.lastHigh(), 5000);
  cv::Mat f(3, 3, CV_32FC2, cv::Scalar(0.5f, 7.0f));
  f.at<cv::Vec2f>(0, 0)[0] = 0.0f;
  f.at<cv::Vec2f>(2, 2)[0] = 1.0f;
  const cv::Mat& o2 = per_frame.convert(f);
  ASSERT_EQ(o2.type(), CV_8UC1);  // first channel only
  EXPECT_EQ(o2.at<std::uint8_t>(2, 2), 255);
  EXPECT_EQ(per_frame.lastHigh(), 1.0);
  // An 8-bit frame after a deeper one is passed through as ever.
  cv::Mat grey(3, 3, CV_8UC1, cv::Scalar(9));
  EXPECT_EQ(per_frame.convert(grey).data, grey.data);
}

TEST(FrameConverterTest, BadFramesThrow) {
  FrameConverter conv;
  EXPECT_THROW(conv.convert(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(FrameConverter(50.0, 10.0), std::invalid_argument);
}

TEST(SequenceFolder, OtbLayoutWithSixteenBitPngsNaturalOrderAndFps) {
  const fs::path dir = tempDir("otb");
  fs::create_directories(dir / "img");
  // Names that sort wrongly as plain strings: 2 before 10.
  for (int i : {1, 2, 10}) {
    cv::Mat img(6, 8, CV_16UC1, cv::Scalar(1000 * i));
    ASSERT_TRUE(cv::imwrite((dir / "img" / ("f" + std::to_string(i) + ".png")).string(), img));
  }
  std::ofstream(dir / "groundtruth_rect.txt") << "1,2,3,4\n0,0,0,0\n";
  std::ofstream(dir / "scene.yaml") << "scenario: test\nfps: 24\n";
  Sequence seq(dir.string());
  EXPECT_EQ(seq.kind(), Sequence::Kind::kOtbFolder);
  EXPECT_EQ(seq.frameCount(), 3);
  EXPECT_DOUBLE_EQ(seq.fps(), 24.0);
  ASSERT_TRUE(seq.hasGroundTruth());
  EXPECT_TRUE(isPresent(seq.groundTruthAt(0)));
  EXPECT_FALSE(isPresent(seq.groundTruthAt(1)));
  EXPECT_FALSE(isPresent(seq.groundTruthAt(2)));  // past the end of the file
  cv::Mat frame;
  std::vector<int> values;
  while (seq.read(frame)) {
    ASSERT_EQ(frame.type(), CV_16UC1);
    values.push_back(frame.at<std::uint16_t>(0, 0));
  }
  EXPECT_EQ(values, (std::vector<int>{1000, 2000, 10000}));
  seq.seek(1);
  ASSERT_TRUE(seq.read(frame));
  EXPECT_EQ(frame.at<std::uint16_t>(0, 0), 2000);
  EXPECT_THROW(seq.seek(4), std::out_of_range);
  fs::remove_all(dir);
}

TEST(SequenceFolder, PlainImageFolderDefaultsTo30Fps) {
  const fs::path dir = tempDir("plain");
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(cv::imwrite((dir / (std::to_string(i) + ".jpg")).string(), cv::Mat(8, 8, CV_8UC1, cv::Scalar(50))));
  }
  std::ofstream(dir / "notes.md") << "not an image";
  Sequence seq(dir.string());
  EXPECT_EQ(seq.kind(), Sequence::Kind::kImageFolder);
  EXPECT_EQ(seq.frameCount(), 2);
  EXPECT_DOUBLE_EQ(seq.fps(), 30.0);
  EXPECT_FALSE(seq.hasGroundTruth());
  cv::Mat frame;
  ASSERT_TRUE(seq.read(frame));
  EXPECT_EQ(frame.type(), CV_8UC1);  // a 1-channel JPEG stays 1-channel
  fs::remove_all(dir);
}

// fps.txt holds either a bare number or an `fps` entry like scene.yaml's.
TEST(SequenceFolder, FpsFileWithABareNumberOrAnEntry) {
  const fs::path dir = tempDir("fps_file");
  ASSERT_TRUE(cv::imwrite((dir / "0.png").string(), cv::Mat(8, 8, CV_8UC1, cv::Scalar(50))));
  std::ofstream(dir / "fps.txt") << "12.5\n";
  EXPECT_DOUBLE_EQ(Sequence(dir.string()).fps(), 12.5);
  std::ofstream(dir / "fps.txt") << "fps: 25\n";
  EXPECT_DOUBLE_EQ(Sequence(dir.string()).fps(), 25.0);
  fs::remove_all(dir);
}

TEST(SequenceFolder, ErrorsNameThePath) {
  const fs::path dir = tempDir("empty");
  EXPECT_THROW(Sequence s(dir.string()), std::runtime_error);
  EXPECT_THROW(Sequence s((dir / "missing").string()), std::runtime_error);
  std::ofstream(dir / "bad.jpg") << "not a jpeg";
  Sequence seq(dir.string());
  cv::Mat frame;
  EXPECT_THROW(seq.read(frame), std::runtime_error);
  fs::remove_all(dir);
}

TEST(SequenceVideo, ReadsFramesFpsAndGroundTruthNextToIt) {
  const fs::path dir = tempDir("video");
  const std::string file = (dir / "clip.avi").string();
  {
    cv::VideoWriter w(file, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 15.0, cv::Size(64, 48));
    if (!w.isOpened()) GTEST_SKIP() << "no MJPG writer in this OpenCV build";
    for (int i = 0; i < 5; ++i) w.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(40 * i, 10, 10)));
  }
  std::ofstream(dir / "clip.txt") << "1 2 3 4\n5 6 7 8\n";
  Sequence seq(file);
  EXPECT_EQ(seq.kind(), Sequence::Kind::kVideo);
  EXPECT_DOUBLE_EQ(seq.fps(), 15.0);
  EXPECT_EQ(seq.groundTruth().size(), 2u);
  cv::Mat frame;
  int n = 0;
  while (seq.read(frame)) {
    EXPECT_EQ(frame.type(), CV_8UC3);
    ++n;
  }
  EXPECT_EQ(n, 5);
  seq.seek(3);
  ASSERT_TRUE(seq.read(frame));
  EXPECT_NEAR(frame.at<cv::Vec3b>(10, 10)[0], 120, 12);
  fs::remove_all(dir);
}

// A sequence folder may hold its frames as one video (as users record flights) instead of img/.
TEST(SequenceVideo, FolderHoldingOneVideoReadsItWithTheFolderGroundTruth) {
  const fs::path dir = tempDir("video_folder");
  const std::string file = (dir / "video.avi").string();
  {
    cv::VideoWriter w(file, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 15.0, cv::Size(64, 48));
    if (!w.isOpened()) GTEST_SKIP() << "no MJPG writer in this OpenCV build";
    for (int i = 0; i < 5; ++i) w.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(40 * i, 10, 10)));
  }
  std::ofstream(dir / "groundtruth_rect.txt") << "1,2,3,4\n5,6,7,8\n9,10,11,12\n";
  std::ofstream(dir / "SOURCE.txt") << "not a ground truth";
  std::ofstream(dir / "._video.avi") << "a hidden file macOS writes beside the video";
  Sequence seq(dir.string());
  EXPECT_EQ(seq.kind(), Sequence::Kind::kVideo);
  EXPECT_EQ(seq.name(), dir.filename().string());
  EXPECT_EQ(seq.videoPath(), file);
  EXPECT_DOUBLE_EQ(seq.fps(), 15.0);
  EXPECT_EQ(seq.frameCount(), 5);
  ASSERT_EQ(seq.groundTruth().size(), 3u);
  EXPECT_FLOAT_EQ(seq.groundTruthAt(2).x, 9.0f);
  cv::Mat frame;
  int n = 0;
  while (seq.read(frame)) ++n;
  EXPECT_EQ(n, 5);
  seq.seek(3);  // back: the video is opened again
  ASSERT_TRUE(seq.read(frame));
  EXPECT_NEAR(frame.at<cv::Vec3b>(10, 10)[0], 120, 12);

  // Two videos and no image: which one is meant is not guessed.
  fs::copy_file(file, dir / "other.avi");
  try {
    Sequence two(dir.string());
    ADD_FAILURE() << "a folder with two videos was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("2 videos"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(SequenceShared, RealSequencesHaveMatchingGroundTruth) {
  const fs::path root = fs::path(OT_SHARED_DIR) / "sequences";
  if (!fs::is_directory(root)) GTEST_SKIP() << "no " << root << " (real sequences are optional)";
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(root)) {
    if (!fs::is_directory(entry.path() / "img")) continue;
    Sequence seq(entry.path().string());
    EXPECT_EQ(seq.kind(), Sequence::Kind::kOtbFolder) << entry.path();
    EXPECT_EQ(static_cast<int>(seq.groundTruth().size()), seq.frameCount()) << entry.path();
    cv::Mat frame;
    ASSERT_TRUE(seq.read(frame));
    const cv::Mat core = obstacle_tracker::eval::toCoreFrame(frame);
    EXPECT_TRUE(core.type() == CV_8UC1 || core.type() == CV_8UC3) << entry.path();
    if (seq.name() == "Vase") {
      EXPECT_EQ(frame.channels(), 1);
    }
    ++checked;
  }
  EXPECT_GT(checked, 0);
}
