// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known answers for the background-motion estimator (background_motion.h): a textured scene
// moved by a known pan, roll or zoom (a similarity about the frame centre) between two frames.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/background_motion.h"

using obstacle_tracker::core::BackgroundMotion;
using obstacle_tracker::core::BackgroundMotionEstimate;

namespace {

// Ground and trees seen from the air: noise blurred at three scales, summed, 8-bit.
cv::Mat texturedScene(cv::Size size, unsigned seed) {
  cv::RNG rng(seed);
  cv::Mat sum(size, CV_32F, cv::Scalar(0));
  for (const int cell : {4, 16, 48}) {
    cv::Mat coarse(size.height / cell + 2, size.width / cell + 2, CV_32F);
    rng.fill(coarse, cv::RNG::UNIFORM, -1.0, 1.0);
    cv::Mat fine;
    cv::resize(coarse, fine, cv::Size(coarse.cols * cell, coarse.rows * cell), 0, 0, cv::INTER_CUBIC);
    sum += fine(cv::Rect(0, 0, size.width, size.height)) * (cell == 4 ? 25.0 : 35.0);
  }
  cv::Mat out;
  sum.convertTo(out, CV_8U, 1.0, 128.0);
  return out;
}

// Pan (dx, dy) px, roll (degrees) and zoom about the frame centre: x' = A x.
cv::Matx23d cameraMotion(cv::Size size, double dx, double dy, double roll_deg, double zoom) {
  const cv::Point2f centre(0.5f * (size.width - 1), 0.5f * (size.height - 1));
  cv::Mat r = cv::getRotationMatrix2D(centre, roll_deg, zoom);  // positive = counter-clockwise
  cv::Matx23d a;
  r.convertTo(cv::Mat(2, 3, CV_64F, a.val), CV_64F);
  a(0, 2) += dx;
  a(1, 2) += dy;
  return a;
}

// The scene as the camera sees it after the motion (the previous frame's content at A^-1 x).
cv::Mat moved(const cv::Mat& frame, const cv::Matx23d& a) {
  cv::Mat out;
  cv::warpAffine(frame, out, a, frame.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

double centreError(const BackgroundMotionEstimate& e, const cv::Matx23d& truth, cv::Size size) {
  const cv::Point2d c(0.5 * (size.width - 1), 0.5 * (size.height - 1));
  const cv::Point2d got = e.displacementAt(c);
  const cv::Point2d want(truth(0, 0) * c.x + truth(0, 1) * c.y + truth(0, 2) - c.x,
                         truth(1, 0) * c.x + truth(1, 1) * c.y + truth(1, 2) - c.y);
  return std::hypot(got.x - want.x, got.y - want.y);
}

double cornerError(const BackgroundMotionEstimate& e, const cv::Matx23d& truth, cv::Size size) {
  double worst = 0.0;
  for (const cv::Point2d p : {cv::Point2d(0, 0), cv::Point2d(size.width - 1, size.height - 1)}) {
    const cv::Point2d got = e.displacementAt(p);
    const cv::Point2d want(truth(0, 0) * p.x + truth(0, 1) * p.y + truth(0, 2) - p.x,
                           truth(1, 0) * p.x + truth(1, 1) * p.y + truth(1, 2) - p.y);
    worst = std::max(worst, std::hypot(got.x - want.x, got.y - want.y));
  }
  return worst;
}

struct Motion {
  const char* name;
  double dx, dy, roll, zoom;
};

const Motion kMotions[] = {
    {"pan", 3.3, -1.7, 0.0, 1.0},     {"fast pan", -14.6, 6.2, 0.0, 1.0}, {"roll", 0.0, 0.0, 2.0, 1.0},
    {"zoom in", 0.0, 0.0, 0.0, 1.03}, {"zoom out", 0.0, 0.0, 0.0, 0.97},  {"all", 5.4, 2.2, -1.5, 1.02},
};

}  // namespace

TEST(BackgroundMotion, FirstFrameIsUnknown) {
  BackgroundMotion motion;
  const BackgroundMotionEstimate& e = motion.update(texturedScene(cv::Size(320, 240), 1));
  EXPECT_FALSE(e.known());
  EXPECT_EQ(e.displacementAt(cv::Point2d(10, 10)), cv::Point2d(0, 0));
}

TEST(BackgroundMotion, RecoversPansRollsAndZoomsAtSeveralResolutions) {
  for (const cv::Size size : {cv::Size(320, 256), cv::Size(640, 512), cv::Size(1920, 1080)}) {
    const cv::Mat first = texturedScene(size, 7);
    for (const Motion& m : kMotions) {
      // Scaled with the frame: the same camera motion seen by a sensor with more pixels.
      const double k = size.width / 640.0;
      const cv::Matx23d truth = cameraMotion(size, m.dx * k, m.dy * k, m.roll, m.zoom);
      BackgroundMotion motion;
      motion.update(first);
      const BackgroundMotionEstimate& e = motion.update(moved(first, truth));
      SCOPED_TRACE(std::string(m.name) + " at " + std::to_string(size.width) + "x" + std::to_string(size.height));
      ASSERT_EQ(e.source, BackgroundMotionEstimate::Source::kFeatures);
      EXPECT_GT(e.quality, 0.8);
      EXPECT_LT(centreError(e, truth, size), 0.25);
      EXPECT_LT(cornerError(e, truth, size), 1.0 * std::max(1.0, k));
    }
  }
}

TEST(BackgroundMotion, IgnoresAMoverCoveringAFifthOfTheFrame) {
  const cv::Size size(640, 480);
  const cv::Mat first = texturedScene(size, 3);
  const cv::Matx23d truth = cameraMotion(size, 4.0, 1.0, 0.5, 1.01);
  cv::Mat second = moved(first, truth);
  // A large object with its own texture, moving against the background, in both frames.
  const cv::Mat object = texturedScene(cv::Size(280, 200), 99);
  cv::Mat a = first.clone();
  object.copyTo(a(cv::Rect(100, 120, 280, 200)));
  object.copyTo(second(cv::Rect(112, 114, 280, 200)));
  BackgroundMotion motion;
  motion.update(a);
  const BackgroundMotionEstimate& e = motion.update(second);
  ASSERT_EQ(e.source, BackgroundMotionEstimate::Source::kFeatures);
  EXPECT_LT(centreError(e, truth, size), 0.25);
  EXPECT_LT(e.quality, 0.95);  // the object's tracks are outliers
}

TEST(BackgroundMotion, ExcludedPixelsCarryNoTrack) {
  // Most of the corners lie on an image-locked pattern (an on-screen grid); excluded, the rest
  // gives the pan.
  const cv::Size size(640, 480);
  const cv::Mat first = texturedScene(size, 5);
  const cv::Matx23d truth = cameraMotion(size, 6.0, -3.0, 0.0, 1.0);
  cv::Mat a = first.clone(), b = moved(first, truth);
  BackgroundMotion motion;
  cv::Mat excluded(motion.workingSize(size), CV_8U, cv::Scalar(0));
  for (int y = 20; y < size.height; y += 24) {
    for (int x = 20; x < 560; x += 24) {
      for (cv::Mat* f : {&a, &b}) cv::rectangle(*f, cv::Rect(x, y, 10, 10), cv::Scalar(255), cv::FILLED);
    }
  }
  cv::rectangle(excluded, cv::Rect(0, 0, 290, excluded.rows), cv::Scalar(255), cv::FILLED);  // x < 580 full px
  motion.update(a);
  const BackgroundMotionEstimate& plain = motion.update(b);
  const double plain_error = centreError(plain, truth, size);
  motion.reset();
  motion.update(a);
  const BackgroundMotionEstimate& masked = motion.update(b, excluded);
  ASSERT_EQ(masked.source, BackgroundMotionEstimate::Source::kFeatures);
  EXPECT_LT(centreError(masked, truth, size), 0.25);
  EXPECT_GT(plain_error, 1.0);  // without the mask, the grid (locked to the image) wins
}

TEST(BackgroundMotion, ASlowPanIsNotPulledTowardsStillText) {
  // On-screen text rows (still in the image) over a world panned by 1 x 0.5 px: the text's corners
  // are near the background's motion at such a pan, and must not be taken in with it.
  const cv::Size size(640, 512);
  const cv::Mat world = texturedScene(cv::Size(800, 600), 13);
  BackgroundMotion motion;
  cv::Point2d sum(0.0, 0.0);
  for (int i = 0; i < 20; ++i) {
    cv::Mat frame;
    cv::warpAffine(world, frame, cv::Matx23d(1, 0, -50.0 - 1.0 * i, 0, 1, -40.0 - 0.5 * i), size);
    cv::putText(frame, "2026-11-22 12:00:00 AZ 17.11 EL 3.60", cv::Point(12, 30), cv::FONT_HERSHEY_SIMPLEX, 0.8,
                cv::Scalar(255), 2);
    cv::putText(frame, "FOV 1.24  ZOOM 4x", cv::Point(12, 480), cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(255), 2);
    const BackgroundMotionEstimate& e = motion.update(frame);
    if (i > 0) {
      ASSERT_TRUE(e.known());
      sum += e.displacementAt(cv::Point2d(319.5, 255.5));
    }
  }
  EXPECT_NEAR(sum.x, -19.0, 0.5);  // the world's content moves left and up in the image
  EXPECT_NEAR(sum.y, -9.5, 0.5);
}

TEST(BackgroundMotion, FeaturelessSkyFallsBackToPhaseCorrelation) {
  const cv::Size size(640, 480);
  // A sky gradient with faint, very smooth clouds: no corner Lucas-Kanade can follow.
  cv::Mat sky(size, CV_8U);
  for (int y = 0; y < size.height; ++y) sky.row(y).setTo(cv::Scalar(150 + y / 8));
  cv::Mat clouds = texturedScene(size, 11);
  cv::GaussianBlur(clouds, clouds, cv::Size(0, 0), 30.0);
  cv::addWeighted(sky, 1.0, clouds, 0.3, -38.0, sky);
  const cv::Matx23d truth = cameraMotion(size, 7.0, 2.0, 0.0, 1.0);
  BackgroundMotion motion;
  motion.update(sky);
  const BackgroundMotionEstimate& e = motion.update(moved(sky, truth));
  EXPECT_EQ(e.source, BackgroundMotionEstimate::Source::kPhaseCorrelation);
  EXPECT_LT(centreError(e, truth, size), 0.25);
}

TEST(BackgroundMotion, SensorNoiseAloneSaysUnknown) {
  // Independent noise in each frame has corners but no motion: the estimate must not invent one.
  const cv::Size size(640, 480);
  cv::Mat n1(size, CV_8U), n2(size, CV_8U);
  cv::RNG rng(4);
  for (const double sigma : {1.0, 3.0, 8.0}) {
    rng.fill(n1, cv::RNG::NORMAL, 128, sigma);
    rng.fill(n2, cv::RNG::NORMAL, 128, sigma);
    BackgroundMotion motion;
    motion.update(n1);
    const BackgroundMotionEstimate& e = motion.update(n2);
    EXPECT_FALSE(e.known()) << "noise sigma " << sigma;
    EXPECT_EQ(e.displacementAt(cv::Point2d(320, 240)), cv::Point2d(0, 0));
  }
}

TEST(BackgroundMotion, RejectsBadInput) {
  BackgroundMotion motion;
  EXPECT_THROW(motion.update(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(motion.update(cv::Mat(64, 64, CV_8UC3)), std::invalid_argument);
  EXPECT_THROW(motion.update(cv::Mat(64, 64, CV_8U, cv::Scalar(1)), cv::Mat(3, 3, CV_8U)), std::invalid_argument);
  obstacle_tracker::core::BackgroundMotionSettings bad;
  bad.working_width = 4;
  EXPECT_THROW(BackgroundMotion{bad}, std::invalid_argument);
}
