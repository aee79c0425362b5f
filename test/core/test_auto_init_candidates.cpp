// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// AutoInitializer's candidates on generated scenes: the second source (auto_init_cells.cpp,
// isolatedPeaks) makes a small, faint object alone on plain sky a candidate although a bright
// structure and a textured tree line take the frame's saliency, and still specks do not crowd it
// out; a band along the frame is no candidate (keepCandidate).
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/auto_init.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/core/salient_region.h"
#include "obstacle_tracker/eval/metrics.h"

namespace oc = obstacle_tracker::core;
using obstacle_tracker::eval::centreError;

namespace {

// 640x512 visible-like frame under a still camera: plain sky (grey 150, sensor noise), a bright
// sign on a post standing in the sky, a textured tree line along the bottom, and a 4x3 px bird
// 14 grey levels darker than the sky at `bird`.
struct BirdScene {
  cv::Mat trees;
  explicit BirdScene(cv::RNG& rng) : trees(112, 640, CV_8U) {
    rng.fill(trees, cv::RNG::UNIFORM, 40, 200);
    cv::GaussianBlur(trees, trees, cv::Size(0, 0), 1.2);
  }
  cv::Mat frame(cv::RNG& rng, cv::Point2f bird, cv::Rect2f* bird_box) const {
    cv::Mat f(512, 640, CV_8U, cv::Scalar(150));
    cv::Mat noise(f.size(), CV_8U);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 3);
    f += noise;
    cv::rectangle(f, cv::Rect(520, 250, 50, 90), cv::Scalar(250), cv::FILLED);  // the sign
    cv::rectangle(f, cv::Rect(543, 340, 4, 60), cv::Scalar(70), cv::FILLED);    // its post
    trees.copyTo(f.rowRange(400, 512));
    *bird_box = cv::Rect2f(bird.x - 2.0f, bird.y - 1.5f, 4.0f, 3.0f);
    cv::rectangle(f, cv::Rect(cvRound(bird_box->x), cvRound(bird_box->y), 4, 3), cv::Scalar(136), cv::FILLED);
    return f;
  }
};

bool anyCandidateNear(const std::vector<oc::SalientRegion>& regions, const cv::Rect2f& truth, float px) {
  for (const oc::SalientRegion& r : regions)
    if (centreError(r.box, truth) <= px) return true;
  return false;
}

}  // namespace

// The bird's local contrast is 14 grey levels on a sky whose own is about 1; the sign's and the
// trees' are far higher, and MBD saliency normalised to the sign leaves the bird a few grey levels
// of the candidate map P. It is a candidate on every frame from the contrast source, and, moving
// 1.5 px a frame, it is confirmed on its motion within a second; nothing else is confirmed.
TEST(AutoInitIsolated, AFaintBirdOnPlainSkyBesideABrightSignIsACandidateAndIsConfirmed) {
  for (int seed = 0; seed < 3; ++seed) {
    cv::RNG rng(300 + seed);
    const BirdScene scene(rng);
    oc::AutoInitializer init;
    cv::Point2f bird(200.0f + 40.0f * seed, 150.0f + 30.0f * seed);
    const cv::Point2f velocity(1.5f, seed == 1 ? -0.5f : 0.3f);
    int confirmed_at = -1;
    for (int i = 0; i < 30 && confirmed_at < 0; ++i) {
      cv::Rect2f truth;
      const cv::Mat f = scene.frame(rng, bird, &truth);
      const auto& confirmed = init.update(f, i / 25.0);
      EXPECT_TRUE(anyCandidateNear(init.candidates(), truth, 4.0f)) << "seed " << seed << " frame " << i;
      if (!confirmed.empty()) {
        EXPECT_EQ(confirmed.size(), 1u) << "seed " << seed << " frame " << i;
        EXPECT_LT(centreError(confirmed[0].box, truth), 4.0f) << "seed " << seed << " frame " << i;
        confirmed_at = i;
      }
      bird += velocity;
    }
    EXPECT_GE(confirmed_at, 0) << "seed " << seed;
  }
}

// A sky full of isolated specks (60 fixed stars, lamps or dead pixels, three cells apart, below
// the bird's path, 20 grey levels darker than the sky where the bird is 14, so more isolated than
// the bird): the contrast source keeps at most its share (8) of candidates beside the peaks of P,
// the still ones after the moving one, so the bird is still found and confirmed, and only the
// bird.
TEST(AutoInitIsolated, ASkyFullOfStillSpecksDoesNotCrowdOutTheBird) {
  cv::RNG rng(400);
  const BirdScene scene(rng);
  std::vector<cv::Point> specks;  // 12 x 5
  for (int y = 180; y < 400; y += 48)
    for (int x = 40; x < 620; x += 48) specks.emplace_back(x, y);
  const oc::SaliencyParams params;
  oc::AutoInitializer init(params);
  cv::Point2f bird(100.0f, 100.0f);
  int confirmed_at = -1;
  for (int i = 0; i < 30 && confirmed_at < 0; ++i) {
    cv::Rect2f truth;
    cv::Mat f = scene.frame(rng, bird, &truth);
    for (const cv::Point& s : specks) cv::rectangle(f, cv::Rect(s.x, s.y, 3, 3), cv::Scalar(130), cv::FILLED);
    const auto& confirmed = init.update(f, i / 25.0);
    EXPECT_LE(static_cast<int>(init.candidates().size()), params.auto_init_candidates + 8) << "frame " << i;
    if (!confirmed.empty()) {
      EXPECT_LT(centreError(confirmed[0].box, truth), 4.0f) << "frame " << i;
      EXPECT_EQ(confirmed.size(), 1u) << "frame " << i;
      confirmed_at = i;
    }
    bird += cv::Point2f(1.5f, 0.5f);
  }
  EXPECT_GE(confirmed_at, 0);
}

// A thermal view under a still camera: a warm strip along the bottom of the frame (a textured band
// the whole width, 6 px tall, its level changing by a few grey levels from frame to frame), and a
// distant aircraft of 4 x 3 px that hardly moves. The band's pieces, cut at the candidates' growth
// radius, are never candidates (a band is no object), so the first box of the loop is the aircraft.
TEST(AutoInitCandidates, AWarmBandAlongTheFrameIsNoCandidate) {
  cv::RNG rng(500);
  cv::Mat band(6, 320, CV_8U);
  rng.fill(band, cv::RNG::UNIFORM, 150, 200);
  cv::GaussianBlur(band, band, cv::Size(0, 0), 2.0);
  oc::Pipeline pipeline;
  int first_box = -1, on_band = 0;
  float first_error = -1.0f;
  for (int i = 0; i < 60; ++i) {
    cv::Mat f(256, 320, CV_8U, cv::Scalar(60));
    cv::Mat noise(f.size(), CV_8U);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 4);
    f += noise;
    cv::Mat row = band.clone();
    row += cv::Scalar(rng.uniform(0, 6));
    row.copyTo(f.rowRange(244, 250));
    const cv::Rect2f aircraft(134.0f + 0.07f * i, 155.0f, 4.0f, 3.0f);
    cv::rectangle(f, cv::Rect(cvRound(aircraft.x), cvRound(aircraft.y), 4, 3), cv::Scalar(110), cv::FILLED);
    for (const oc::Obstacle& o : pipeline.process(f, i / 25.0)) {
      if (first_box < 0) {
        first_box = i;
        first_error = centreError(o.box, aircraft);
      }
      on_band += o.box.y + o.box.height > 240.0f;
    }
  }
  EXPECT_GE(first_box, 0);
  EXPECT_LE(first_error, 4.0f);
  EXPECT_EQ(on_band, 0);
}
