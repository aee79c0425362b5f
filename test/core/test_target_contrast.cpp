// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// TargetContrast (target_contrast.h): known answers for a small target against sky noise, a box
// on plain sky, one hot pixel, a thin object, a box that covers the view, a colour-only target, a
// near obstacle at 1080p (sampled grids), an object in front of clutter, no allocation, the lost()
// rule, a faint target on a smooth sky and in texture, a box on a piece of cloud when the clouds
// clear, and bad input.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "alloc_counter.h"
#include "noisy_frame.h"
#include "obstacle_tracker/core/target_contrast.h"

namespace core = obstacle_tracker::core;

namespace {

// Sky: a level with Gaussian noise (sigma grey levels).
cv::Mat skyFrame(cv::Size size, double level, double sigma, unsigned seed = 3) {
  return obstacle_tracker::testing::withNoiseAs8Bit(cv::Mat(size, CV_32F, cv::Scalar(level)), sigma, seed);
}

}  // namespace

TEST(TargetContrast, ASmallTargetStandsOutOfTheSkyAndAnEmptyBoxDoesNot) {
  cv::Mat frame = skyFrame(cv::Size(320, 240), 90.0, 3.0);
  // A 5x3 px aircraft 60 levels above the sky in a 17x13 box (annotated boxes keep a margin).
  cv::rectangle(frame, cv::Rect(156, 118, 5, 3), cv::Scalar(150), cv::FILLED);
  const core::TargetContrast contrast;
  const core::TargetContrast::Reading on_target = contrast.read(frame, cv::Rect2f(150.0f, 113.0f, 17.0f, 13.0f));
  const core::TargetContrast::Reading on_sky = contrast.read(frame, cv::Rect2f(60.0f, 60.0f, 17.0f, 13.0f));
  // Noise sigma 3: the target is about 20 sigma out, the empty box's 4th largest pixel ~2-3.
  EXPECT_GT(on_target.ratio, 12.0f);
  EXPECT_LT(on_sky.ratio, core::TargetContrast::kFloor);
  // The ring's noise is the sky's sigma (MAD of the contrasts to the median, to a grey level).
  EXPECT_NEAR(on_target.noise, 3.0f, 1.0f);
  EXPECT_NEAR(on_sky.noise, 3.0f, 1.0f);
  EXPECT_TRUE(core::TargetContrast::lost(on_target, on_sky));
  EXPECT_FALSE(core::TargetContrast::lost(on_target, on_target));
}

TEST(TargetContrast, AnObjectInFrontOfClutterIsNotLost) {
  // An aircraft on plain sky, then the same aircraft in front of a mottled hillside that fills
  // its box's ring: the ratio falls under the floor because the ring's noise rose, not
  // because the box lost the aircraft. The same box on the same clutter without the aircraft is
  // not lost either (nothing can be told there), while a box on plain sky again is.
  const core::TargetContrast contrast;
  const cv::Rect2f box(140.0f, 110.0f, 40.0f, 20.0f);
  cv::Mat sky = skyFrame(cv::Size(320, 240), 150.0, 2.0);
  cv::rectangle(sky, cv::Rect(145, 115, 30, 10), cv::Scalar(220), cv::FILLED);
  const core::TargetContrast::Reading start = contrast.read(sky, box);
  ASSERT_TRUE(core::TargetContrast::checkable(start));
  // The hillside: 4 x 4 px patches of grey levels spread evenly over 40..200.
  cv::Mat patches(60, 80, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(patches, cv::RNG::UNIFORM, 40, 201);
  cv::Mat hill;
  cv::resize(patches, hill, cv::Size(320, 240), 0.0, 0.0, cv::INTER_NEAREST);
  cv::Mat in_front = hill.clone();
  cv::rectangle(in_front, cv::Rect(145, 115, 30, 10), cv::Scalar(220), cv::FILLED);
  const core::TargetContrast::Reading cluttered = contrast.read(in_front, box);
  EXPECT_LT(cluttered.ratio, core::TargetContrast::kFloor);
  EXPECT_GT(cluttered.noise, core::TargetContrast::kMaxNoiseRise * start.noise);
  EXPECT_FALSE(core::TargetContrast::lost(start, cluttered));
  EXPECT_FALSE(core::TargetContrast::lost(start, contrast.read(hill, box)));
  EXPECT_TRUE(core::TargetContrast::lost(start, contrast.read(skyFrame(cv::Size(320, 240), 150.0, 2.0, 9), box)));
}

TEST(TargetContrast, OneHotPixelIsNotAnObject) {
  const cv::Mat sky = skyFrame(cv::Size(200, 150), 90.0, 2.0);
  cv::Mat hot = sky.clone();
  hot.at<uchar>(75, 100) = 255;
  core::TargetContrast contrast;
  const cv::Rect2f box(92.0f, 68.0f, 17.0f, 13.0f);
  // The 4th brightest pixel decides: one saturated pixel moves it by at most one rank.
  EXPECT_NEAR(contrast.measure(hot, box), contrast.measure(sky, box), 0.75f);
  EXPECT_LT(contrast.measure(hot, box), 4.0f);
}

TEST(TargetContrast, AThinObjectInALargeBoxIsSeenWhereverTheSamplingGridFalls) {
  // A wire or an edge-on wing: one row of pixels across a box far wider than the ring's grid.
  for (const int row : {238, 239, 240, 241, 242}) {
    cv::Mat frame = skyFrame(cv::Size(640, 480), 100.0, 2.0);
    frame.row(row).colRange(130, 510).setTo(170);
    core::TargetContrast contrast;
    SCOPED_TRACE(row);
    EXPECT_GT(contrast.measure(frame, cv::Rect2f(120.0f, static_cast<float>(row) - 1.0f, 400.0f, 3.0f)), 20.0f);
  }
}

TEST(TargetContrast, ABoxThatCoversTheViewIsUnknownNotLost) {
  // An obstacle about to hit fills the frame: no ring is left to compare with.
  cv::Mat frame = skyFrame(cv::Size(320, 240), 140.0, 3.0);
  cv::circle(frame, cv::Point(160, 120), 30, cv::Scalar(40), cv::FILLED);
  core::TargetContrast contrast;
  const core::TargetContrast::Reading start = contrast.read(frame, cv::Rect2f(125.0f, 85.0f, 70.0f, 70.0f));
  EXPECT_TRUE(core::TargetContrast::checkable(start));
  cv::circle(frame, cv::Point(160, 120), 400, cv::Scalar(40), cv::FILLED);
  const core::TargetContrast::Reading close = contrast.read(frame, cv::Rect2f(-40.0f, -30.0f, 400.0f, 300.0f));
  EXPECT_EQ(close.ratio, core::TargetContrast::kUnknown);
  EXPECT_FALSE(core::TargetContrast::lost(start, close));
}

TEST(TargetContrast, AColourOnlyTargetCounts) {
  // Same grey level as the sky in two channels: only its red differs (BGR order).
  cv::Mat frame(cv::Size(200, 150), CV_8UC3, cv::Scalar(120, 120, 120));
  cv::Mat noise(frame.size(), CV_8UC3);
  cv::RNG rng(5);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 3);
  frame += noise;
  cv::rectangle(frame, cv::Rect(98, 72, 6, 4), cv::Scalar(120, 120, 200), cv::FILLED);
  const core::TargetContrast contrast;
  EXPECT_GT(contrast.measure(frame, cv::Rect2f(92.0f, 66.0f, 18.0f, 16.0f)), 20.0f);
}

TEST(TargetContrast, ANearObstacleAt1080pIsMeasuredOnSampledGrids) {
  cv::Mat frame = skyFrame(cv::Size(1920, 1080), 140.0, 3.0);
  cv::circle(frame, cv::Point(960, 540), 250, cv::Scalar(60), cv::FILLED);
  const core::TargetContrast contrast;
  const cv::Rect2f box(700.0f, 280.0f, 520.0f, 520.0f);
  EXPECT_GT(contrast.measure(frame, box), 20.0f);
  const cv::Mat sky = skyFrame(cv::Size(1920, 1080), 140.0, 3.0, 9);
  EXPECT_LT(contrast.measure(sky, box), core::TargetContrast::kFloor);
}

TEST(TargetContrast, NoHeapAllocation) {
  OT_SKIP_UNLESS_COUNTING_ALLOCATIONS();
  const cv::Mat frame = skyFrame(cv::Size(1920, 1080), 140.0, 3.0);
  cv::Mat colour;
  cv::cvtColor(frame, colour, cv::COLOR_GRAY2BGR);
  const core::TargetContrast contrast;
  g_allocations = 0;
  g_counting = true;
  float sum = 0.0f;
  for (const cv::Rect2f& box : {cv::Rect2f(700, 280, 520, 520), cv::Rect2f(10, 10, 17, 13), cv::Rect2f(-40, -30, 4000, 3000)}) {
    sum += contrast.measure(frame, box) + contrast.measure(colour, box);
  }
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 0);
  EXPECT_TRUE(std::isfinite(sum));
}

TEST(TargetContrast, LostOnlyWhenNothingStandsOutOfAnObjectThatDidAtItsStart) {
  using C = core::TargetContrast;
  // Readings with the same ring noise, unless said otherwise.
  const auto at = [](float ratio, float noise = 3.0f) { return C::Reading{ratio, noise}; };
  EXPECT_FALSE(C::lost(at(40.0f), at(8.0f)));               // faded to a fifth, still well out of the noise
  EXPECT_TRUE(C::lost(at(40.0f), at(2.0f)));                // nothing there
  // A strong start's floor is kFadeShare of it: a box that slid off a hot drone keeps only its
  // edge, a few sigmas, while the drone itself stays over a hundred.
  EXPECT_TRUE(C::lost(at(120.0f), at(C::kFadeShare * 120.0f - 0.1f)));
  EXPECT_FALSE(C::lost(at(120.0f), at(C::kFadeShare * 120.0f + 0.1f)));
  EXPECT_TRUE(C::lost(at(C::kFirmReference), at(C::kFloor - 0.01f)));
  EXPECT_FALSE(C::lost(at(C::kFirmReference), at(C::kFloor)));
  EXPECT_FALSE(C::lost(at(C::kMinReference - 0.01f), at(0.0f)));  // started faint: no check
  EXPECT_FALSE(C::lost(at(5.0f), at(0.0f)));  // under kFirmReference, its ring unknown: no check
  // A start between kMinReference and kFirmReference counts only if it stood out of what the
  // ring's own pixels read by kStandOut, and then its floor is half of what it read.
  const C::Reading faint{5.0f, 3.0f, 5.0f / C::kStandOut};
  EXPECT_TRUE(C::lost(faint, at(C::kFloorShare * 5.0f - 0.01f)));
  EXPECT_FALSE(C::lost(faint, at(C::kFloorShare * 5.0f)));
  EXPECT_FALSE(C::lost(C::Reading{5.0f, 3.0f, 5.0f / C::kStandOut + 0.01f}, at(0.0f)));  // in clutter: no check
  EXPECT_TRUE(C::lost(C::Reading{C::kFirmReference, 3.0f, C::kFirmReference}, at(C::kFloor - 0.01f)));  // firm: checked
  EXPECT_FALSE(C::lost(at(C::kUnknown, 0.0f), at(0.0f)));   // unknown at the start (box at the frame's edge)
  EXPECT_FALSE(C::lost(at(40.0f), at(C::kUnknown, 0.0f)));  // unknown now (box covers the view)
  // The ring's noise rose: clutter behind the object, where a low ratio tells nothing.
  EXPECT_TRUE(C::lost(at(40.0f, 3.0f), at(2.0f, 3.0f * C::kMaxNoiseRise)));
  EXPECT_FALSE(C::lost(at(40.0f, 3.0f), at(2.0f, 3.0f * C::kMaxNoiseRise + 0.1f)));
  EXPECT_TRUE(C::lost(at(40.0f, 3.0f), at(2.0f, 1.0f)));    // calmer surroundings: still lost
  // The ring's noise fell: the signal must still stand out of the noise the object was first
  // seen against (a ratio of 4.8 on a 5x calmer ring is a signal of 0.9 of that noise).
  EXPECT_TRUE(C::lost(at(10.0f, 16.0f), at(4.8f, 3.1f)));
  EXPECT_TRUE(C::lost(at(10.0f, 16.0f), at(C::kFloor * 16.0f / 3.0f - 0.1f, 3.0f)));
  EXPECT_FALSE(C::lost(at(10.0f, 16.0f), at(C::kFloor * 16.0f / 3.0f + 0.1f, 3.0f)));
  EXPECT_FALSE(C::lost(at(10.0f, 16.0f), at(40.0f, 3.0f)));  // an aircraft out of the clutter into clear sky
}

TEST(TargetContrast, AFaintTargetOnASmoothSkyIsLostWhenItsBoxHoldsOnlySky) {
  // A compressed video's sky is smoother than the sensor's noise: a bird a few levels darker
  // than it reads under kFirmReference but stands out of what the ring's own pixels read. A box
  // the filter left on that sky (the bird flew on) reads under half the bird, and is lost; the
  // same bird on a sky speckled as dark as it, whose ring reads as high as the bird, is not checked.
  const core::TargetContrast contrast;
  cv::Mat sky = skyFrame(cv::Size(320, 240), 150.0, 0.6);
  cv::rectangle(sky, cv::Rect(158, 118, 3, 2), cv::Scalar(145), cv::FILLED);
  const cv::Rect2f box(148.0f, 108.0f, 23.0f, 22.0f);  // an annotated box, mostly sky
  const core::TargetContrast::Reading start = contrast.read(sky, box);
  ASSERT_GE(start.ratio, core::TargetContrast::kMinReference);
  ASSERT_LT(start.ratio, core::TargetContrast::kFirmReference);
  ASSERT_TRUE(core::TargetContrast::checkable(start));
  const core::TargetContrast::Reading left_behind = contrast.read(sky, cv::Rect2f(60.0f, 60.0f, 23.0f, 22.0f));
  EXPECT_TRUE(core::TargetContrast::lost(start, left_behind));
  EXPECT_FALSE(core::TargetContrast::lost(start, start));

  // The textured sky: 3 % of its pixels as dark as the bird.
  cv::Mat textured = skyFrame(cv::Size(320, 240), 150.0, 0.6);
  cv::Mat speckle(240, 320, CV_32F);
  cv::RNG rng(11);
  rng.fill(speckle, cv::RNG::UNIFORM, 0.0, 1.0);
  textured.setTo(145, speckle < 0.03);
  cv::rectangle(textured, cv::Rect(158, 118, 3, 2), cv::Scalar(145), cv::FILLED);
  const core::TargetContrast::Reading in_texture = contrast.read(textured, box);
  ASSERT_GE(in_texture.ratio, core::TargetContrast::kMinReference);
  ASSERT_LT(in_texture.ratio, core::TargetContrast::kFirmReference);
  EXPECT_GT(in_texture.ring_ratio * core::TargetContrast::kStandOut, in_texture.ratio);
  EXPECT_FALSE(core::TargetContrast::checkable(in_texture));
  EXPECT_FALSE(core::TargetContrast::lost(in_texture, contrast.read(textured, cv::Rect2f(60.0f, 60.0f, 23.0f, 22.0f))));
}

TEST(TargetContrast, ABoxOnAPieceOfCloudIsLostWhenTheCloudsClear) {
  // A filter started on a bright streak in a bank of mottled cloud: its ring is noisy and the
  // streak stands out of it by 6 of that noise or more. Then the clouds clear and the box holds a
  // faint remnant of the streak on a plain sky: out of the new, calmer ring's noise by over the
  // floor, but under the floor of the noise it was first measured against. An aircraft that
  // leaves the same clouds for the same sky keeps its signal and is not lost.
  const core::TargetContrast contrast;
  const cv::Rect2f box(140.0f, 110.0f, 40.0f, 20.0f);
  cv::Mat patches(60, 80, CV_8UC1);
  cv::RNG rng(3);
  rng.fill(patches, cv::RNG::NORMAL, 100, 12);
  cv::Mat clouds;
  cv::resize(patches, clouds, cv::Size(320, 240), 0.0, 0.0, cv::INTER_NEAREST);
  cv::rectangle(clouds, cv::Rect(145, 115, 30, 10), cv::Scalar(230), cv::FILLED);
  const core::TargetContrast::Reading start = contrast.read(clouds, box);
  ASSERT_GE(start.ratio, core::TargetContrast::kFirmReference);
  ASSERT_TRUE(core::TargetContrast::checkable(start));
  cv::Mat clear = skyFrame(cv::Size(320, 240), 100.0, 2.0);
  cv::Mat remnant = clear.clone();
  cv::rectangle(remnant, cv::Rect(145, 115, 30, 10), cv::Scalar(112), cv::FILLED);
  const core::TargetContrast::Reading faint = contrast.read(remnant, box);
  ASSERT_GE(faint.ratio, core::TargetContrast::kFloor);  // the ratio alone would keep it
  EXPECT_TRUE(core::TargetContrast::lost(start, faint));
  cv::Mat aircraft = clear.clone();
  cv::rectangle(aircraft, cv::Rect(145, 115, 30, 10), cv::Scalar(230), cv::FILLED);
  EXPECT_FALSE(core::TargetContrast::lost(start, contrast.read(aircraft, box)));
}

TEST(TargetContrast, BadInputIsUnknown) {
  const core::TargetContrast contrast;
  const cv::Mat grey(120, 160, CV_8UC1, cv::Scalar(50));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  constexpr float kUnknown = core::TargetContrast::kUnknown;
  EXPECT_EQ(contrast.measure(cv::Mat(), cv::Rect2f(10, 10, 20, 20)), kUnknown);
  EXPECT_EQ(contrast.measure(cv::Mat(120, 160, CV_16UC1, cv::Scalar(0)), cv::Rect2f(10, 10, 20, 20)), kUnknown);
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(nan, 10, 20, 20)), kUnknown);
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(10, 10, 0.5f, 20)), kUnknown);
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(500, 500, 20, 20)), kUnknown);  // outside the frame
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(-1e30f, 10, 1e30f, 20)), kUnknown);
  EXPECT_EQ(contrast.measure(grey, cv::Rect2f(0, 0, 160, 120)), kUnknown);  // no ring left
}
