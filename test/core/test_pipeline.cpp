// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The closed loop on synthetic frames made here with a fixed seed: textured objects on a smooth
// sky-like background.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/eval/metrics.h"

using obstacle_tracker::core::boxIou;
using obstacle_tracker::core::Obstacle;
using obstacle_tracker::core::Params;
using obstacle_tracker::core::Pipeline;
using obstacle_tracker::core::TrackState;
using obstacle_tracker::eval::centreError;

namespace {

constexpr int kW = 320, kH = 240;

// Smooth sky: vertical gradient plus a faint low-frequency ripple.
cv::Mat sky(unsigned seed = 7) {
  cv::Mat img(kH, kW, CV_8UC3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 6.283f);
  const float p1 = u(rng), p2 = u(rng);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const float v = 150.0f + 60.0f * y / kH + 3.0f * std::sin(0.02f * x + p1) * std::cos(0.015f * y + p2);
      img.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uint8_t>(v + 25), cv::saturate_cast<uint8_t>(v + 10),
                                          cv::saturate_cast<uint8_t>(v - 10));
    }
  }
  return img;
}

// A dark textured object (random blocks), made once per seed and resized to the box.
cv::Mat texture(unsigned seed, cv::Scalar base) {
  cv::Mat t(16, 16, CV_8UC3);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(-45, 45);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      const int n = d(rng);
      t.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uint8_t>(base[0] + n), cv::saturate_cast<uint8_t>(base[1] + n),
                                        cv::saturate_cast<uint8_t>(base[2] + n));
    }
  }
  return t;
}

void drawObject(cv::Mat& frame, const cv::Mat& tex, const cv::Rect& box) {
  const cv::Rect clipped = box & cv::Rect(0, 0, frame.cols, frame.rows);
  if (clipped.area() <= 0) return;
  cv::Mat patch;
  cv::resize(tex, patch, box.size(), 0, 0, cv::INTER_NEAREST);
  patch(cv::Rect(clipped.tl() - box.tl(), clipped.size())).copyTo(frame(clipped));
}

const Obstacle* findId(const std::vector<Obstacle>& obs, int id) {
  for (const auto& o : obs) {
    if (o.id == id) return &o;
  }
  return nullptr;
}

}  // namespace

TEST(Pipeline, BadFramesThrow) {
  Pipeline p;
  EXPECT_THROW(p.process(cv::Mat(), 0.0), std::invalid_argument);
  EXPECT_THROW(p.process(cv::Mat(10, 10, CV_16UC1, cv::Scalar(0)), 0.0), std::invalid_argument);
  EXPECT_THROW(p.process(cv::Mat(10, 10, CV_32FC3, cv::Scalar(0)), 0.0), std::invalid_argument);
  EXPECT_THROW(p.process(cv::Mat(10, 10, CV_8UC4, cv::Scalar(0)), 0.0), std::invalid_argument);
  EXPECT_THROW(p.process(sky(), std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(p.startTrack(sky(), 0.0, cv::Rect2f(nan, 0, 10, 10)), std::invalid_argument);
  EXPECT_THROW(p.startTrack(sky(), 0.0, cv::Rect2f(1000, 1000, 10, 10)), std::invalid_argument);
  EXPECT_THROW(p.startTrack(sky(), 0.0, cv::Rect2f(10, 10, 0, 10)), std::invalid_argument);
  EXPECT_THROW(p.startTrack(cv::Mat(), 0.0, cv::Rect2f(10, 10, 10, 10)), std::invalid_argument);
  // Still usable afterwards.
  EXPECT_NO_THROW(p.process(sky(), 0.0));
}

TEST(Pipeline, NothingInViewGivesEmptyOutput) {
  Pipeline p;
  const cv::Mat frame = sky();
  for (int k = 0; k < 40; ++k) {
    EXPECT_TRUE(p.process(frame, k / 30.0).empty()) << "frame " << k;
    EXPECT_EQ(p.state(), TrackState::kSearching);
  }
}

TEST(Pipeline, TracksAMovingObjectAndGrowsNoStaleBoxWhenItLeaves) {
  Params params;
  params.max_redetect_failures = 5;
  Pipeline p(params);
  const cv::Mat bg = sky();
  const cv::Mat tex = texture(3, cv::Scalar(60, 60, 70));
  cv::Rect truth(60, 100, 24, 18);
  cv::Mat frame = bg.clone();
  drawObject(frame, tex, truth);
  auto out = p.startTrack(frame, 0.0, truth);
  ASSERT_EQ(out.size(), 1u);
  const int id = out[0].id;
  EXPECT_EQ(out[0].state, TrackState::kTracking);
  for (int k = 1; k <= 40; ++k) {
    truth.x += 3;
    truth.y += (k % 2);
    frame = bg.clone();
    drawObject(frame, tex, truth);
    out = p.process(frame, k / 30.0);
    ASSERT_FALSE(out.empty()) << "frame " << k;
    EXPECT_EQ(out[0].id, id);
    EXPECT_LT(centreError(out[0].box, truth), 4.0f) << "frame " << k;
    EXPECT_GT(out[0].confidence, 0.3f);
  }
  // The object vanishes: a few re-detecting frames, one lost report, then nothing.
  int redetecting = 0, lost = 0, k = 41;
  for (; k < 80; ++k) {
    out = p.process(bg, k / 30.0);
    if (out.empty()) break;
    ASSERT_EQ(out.size(), 1u);
    if (out[0].state == TrackState::kRedetecting) ++redetecting;
    if (out[0].state == TrackState::kLost) ++lost;
    EXPECT_NE(out[0].state, TrackState::kTracking) << "a stale box at frame " << k;
  }
  EXPECT_EQ(redetecting, params.max_redetect_failures);
  EXPECT_EQ(lost, 1);
  for (int j = 0; j < 10; ++j) EXPECT_TRUE(p.process(bg, (k + 1 + j) / 30.0).empty());
  EXPECT_EQ(p.state(), TrackState::kSearching);
}

TEST(Pipeline, ReDetectsAfterAJumpInsideTheWindowKeepingTheId) {
  Pipeline p;
  const cv::Mat bg = sky();
  const cv::Mat tex = texture(5, cv::Scalar(50, 55, 60));
  cv::Rect truth(100, 90, 22, 16);
  cv::Mat frame = bg.clone();
  drawObject(frame, tex, truth);
  const int id = p.startTrack(frame, 0.0, truth).at(0).id;
  for (int k = 1; k < 10; ++k) {
    frame = bg.clone();
    drawObject(frame, tex, truth);
    p.process(frame, k / 30.0);
  }
  // A camera jerk: 26 px right, 12 px down, beyond the filter's reach for this box but inside
  // the search window (3 x the box).
  truth.x += 26;
  truth.y += 12;
  bool recovered = false;
  for (int k = 10; k < 20 && !recovered; ++k) {
    frame = bg.clone();
    drawObject(frame, tex, truth);
    const auto& out = p.process(frame, k / 30.0);
    const Obstacle* o = findId(out, id);
    ASSERT_NE(o, nullptr) << "track ended at frame " << k;
    recovered = o->state == TrackState::kTracking && boxIou(o->box, truth) > 0.5f;
  }
  EXPECT_TRUE(recovered);
}

TEST(Pipeline, ReDetectsAfterAJumpLargerThanTheSearchWindow) {
  Params params;
  params.max_redetect_failures = 3;
  Pipeline p(params);
  const cv::Mat bg = sky();
  const cv::Mat tex = texture(9, cv::Scalar(40, 45, 50));
  cv::Rect truth(60, 60, 24, 18);
  cv::Mat frame = bg.clone();
  drawObject(frame, tex, truth);
  p.startTrack(frame, 0.0, truth);
  for (int k = 1; k < 8; ++k) {
    frame = bg.clone();
    drawObject(frame, tex, truth);
    p.process(frame, k / 30.0);
  }
  truth = cv::Rect(200, 140, 24, 18);  // ~170 px away; the window is ~72 px wide
  int found_at = -1;
  for (int k = 8; k < 80; ++k) {
    // It keeps flying (the auto-initialiser confirms moving objects).
    truth.x += 1 + (k % 2);
    truth.y += (k % 3 == 0) ? 1 : 0;
    frame = bg.clone();
    drawObject(frame, tex, truth);
    const auto& out = p.process(frame, k / 30.0);
    if (!out.empty() && out[0].state == TrackState::kTracking && boxIou(out[0].box, truth) > 0.3f) {
      found_at = k;
      break;
    }
  }
  EXPECT_GE(found_at, 8) << "not re-detected within 72 frames";
}

TEST(Pipeline, FullOcclusionLowersConfidenceAndIsNotLearned) {
  Params params;
  params.max_redetect_failures = 30;  // the occlusion lasts 12 frames
  Pipeline p(params);
  const cv::Mat bg = sky();
  const cv::Mat tex = texture(11, cv::Scalar(60, 50, 50));
  const cv::Mat occluder_tex = texture(12, cv::Scalar(200, 200, 200));
  const cv::Rect truth(140, 100, 24, 20);
  cv::Mat frame = bg.clone();
  drawObject(frame, tex, truth);
  const int id = p.startTrack(frame, 0.0, truth).at(0).id;
  float before = 0.0f;
  for (int k = 1; k < 15; ++k) {
    frame = bg.clone();
    drawObject(frame, tex, truth);
    const auto& out = p.process(frame, k / 30.0);
    ASSERT_FALSE(out.empty());
    before = out[0].confidence;
  }
  EXPECT_GT(before, 0.5f);
  // A bright occluder covers the object fully for 12 frames.
  const cv::Rect occluder(truth.x - 8, truth.y - 8, truth.width + 16, truth.height + 16);
  for (int k = 15; k < 27; ++k) {
    frame = bg.clone();
    drawObject(frame, tex, truth);
    drawObject(frame, occluder_tex, occluder);
    const auto& out = p.process(frame, k / 30.0);
    const Obstacle* o = findId(out, id);
    ASSERT_NE(o, nullptr) << "frame " << k;
    EXPECT_LT(o->confidence, 0.5f * before) << "frame " << k;
    EXPECT_FALSE(o->model_updated) << "frame " << k;
    EXPECT_NE(o->state, TrackState::kTracking) << "frame " << k;
  }
  // The object reappears where it was: the same track picks it up again.
  bool back = false;
  for (int k = 27; k < 35 && !back; ++k) {
    frame = bg.clone();
    drawObject(frame, tex, truth);
    const auto& out = p.process(frame, k / 30.0);
    const Obstacle* o = findId(out, id);
    ASSERT_NE(o, nullptr);
    back = o->state == TrackState::kTracking && boxIou(o->box, truth) > 0.5f;
  }
  EXPECT_TRUE(back);
}

TEST(Pipeline, TwoCrossingObjectsKeepTheirIds) {
  Params params;
  params.max_obstacles = 2;
  Pipeline p(params);
  const cv::Mat bg = sky();
  const cv::Mat tex_a = texture(21, cv::Scalar(40, 40, 90));
  const cv::Mat tex_b = texture(22, cv::Scalar(90, 60, 30));
  auto boxA = [](int k) { return cv::Rect(40 + 4 * k, 100, 24, 18); };
  auto boxB = [](int k) { return cv::Rect(260 - 4 * k, 112, 24, 18); };
  auto render = [&](int k) {
    cv::Mat f = bg.clone();
    drawObject(f, tex_a, boxA(k));
    drawObject(f, tex_b, boxB(k));  // B passes in front of A
    return f;
  };
  cv::Mat frame = render(0);
  const int id_a = p.startTrack(frame, 0.0, boxA(0)).at(0).id;
  const auto& first = p.startTrack(frame, 0.0, boxB(0));
  ASSERT_EQ(first.size(), 2u);
  const int id_b = findId(first, id_a) == &first[0] ? first[1].id : first[0].id;
  ASSERT_NE(id_a, id_b);
  for (int k = 1; k <= 50; ++k) {
    frame = render(k);
    const auto& out = p.process(frame, k / 30.0);
    const Obstacle* a = findId(out, id_a);
    const Obstacle* b = findId(out, id_b);
    if (k < 20 || k > 36) {  // away from the crossing (centres meet at k = 27.5)
      ASSERT_NE(a, nullptr) << "frame " << k;
      ASSERT_NE(b, nullptr) << "frame " << k;
      EXPECT_LT(centreError(a->box, boxA(k)), 6.0f) << "frame " << k;
      EXPECT_LT(centreError(b->box, boxB(k)), 6.0f) << "frame " << k;
    }
  }
  EXPECT_LE(p.process(render(51), 51 / 30.0).size(), 2u);
}

TEST(Pipeline, StampGoingBackwardsResets) {
  Pipeline p;
  const cv::Mat bg = sky();
  const cv::Mat tex = texture(31, cv::Scalar(50, 50, 50));
  const cv::Rect truth(100, 100, 24, 18);
  cv::Mat frame = bg.clone();
  drawObject(frame, tex, truth);
  const int id = p.startTrack(frame, 10.0, truth).at(0).id;
  EXPECT_EQ(p.process(frame, 10.1).size(), 1u);
  const auto& out = p.process(frame, 5.0);  // backwards
  EXPECT_EQ(findId(out, id), nullptr);
  const int id2 = p.startTrack(frame, 5.1, truth).at(0).id;
  EXPECT_NE(id2, id);
  p.reset();
  EXPECT_EQ(p.state(), TrackState::kSearching);
}

TEST(Pipeline, SetParamsAppliesFromTheNextFrame) {
  Pipeline p;
  const cv::Mat bg = sky();
  const cv::Mat tex = texture(41, cv::Scalar(50, 50, 50));
  const cv::Rect truth(100, 100, 24, 18);
  cv::Mat frame = bg.clone();
  drawObject(frame, tex, truth);
  p.startTrack(frame, 0.0, truth);
  EXPECT_EQ(p.process(frame, 0.1).at(0).state, TrackState::kTracking);
  Params strict = p.params();
  strict.peak_threshold = 1.0;  // no response reaches it
  strict.max_redetect_failures = 100;
  strict.merge_iou = 7.0;  // out of range: clamped
  p.setParams(strict);
  EXPECT_DOUBLE_EQ(p.params().peak_threshold, 1.0);
  EXPECT_DOUBLE_EQ(p.params().merge_iou, 1.0);
  EXPECT_EQ(p.process(frame, 0.2).at(0).state, TrackState::kRedetecting);
}

TEST(Pipeline, LoomingOfAnApproachingObject) {
  // Constant closing speed: s(t) = s0 * T / (T - t), contact at T = 3 s, 30 frames per second.
  Params params;
  Pipeline p(params);
  const cv::Mat bg = sky();
  const cv::Mat tex = texture(51, cv::Scalar(40, 40, 40));
  const double T = 3.0, s0 = 16.0;
  auto boxAt = [&](int k) {
    const double t = k / 30.0;
    const double s = s0 * T / (T - t);
    return cv::Rect(cvRound(160 - 0.65 * s), cvRound(120 - 0.5 * s), cvRound(1.3 * s), cvRound(s));
  };
  cv::Mat frame = bg.clone();
  drawObject(frame, tex, boxAt(0));
  p.startTrack(frame, 0.0, boxAt(0));
  for (int k = 1; k <= 45; ++k) {
    frame = bg.clone();
    drawObject(frame, tex, boxAt(k));
    const auto& out = p.process(frame, k / 30.0);
    ASSERT_FALSE(out.empty());
    // The object is drawn at whole-pixel sizes, so it grows in 1 px steps; the rate from its
    // pixel expansions is within 25 % once it has grown a few steps.
    if (k >= 24) {
      const double truth = T - k / 30.0;
      EXPECT_NEAR(out[0].time_to_contact, truth, 0.25 * truth) << "frame " << k;
    }
  }
}
