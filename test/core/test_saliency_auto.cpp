// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// AutoInitializer on generated sequences with known answers: a small target moving across a sky
// with a fixed on-screen text overlay and a static bright distractor; global motion estimate;
// reset; bad input.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/auto_init.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/core/salient_region.h"
#include "obstacle_tracker/eval/metrics.h"

namespace oc = obstacle_tracker::core;
using obstacle_tracker::eval::centreError;

namespace {

// 640x512 thermal-like frame: textured dark sky (scrolling with the camera by `pan` px), a bright
// static scene blob (moves with the background), a bright ground band, white overlay text fixed
// in the image, and a 12x7 px target at `target` (image coordinates).
cv::Mat makeFrame(const cv::Mat& sky, cv::Point2f pan, cv::Point2f target, cv::Rect2f* target_box) {
  const cv::Size size(640, 512);
  // The camera's view of a larger scene: content moves by +pan in the image.
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, pan.x - 64, 0, 1, pan.y - 64);
  cv::Mat frame;
  cv::warpAffine(sky, frame, shift, size, cv::INTER_LINEAR);
  // Static scene object (moves with the background).
  cv::ellipse(frame, cv::Point(150 + cvRound(pan.x), 300 + cvRound(pan.y)), cv::Size(9, 6), 0, 0, 360,
              cv::Scalar(200), cv::FILLED);
  // Overlay text, fixed in the image.
  cv::putText(frame, "2026-11-22 AZ 17.11 EL 3.60", cv::Point(12, 30), cv::FONT_HERSHEY_SIMPLEX, 0.7,
              cv::Scalar(255), 2);
  cv::putText(frame, "FOV 1.24", cv::Point(12, 70), cv::FONT_HERSHEY_SIMPLEX, 0.7, cv::Scalar(255), 2);
  // The target.
  cv::ellipse(frame, cv::Point(cvRound(target.x), cvRound(target.y)), cv::Size(6, 3), 0, 0, 360, cv::Scalar(170),
              cv::FILLED, cv::LINE_AA);
  *target_box = cv::Rect2f(target.x - 6, target.y - 3, 13, 7);
  return frame;
}

cv::Mat makeSky(cv::RNG& rng) {
  cv::Mat sky(512 + 128, 640 + 128, CV_32F);
  rng.fill(sky, cv::RNG::NORMAL, 0.0, 1.0);
  // Clouds with texture at several scales (the background-motion estimate needs some texture;
  // over a textureless sky the motion is unknown, see background_motion.h).
  cv::Mat fine = sky.clone();
  cv::GaussianBlur(sky, sky, cv::Size(0, 0), 8.0);
  cv::GaussianBlur(fine, fine, cv::Size(0, 0), 2.0);
  cv::normalize(sky, sky, 20, 70, cv::NORM_MINMAX);
  cv::normalize(fine, fine, 0, 25, cv::NORM_MINMAX);
  sky += fine;
  // Textured ground band (trees) touching the bottom border: background the motion estimate can
  // follow.
  cv::Mat ground(sky.rows - (64 + 400), sky.cols, CV_32F);
  rng.fill(ground, cv::RNG::NORMAL, 150.0, 30.0);
  cv::GaussianBlur(ground, ground, cv::Size(0, 0), 1.5);
  ground.copyTo(sky.rowRange(64 + 400, sky.rows));
  cv::Mat u8;
  sky.convertTo(u8, CV_8U);
  cv::Mat noise(u8.size(), CV_8U);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 4);
  u8 += noise;
  return u8;
}

}  // namespace

TEST(AutoInit, ConfirmsTheMovingTargetNotTextNorStaticObjects) {
  for (int seed = 0; seed < 4; ++seed) {
    cv::RNG rng(100 + seed);
    const cv::Mat sky = makeSky(rng);
    oc::AutoInitializer init;
    // The velocity from its own generator: cv::RNG::fill's normal draws (the sky) consume the
    // generator differently on arm64 and x86-64, and the velocity drawn after them differed.
    cv::RNG velocity_rng(200 + seed);
    const cv::Point2f velocity(velocity_rng.uniform(1.5f, 3.0f) * (seed % 2 ? 1 : -1),
                               velocity_rng.uniform(-1.0f, 1.0f));
    const cv::Point2f pan_step(seed >= 2 ? 1.0f : 0.0f, seed >= 2 ? 0.5f : 0.0f);  // camera pans in 2 of 4
    cv::Point2f target(320.0f, 220.0f);
    int confirmed_at = -1;
    for (int i = 0; i < 30; ++i) {
      cv::Rect2f truth;
      const cv::Mat frame = makeFrame(sky, pan_step * static_cast<float>(i), target, &truth);
      const auto& out = init.update(frame, i / 25.0);
      if (!out.empty()) {
        EXPECT_LT(centreError(out[0].box, truth), 6.0f) << "seed " << seed << " frame " << i << " box " << out[0].box << " truth " << truth << " bg " << init.backgroundMotion();
        confirmed_at = i;
        break;
      }
      target += velocity;
    }
    EXPECT_GE(confirmed_at, oc::Params().auto_init_frames - 1) << "seed " << seed;
    EXPECT_LT(confirmed_at, 25) << "seed " << seed;
  }
}

// A 1920 x 1536 and a 1366 x 1093 camera (the scene above, 3x and 2.13x as fine): the front end
// works on the frame shrunk to auto_init_max_width (640), and what it reports is in the camera's
// own pixels: the confirmed box on the target at the camera's scale, candidates inside its frame,
// the background's motion the pan times the scale; when the working width is changed mid-stream
// the front end restarts at the new size and the background's motion goes on from where it was.
TEST(AutoInit, AWideFrameIsSearchedAtTheWorkingWidthAndAnsweredInItsOwnPixels) {
  for (const float fine : {3.0f, 1366.0f / 640.0f}) {
    cv::RNG rng(102);
    const cv::Mat sky = makeSky(rng);
    oc::AutoInitializer init;
    // Seed 2 of the test above: a panning camera.
    cv::RNG velocity_rng(202);
    const cv::Point2f velocity(-velocity_rng.uniform(1.5f, 3.0f), velocity_rng.uniform(-1.0f, 1.0f));
    const cv::Point2f pan_step(1.0f, 0.5f);
    cv::Point2f target(320.0f, 220.0f);
    int confirmed_at = -1;
    for (int i = 0; i < 40; ++i) {
      cv::Rect2f truth;
      const cv::Mat coarse = makeFrame(sky, pan_step * static_cast<float>(i), target, &truth);
      target += velocity;
      cv::Mat frame;
      cv::resize(coarse, frame, cv::Size(cvRound(640 * fine), cvRound(512 * fine)), 0, 0, cv::INTER_LINEAR);
      if (i == 30) {  // a quarter of the width from here on
        oc::SaliencyParams narrower;
        narrower.auto_init_max_width = 160;
        init.setParams(narrower);
      }
      const auto& out = init.update(frame, i / 25.0);
      EXPECT_NEAR(init.backgroundMotion().x, fine * pan_step.x * i, 2.0 * fine) << "frame " << i;
      EXPECT_NEAR(init.backgroundMotion().y, fine * pan_step.y * i, 2.0 * fine) << "frame " << i;
      EXPECT_NEAR(init.framePixelsPerWorkingPixel(), frame.cols / (i < 30 ? 640.0 : 160.0), 1e-9);
      for (const auto& c : init.candidates())
        EXPECT_TRUE(cv::Rect2f(0, 0, frame.cols, frame.rows).contains(oc::boxCentre(c.box))) << c.box;
      if (out.empty() || confirmed_at >= 0) continue;
      confirmed_at = i;
      const cv::Rect2f fine_truth(truth.x * fine, truth.y * fine, truth.width * fine, truth.height * fine);
      EXPECT_LT(centreError(out[0].box, fine_truth), 6.0f * fine) << out[0].box << " truth " << fine_truth;
      EXPECT_GT(out[0].box.width, 0.5f * fine_truth.width) << out[0].box;
      EXPECT_LT(out[0].box.width, 2.0f * fine_truth.width) << out[0].box;
    }
    EXPECT_GE(confirmed_at, oc::Params().auto_init_frames - 1) << fine;
    EXPECT_LT(confirmed_at, 25) << fine;
  }
}

TEST(AutoInit, StaticSceneAloneIsNeverConfirmed) {
  // Same scene without the target: text, static blob and ground must never be confirmed.
  cv::RNG rng(7);
  const cv::Mat sky = makeSky(rng);
  oc::AutoInitializer init;
  for (int i = 0; i < 30; ++i) {
    cv::Rect2f truth;
    cv::Mat frame = makeFrame(sky, cv::Point2f(0.7f * i, 0.0f), cv::Point2f(-50.0f, -50.0f), &truth);
    EXPECT_TRUE(init.update(frame, i / 25.0).empty()) << "frame " << i;
  }
}

TEST(AutoInit, WithoutMotionAndOverlayCuesAStaticObjectWins) {
  // The cues are what makes the difference on this scene: with the motion cue and the overlay
  // rejections off, persistence alone confirms something that is not the target (text, the
  // static blob or the ground) first.
  oc::Params p;
  p.auto_init_min_motion = 0.0;
  p.auto_init_reject_static = false;
  int wrong = 0;
  for (int seed = 0; seed < 4; ++seed) {
    cv::RNG rng(100 + seed);
    const cv::Mat sky = makeSky(rng);
    oc::AutoInitializer init(p);
    cv::Point2f target(320.0f, 220.0f);
    for (int i = 0; i < 30; ++i) {
      cv::Rect2f truth;
      const auto& out = init.update(makeFrame(sky, cv::Point2f(0.0f, 0.0f), target, &truth), i / 25.0);
      if (!out.empty()) {
        wrong += centreError(out[0].box, truth) > 20.0f;
        break;
      }
      target += cv::Point2f(2.0f, 0.5f);
    }
  }
  EXPECT_GE(wrong, 3);
}

TEST(AutoInit, BackgroundMotionFollowsThePan) {
  cv::RNG rng(9);
  const cv::Mat sky = makeSky(rng);
  oc::AutoInitializer init;
  for (int i = 0; i < 10; ++i) {
    cv::Rect2f truth;
    init.update(makeFrame(sky, cv::Point2f(2.0f * i, -1.0f * i), cv::Point2f(-50.0f, -50.0f), &truth), i / 25.0);
  }
  EXPECT_NEAR(init.backgroundMotion().x, 18.0, 2.0);
  EXPECT_NEAR(init.backgroundMotion().y, -9.0, 2.0);
  init.reset();
  EXPECT_EQ(init.backgroundMotion().x, 0.0);
}

// The failure seen on unseen anti-drone footage: a reticle arm (a long thin dark line locked to
// the image) "moves against the background" under a slow pan with a little tilt, and a loop
// that does not know about overlays confirmed it and held it at confidence 1. With the overlay
// mask (overlay_mask.h) the display's lines stop being candidates once the camera has moved a
// little (without it they stay candidates throughout), no obstacle with confidence >= 0.5 is
// ever reported on the display, and
// the first track starts on the target that enters later (this faint 13 x 7 px target over a
// textured sky is then lost by the filter, unverified, which is not this test's subject).
TEST(AutoInit, AReticleUnderASlowPanIsNeverAConfidentObstacle) {
  cv::RNG rng(31);
  const cv::Mat sky = makeSky(rng);
  oc::Pipeline pipeline;
  oc::AutoInitializer init;
  const cv::Rect left_arm(170, 255, 100, 3), right_arm(370, 255, 100, 3), bracket(40, 40, 50, 3);
  int confident_on_display = 0, candidates_on_display = 0;
  float first_error = -1.0f;
  for (int i = 0; i < 150; ++i) {
    // A slow pan with a little tilt and a hand's jitter.
    const cv::Point2f pan(0.7f * i + 0.6f * std::sin(0.7f * i), 0.25f * i + 0.5f * std::cos(1.1f * i));
    // The target flies in from the right after two seconds.
    const cv::Point2f target = i < 50 ? cv::Point2f(-50.0f, -50.0f) : cv::Point2f(560.0f - 2.5f * (i - 50), 150.0f);
    cv::Rect2f truth;
    cv::Mat frame = makeFrame(sky, pan, target, &truth);
    for (const cv::Rect& r : {left_arm, right_arm, bracket}) {
      cv::rectangle(frame, r, cv::Scalar(r == right_arm ? 235 : 20), cv::FILLED);
    }
    // Sensor noise and re-encoding change every pixel, the display's too, by a few grey levels
    // from frame to frame, so the still-pixel cue does not see the display.
    cv::Mat noise(frame.size(), CV_16S);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, 3.0);
    cv::add(frame, noise, frame, cv::noArray(), CV_8U);
    // Candidates on the display: present until the mask has formed (a few frames of pan).
    init.update(frame, i / 25.0);
    for (const oc::SalientRegion& c : init.candidates()) {
      const cv::Rect box(c.box);
      if (i >= 20 && ((box & left_arm).area() > 0 || (box & right_arm).area() > 0 || (box & bracket).area() > 0)) {
        ++candidates_on_display;
      }
    }
    for (const oc::Obstacle& o : pipeline.process(frame, i / 25.0)) {
      if (first_error < 0.0f) first_error = centreError(o.box, truth);
      if (o.confidence < 0.5f) continue;
      const cv::Rect box(o.box);
      if ((box & left_arm).area() > 0 || (box & right_arm).area() > 0 || (box & bracket).area() > 0) {
        ++confident_on_display;
      }
    }
  }
  EXPECT_EQ(confident_on_display, 0);
  EXPECT_EQ(candidates_on_display, 0);
  EXPECT_GE(first_error, 0.0f);
  EXPECT_LE(first_error, 20.0f);
}

// A target the camera follows stays at one place in the image while the background pans: no
// motion cue (it hardly moves in the image) and no growth. The persistence start gives it a
// provisional box within the first second (the most persistent candidate that is neither still
// nor carried by the background: the static scene blob moves with the pan, the overlay text is
// still); nothing off the target is ever reported with confidence >= 0.5.
TEST(AutoInit, ATargetTheCameraFollowsGetsAProvisionalBox) {
  cv::RNG rng(7);
  const cv::Mat sky = makeSky(rng);
  oc::Pipeline pipeline;
  int first_on_target = -1, confident_off_target = 0, first_box = -1;
  for (int i = 0; i < 60; ++i) {
    const cv::Point2f pan(-1.5f * i, 0.4f * i);
    // The camera keeps the target near the centre, with a hand's error of a pixel or two.
    const cv::Point2f target(400.0f + 1.5f * std::sin(0.5f * i), 200.0f + 1.0f * std::cos(0.7f * i));
    cv::Rect2f truth;
    const cv::Mat frame = makeFrame(sky, pan, target, &truth);
    for (const oc::Obstacle& o : pipeline.process(frame, i / 25.0)) {
      if (first_box < 0) {
        // An auto-started track (here the provisional one): unconfirmed, below confidence 0.5.
        first_box = i;
        EXPECT_FALSE(o.confirmed);
        EXPECT_LT(o.confidence, 0.5f);
      }
      const bool on_target = centreError(o.box, truth) <= 20.0f;
      if (on_target && first_on_target < 0) first_on_target = i;
      if (!on_target && o.confidence >= 0.5f) ++confident_off_target;
    }
  }
  EXPECT_GE(first_on_target, 0);
  EXPECT_LT(first_on_target, 25);
  EXPECT_EQ(confident_off_target, 0);
}

// Under a still camera a bright fixed blob (a hot pixel cluster, a buoy) is more salient than a
// dim target that hovers: the persistence start boxes the blob first. The blob never moves in the
// image and is never verified; after auto_init_verify_frames checks it gives the next most
// persistent candidate its chance, and the box goes to the target and stays there (the target
// moves in the image by a few pixels, so it keeps its place although it is not verified either).
TEST(AutoInit, AMotionlessUnverifiedTrackGivesTheNextCandidateItsChance) {
  cv::RNG rng(11);
  cv::Mat sky(256, 320, CV_32F);
  rng.fill(sky, cv::RNG::NORMAL, 0.0, 1.0);
  cv::GaussianBlur(sky, sky, cv::Size(0, 0), 10.0);
  cv::normalize(sky, sky, 30, 60, cv::NORM_MINMAX);
  oc::Pipeline pipeline;
  int first_on_target = -1, first_box = -1, confident_off_target = 0, on_target_after = 0, boxes_after = 0;
  bool first_box_on_target = false;
  for (int i = 0; i < 120; ++i) {
    cv::Mat frame_f = sky.clone();
    cv::ellipse(frame_f, cv::Point(80, 180), cv::Size(6, 5), 0, 0, 360, cv::Scalar(230), cv::FILLED);
    const cv::Point2f target(230.0f + 2.0f * std::sin(0.3f * i), 90.0f + 1.5f * std::cos(0.2f * i));
    cv::ellipse(frame_f, cv::RotatedRect(target, cv::Size2f(20.0f, 12.0f), 0.0f), cv::Scalar(140), cv::FILLED);
    cv::Mat noise(sky.size(), CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, 3.0);  // sensor noise: no pixel stays still
    frame_f += noise;
    const cv::Rect2f truth(target.x - 10.0f, target.y - 6.0f, 20.0f, 12.0f);
    cv::Mat frame;
    frame_f.convertTo(frame, CV_8U);
    for (const oc::Obstacle& o : pipeline.process(frame, i / 25.0)) {
      const bool on_target = centreError(o.box, truth) <= 20.0f;
      if (first_box < 0) {
        first_box = i;
        first_box_on_target = on_target;
      }
      if (on_target && first_on_target < 0) first_on_target = i;
      if (!on_target && o.confidence >= 0.5f) ++confident_off_target;
      if (i >= 80) {
        ++boxes_after;
        on_target_after += on_target;
      }
    }
  }
  EXPECT_GE(first_box, 0);
  EXPECT_FALSE(first_box_on_target);  // the blob first: the scene tests what it says
  EXPECT_GE(first_on_target, 0);
  EXPECT_LT(first_on_target, 80);
  EXPECT_GE(boxes_after, 36);  // frames 80-119
  EXPECT_GE(on_target_after, boxes_after - 2);
  EXPECT_EQ(confident_off_target, 0);
}

// Known answers of the line test used by the verification (pipeline_search.cpp): a straight
// line crossing the box reads near 1, a round blob near 0.
TEST(AutoInit, LineCoherenceKnownAnswers) {
  oc::AutoInitializer init;
  cv::Mat frame(240, 320, CV_8UC1, cv::Scalar(40));
  cv::line(frame, cv::Point(20, 200), cv::Point(180, 40), cv::Scalar(120), 2, cv::LINE_AA);
  cv::circle(frame, cv::Point(250, 120), 10, cv::Scalar(200), cv::FILLED, cv::LINE_AA);
  init.update(frame, 0.0);
  EXPECT_GT(init.lineCoherence(cv::Rect2f(70, 90, 60, 60)), 0.9);
  EXPECT_LT(init.lineCoherence(cv::Rect2f(235, 105, 30, 30)), 0.2);
  EXPECT_DOUBLE_EQ(init.lineCoherence(cv::Rect2f(5, 5, 20, 20)), 0.0);  // flat: no gradient
  EXPECT_DOUBLE_EQ(init.lineCoherence(cv::Rect2f(400, 300, 20, 20)), 0.0);  // outside the frame
}

TEST(AutoInit, SingleFrameModeReturnsCandidatesAtOnce) {
  oc::Params p;
  p.auto_init_frames = 1;
  p.auto_init_min_motion = 0.0;
  oc::AutoInitializer init(p);
  cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(120, 110, 100));
  cv::circle(frame, cv::Point(160, 100), 8, cv::Scalar(20, 20, 20), cv::FILLED);
  const auto& out = init.update(frame, 0.0);
  ASSERT_FALSE(out.empty());
  EXPECT_LT(centreError(out[0].box, cv::Rect2f(152, 92, 17, 17)), 2.0f);
}

TEST(AutoInit, BadInputThrows) {
  oc::AutoInitializer init;
  EXPECT_THROW(init.update(cv::Mat(), 0.0), std::invalid_argument);
  EXPECT_THROW(init.update(cv::Mat(64, 64, CV_32FC1, cv::Scalar(0)), 0.0), std::invalid_argument);
  EXPECT_THROW(init.update(cv::Mat(64, 64, CV_8UC2, cv::Scalar(0)), 0.0), std::invalid_argument);
  // Frame size changes are accepted (state restarts).
  EXPECT_NO_THROW(init.update(cv::Mat(64, 64, CV_8UC1, cv::Scalar(0)), 0.0));
  EXPECT_NO_THROW(init.update(cv::Mat(80, 96, CV_8UC3, cv::Scalar(0)), 0.04));
  EXPECT_NO_THROW(init.update(cv::Mat(2, 2, CV_8UC1, cv::Scalar(0)), 0.08));
  for (const cv::Size sz : {cv::Size(1, 1), cv::Size(1, 500), cv::Size(700, 1), cv::Size(5000, 4), cv::Size(70, 65)})
    for (int i = 0; i < 3; ++i) EXPECT_NO_THROW(init.update(cv::Mat(sz, CV_8UC1, cv::Scalar(i * 40)), 0.1 * i)) << sz;
}
