// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known answers for the overlay mask (overlay_mask.h) fed by the background-motion estimator
// (background_motion.h): a textured world seen by a panning (or still) camera, an on-screen
// display drawn over it at fixed image positions, and targets that move in the world.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/background_motion.h"
#include "obstacle_tracker/core/overlay_mask.h"

using obstacle_tracker::core::BackgroundMotion;
using obstacle_tracker::core::OverlayMask;

namespace {

const cv::Size kFrame(640, 512);

// A world larger than the frame: noise blurred at two scales (trees and fields from afar).
cv::Mat world(unsigned seed) {
  const cv::Size size(kFrame.width + 400, kFrame.height + 200);
  cv::RNG rng(seed);
  cv::Mat sum(size, CV_32F, cv::Scalar(0));
  for (const int cell : {6, 24}) {
    cv::Mat coarse(size.height / cell + 2, size.width / cell + 2, CV_32F);
    rng.fill(coarse, cv::RNG::UNIFORM, -1.0, 1.0);
    cv::Mat fine;
    cv::resize(coarse, fine, cv::Size(coarse.cols * cell, coarse.rows * cell), 0, 0, cv::INTER_CUBIC);
    sum += fine(cv::Rect(0, 0, size.width, size.height)) * 35.0;
  }
  cv::Mat out;
  sum.convertTo(out, CV_8U, 1.0, 120.0);
  return out;
}

// The camera's view of the world at a sub-pixel offset.
cv::Mat view(const cv::Mat& w, cv::Point2d offset) {
  cv::Mat out;
  const cv::Matx23d shift(1, 0, -offset.x, 0, 1, -offset.y);
  cv::warpAffine(w, out, shift, kFrame, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

// An on-screen display like an anti-drone camera's: reticle arms (long thin lines, one dark,
// one bright), corner brackets and text rows. Drawn into `frame`, and into `where` (255).
void drawOverlay(cv::Mat& frame, cv::Mat* where, int clock) {
  const auto line = [&](cv::Point a, cv::Point b, int grey, int width) {
    cv::line(frame, a, b, cv::Scalar(grey), width);
    if (where) cv::line(*where, a, b, cv::Scalar(255), width);
  };
  line({170, 256}, {270, 256}, 20, 2);   // left reticle arm: a 100 x 2 px dark line
  line({370, 256}, {470, 256}, 235, 2);  // right arm, bright
  line({320, 120}, {320, 200}, 235, 2);
  line({40, 40}, {90, 40}, 235, 2);      // corner bracket
  line({40, 40}, {40, 90}, 235, 2);
  const std::string text = "AZ 123.4  EL 05.6  FOV 2.1  12:00:" + std::to_string(10 + clock / 25);
  cv::putText(frame, text, {60, 480}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(240), 2);
  if (where) cv::putText(*where, text, {60, 480}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255), 2);
}

void drawTarget(cv::Mat& frame, cv::Point2d centre, double angle) {
  const cv::RotatedRect body(cv::Point2f(centre), cv::Size2f(26, 12), static_cast<float>(angle));
  cv::ellipse(frame, body, cv::Scalar(40), cv::FILLED, cv::LINE_AA);
  cv::circle(frame, cv::Point(centre) + cv::Point(-13, -5), 3, cv::Scalar(30), cv::FILLED, cv::LINE_AA);
}

struct SimulatedFlight {
  cv::Mat mask;         // the overlay mask at the end, working size
  cv::Mat overlay;      // where the overlay was drawn, working size
  cv::Rect target;      // the target's box in the last frame, working coordinates
  double scale = 1.0;
};

// `pan`: camera speed (px / frame); `target_speed`: the target's speed in the world;
// `followed`: the camera keeps the target near the image centre (it wobbles by about 1.5 px).
SimulatedFlight simulate(cv::Point2d pan, cv::Point2d target_speed, bool followed, int frames = 40) {
  const cv::Mat w = world(21);
  BackgroundMotion motion;
  OverlayMask overlay;
  SimulatedFlight run;
  cv::Mat drawn;
  cv::Point2d target_in_image;
  for (int f = 0; f < frames; ++f) {
    const cv::Point2d offset = cv::Point2d(200, 100) + pan * f;
    cv::Mat frame = view(w, offset);
    const cv::Point2d target_world = cv::Point2d(150, 330) + target_speed * f;
    target_in_image = followed ? cv::Point2d(320 + 1.5 * std::sin(0.9 * f), 330 + 1.5 * std::cos(1.3 * f))
                               : target_world - offset + cv::Point2d(200, 100);
    drawTarget(frame, target_in_image, 8.0 * f);
    drawn = cv::Mat::zeros(kFrame, CV_8U);
    drawOverlay(frame, &drawn, f);
    const auto& e = motion.update(frame, overlay.mask());
    if (e.known()) overlay.update(motion.previousWorkingFrame(), motion.currentWorkingFrame(), motion.workingTransform());
  }
  run.scale = motion.workingScale().x;
  run.mask = overlay.mask().clone();
  cv::resize(drawn, run.overlay, motion.workingSize(kFrame), 0, 0, cv::INTER_AREA);
  cv::compare(run.overlay, 64, run.overlay, cv::CMP_GE);
  const cv::Rect full(cv::Point(target_in_image) - cv::Point(14, 8), cv::Size(28, 16));
  run.target = cv::Rect(cv::Point(full.tl() * run.scale), cv::Point(full.br() * run.scale));
  return run;
}

double coveredShare(const cv::Mat& mask, const cv::Mat& where) {
  return static_cast<double>(cv::countNonZero(mask & where)) / std::max(1, cv::countNonZero(where));
}

double outsideShare(const cv::Mat& mask, const cv::Mat& where) {
  cv::Mat grown;
  cv::dilate(where, grown, cv::Mat(), cv::Point(-1, -1), 2);
  return static_cast<double>(cv::countNonZero(mask & ~grown)) / (mask.rows * mask.cols);
}

}  // namespace

TEST(OverlayMask, FindsTheDisplayUnderASlowPan) {
  // (A pan exactly along a line cannot show that the line is locked: the pans have some tilt, as
  // a real platform's have.)
  for (const cv::Point2d pan : {cv::Point2d(1.0, 0.3), cv::Point2d(0.6, 0.4), cv::Point2d(-3.0, 1.0)}) {
    const SimulatedFlight run = simulate(pan, cv::Point2d(2.5, 1.0), false);
    SCOPED_TRACE("pan " + std::to_string(pan.x) + ", " + std::to_string(pan.y));
    EXPECT_GT(coveredShare(run.mask, run.overlay), 0.8);
    EXPECT_LT(outsideShare(run.mask, run.overlay), 0.005);
    EXPECT_LT(cv::countNonZero(run.mask(run.target & cv::Rect(0, 0, run.mask.cols, run.mask.rows))),
              0.1 * run.target.area());
  }
}

TEST(OverlayMask, ATargetTheCameraFollowsIsNotAnOverlay) {
  const SimulatedFlight run = simulate(cv::Point2d(2.0, -0.5), cv::Point2d(2.0, -0.5), true, 60);
  EXPECT_GT(coveredShare(run.mask, run.overlay), 0.8);
  EXPECT_LT(cv::countNonZero(run.mask(run.target)), 0.2 * run.target.area());
}

TEST(OverlayMask, AStillCameraLeavesTheMaskEmpty) {
  // No camera motion: overlay and world cannot be told apart by motion, and nothing is masked
  // (neither the display nor the still world nor the target).
  const SimulatedFlight run = simulate(cv::Point2d(0.0, 0.0), cv::Point2d(2.5, 1.0), false);
  EXPECT_EQ(cv::countNonZero(run.mask), 0);
}

TEST(OverlayMask, ShareOfABoxAndBadInput) {
  OverlayMask overlay;
  EXPECT_EQ(overlay.share(cv::Rect(0, 0, 10, 10)), 0.0);
  cv::Mat a(64, 64, CV_8U), b;
  cv::randu(a, 0, 255);
  const cv::Matx23d shift(1, 0, 2, 0, 1, 0);
  cv::warpAffine(a, b, shift, a.size());
  for (int i = 0; i < 12; ++i) {
    cv::Mat pa = a.clone(), pb = b.clone();
    for (int x = 10; x < 30; x += 4) {  // vertical bars locked to the image in both frames
      pa(cv::Rect(x, 10, 2, 12)).setTo(255);
      pb(cv::Rect(x, 10, 2, 12)).setTo(255);
      pa(cv::Rect(x + 2, 10, 2, 12)).setTo(0);
      pb(cv::Rect(x + 2, 10, 2, 12)).setTo(0);
    }
    overlay.update(pa, pb, shift);
  }
  EXPECT_GT(overlay.share(cv::Rect(12, 12, 16, 8)), 0.9);
  EXPECT_LT(overlay.share(cv::Rect(40, 40, 16, 16)), 0.1);
  EXPECT_THROW(overlay.update(a, cv::Mat(32, 32, CV_8U), shift), std::invalid_argument);
  EXPECT_THROW(overlay.update(cv::Mat(64, 64, CV_8UC3), b, shift), std::invalid_argument);
}
