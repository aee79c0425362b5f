// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Known-answer tests of the OTB and VOT long-term metrics (src/eval/metrics.cpp).
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "obstacle_tracker/eval/metrics.h"

namespace ev = obstacle_tracker::eval;
namespace oc = obstacle_tracker::core;
using cv::Rect2f;

namespace {
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const Rect2f kGt(0, 0, 10, 10);
const Rect2f kNone(0, 0, 0, 0);

// The OTB toolkit's calcRectInt.m + overlap, written out independently (pixel-inclusive corners).
double otbToolkitOverlap(const Rect2f& a, const Rect2f& b) {
  const double la = a.x, ra = a.x + a.width - 1, ta = a.y, ba = a.y + a.height - 1;
  const double lb = b.x, rb = b.x + b.width - 1, tb = b.y, bb = b.y + b.height - 1;
  const double w = std::max(0.0, std::min(ra, rb) - std::max(la, lb) + 1);
  const double h = std::max(0.0, std::min(ba, bb) - std::max(ta, tb) + 1);
  const double inter = w * h;
  return inter / (double(a.width) * a.height + double(b.width) * b.height - inter);
}
}  // namespace

TEST(Metrics, AbsentBoxes) {
  EXPECT_TRUE(ev::isAbsent(kNone));
  EXPECT_TRUE(ev::isAbsent(Rect2f(5, 5, 0, 10)));
  EXPECT_TRUE(ev::isAbsent(Rect2f(5, 5, -3, 10)));
  EXPECT_TRUE(ev::isAbsent(Rect2f(kNaN, 5, 10, 10)));
  EXPECT_TRUE(ev::isAbsent(Rect2f(5, 5, 10, kNaN)));
  EXPECT_FALSE(ev::isAbsent(Rect2f(0, 0, 1, 1)));
  EXPECT_FALSE(ev::isAbsent(Rect2f(-4, -4, 1, 1)));  // partly outside the image is still a box
}

TEST(Metrics, CentreErrorAndIou) {
  EXPECT_DOUBLE_EQ(ev::centreError(kGt, Rect2f(3, 4, 10, 10)), 5.0);
  EXPECT_DOUBLE_EQ(ev::centreError(kGt, Rect2f(-1, -1, 12, 12)), 0.0);  // same centre, other size
  EXPECT_TRUE(std::isinf(ev::centreError(kGt, kNone)));
  EXPECT_DOUBLE_EQ(oc::boxIou<double>(kGt, kGt), 1.0);
  EXPECT_DOUBLE_EQ(oc::boxIou<double>(kGt, Rect2f(5, 0, 10, 10)), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(oc::boxIou<double>(kGt, Rect2f(2, 2, 5, 5)), 25.0 / 100.0);   // inside
  EXPECT_DOUBLE_EQ(oc::boxIou<double>(kGt, Rect2f(10, 0, 10, 10)), 0.0);         // touching edges
  EXPECT_DOUBLE_EQ(oc::boxIou<double>(kGt, Rect2f(30, 30, 5, 5)), 0.0);
  EXPECT_DOUBLE_EQ(oc::boxIou<double>(kGt, kNone), 0.0);
  EXPECT_DOUBLE_EQ(oc::boxIou<double>(kGt, Rect2f(kNaN, 0, 10, 10)), 0.0);
  EXPECT_EQ(oc::boxIou<float>(kGt, kNone), 0.0f);
  EXPECT_EQ(oc::boxIou<float>(kGt, Rect2f(kNaN, 0, 10, 10)), 0.0f);
}

TEST(Metrics, IouMatchesOtbToolkitFormula) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pos(-20, 60), size(1, 40);
  for (int k = 0; k < 2000; ++k) {
    const Rect2f a(pos(rng), pos(rng), size(rng), size(rng));
    const Rect2f b(pos(rng), pos(rng), size(rng), size(rng));
    ASSERT_NEAR(oc::boxIou<double>(a, b), otbToolkitOverlap(a, b), 1e-12) << k;
    ASSERT_DOUBLE_EQ(oc::boxIou<double>(a, b), oc::boxIou<double>(b, a));
    // The tracking loop's float IoU is the same computation, to float rounding.
    ASSERT_NEAR(oc::boxIou<float>(a, b), oc::boxIou<double>(a, b), 1e-6) << k;
  }
}

TEST(Metrics, ThresholdGrids) {
  EXPECT_EQ(ev::kPrecisionThresholdCount, 51);
  EXPECT_EQ(ev::kSuccessThresholdCount, 21);
  EXPECT_DOUBLE_EQ(ev::precisionThreshold(50), 50.0);
  EXPECT_NEAR(ev::successThreshold(20), 1.0, 1e-12);
  EXPECT_NEAR(ev::successThreshold(10), 0.5, 1e-12);
}

TEST(Metrics, OtbPrecisionKnownAnswer) {
  // Centre errors 0, 10, 30, none (tracker reported nothing); the fifth frame has no ground
  // truth and is left out.
  const std::vector<Rect2f> gt = {kGt, kGt, kGt, kGt, kNone};
  const std::vector<Rect2f> pred = {kGt, Rect2f(6, 8, 10, 10), Rect2f(18, 24, 10, 10), kNone,
                                    Rect2f(100, 100, 5, 5)};
  const ev::FrameErrors e = ev::frameErrors(pred, gt);
  EXPECT_EQ(e.absent_gt_frames, 1);
  ASSERT_EQ(e.centre_error.size(), 4u);
  const ev::OtbScores s = ev::otbScores(e);
  EXPECT_EQ(s.frames, 4);
  ASSERT_EQ(s.precision.size(), 51u);
  EXPECT_DOUBLE_EQ(s.precision[0], 0.25);
  EXPECT_DOUBLE_EQ(s.precision[9], 0.25);
  EXPECT_DOUBLE_EQ(s.precision[10], 0.5);  // <= t, as in OTB
  EXPECT_DOUBLE_EQ(s.precision20, 0.5);
  EXPECT_DOUBLE_EQ(s.precision[29], 0.5);
  EXPECT_DOUBLE_EQ(s.precision[30], 0.75);
  EXPECT_DOUBLE_EQ(s.precision[50], 0.75);  // the lost frame never counts
  EXPECT_DOUBLE_EQ(s.mean_centre_error, 40.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.lost_fraction, 0.25);
}

TEST(Metrics, OtbSuccessKnownAnswer) {
  // IoUs 1, 1/3, 0.
  const std::vector<Rect2f> gt = {kGt, kGt, kGt};
  const std::vector<Rect2f> pred = {kGt, Rect2f(5, 0, 10, 10), Rect2f(40, 0, 10, 10)};
  const ev::OtbScores s = ev::otbScores(pred, gt);
  ASSERT_EQ(s.success.size(), 21u);
  for (int i = 0; i <= 6; ++i) EXPECT_DOUBLE_EQ(s.success[i], 2.0 / 3.0) << i;   // o <= 0.30
  for (int i = 7; i <= 19; ++i) EXPECT_DOUBLE_EQ(s.success[i], 1.0 / 3.0) << i;  // 0.35..0.95
  EXPECT_DOUBLE_EQ(s.success[20], 0.0);  // IoU > 1 never holds (OTB's strict >)
  EXPECT_NEAR(s.auc, 9.0 / 21.0, 1e-12);
}

TEST(Metrics, AucApproximatesMeanOverlap) {
  // The AUC of the success plot is the mean overlap up to the threshold grid (Cehovin et al.).
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> shift(-8.0f, 8.0f);
  std::vector<Rect2f> gt, pred;
  double mean_iou = 0.0;
  for (int k = 0; k < 5000; ++k) {
    gt.push_back(kGt);
    pred.emplace_back(shift(rng), shift(rng), 10.0f, 10.0f);
    mean_iou += oc::boxIou<double>(pred.back(), kGt);
  }
  mean_iou /= gt.size();
  EXPECT_NEAR(ev::otbScores(pred, gt).auc, mean_iou, 0.05 / 2 + 1e-3);
}

TEST(Metrics, EmptyAndAllAbsent) {
  const ev::OtbScores s = ev::otbScores(std::vector<Rect2f>{kNone, kNone}, std::vector<Rect2f>{kNone, kNone});
  EXPECT_EQ(s.frames, 0);
  EXPECT_DOUBLE_EQ(s.precision20, 0.0);
  EXPECT_DOUBLE_EQ(s.auc, 0.0);
  EXPECT_TRUE(std::isnan(s.mean_centre_error));
}

TEST(Metrics, SizeMismatchThrows) {
  EXPECT_THROW(ev::frameErrors({kGt}, {kGt, kGt}), std::invalid_argument);
  EXPECT_THROW(ev::longTermScores({kGt}, {1.0f, 1.0f}, {kGt}), std::invalid_argument);
  EXPECT_THROW(ev::longTermScores({kGt}, {kNaN}, {kGt}), std::invalid_argument);
}

TEST(Metrics, PooledSegmentsEqualOneRun) {
  // TRE pools the frames of its segments: appending errors = scoring the concatenation.
  const std::vector<Rect2f> gt = {kGt, kGt, kGt, kNone, kGt};
  const std::vector<Rect2f> pred = {kGt, Rect2f(5, 0, 10, 10), kNone, kGt, Rect2f(1, 2, 10, 10)};
  ev::FrameErrors pooled = ev::frameErrors({pred[0], pred[1]}, {gt[0], gt[1]});
  pooled.append(ev::frameErrors({pred[2], pred[3], pred[4]}, {gt[2], gt[3], gt[4]}));
  const ev::OtbScores a = ev::otbScores(pooled), b = ev::otbScores(pred, gt);
  EXPECT_EQ(a.precision, b.precision);
  EXPECT_EQ(a.success, b.success);
  EXPECT_EQ(pooled.absent_gt_frames, 1);
}

TEST(Metrics, MeanOverRuns) {
  const ev::OtbScores a = ev::otbScores(std::vector<Rect2f>{kGt}, std::vector<Rect2f>{kGt});
  const ev::OtbScores b = ev::otbScores(std::vector<Rect2f>{kNone}, std::vector<Rect2f>{kGt});
  const ev::OtbScores m = ev::meanOtbScores({a, b});
  EXPECT_DOUBLE_EQ(m.precision20, 0.5);
  EXPECT_DOUBLE_EQ(m.auc, (1.0 + 0.0) / 2.0 * 20.0 / 21.0 + 0.0);  // a's curve is 1 except at o = 1
  EXPECT_DOUBLE_EQ(m.success[0], 0.5);
  EXPECT_DOUBLE_EQ(m.mean_centre_error, 0.0);  // b has no finite error
  EXPECT_EQ(m.frames, 2);
}

TEST(Metrics, LongTermKnownAnswer) {
  // Four frames with the target, two without. Reports: exact (0.9), IoU 1/3 (0.6), nothing,
  // exact (0.2), false positive (0.1), false positive (0.8).
  const std::vector<Rect2f> gt = {kGt, kGt, kGt, kGt, kNone, kNone};
  const std::vector<Rect2f> pred = {kGt, Rect2f(5, 0, 10, 10), kNone, kGt, Rect2f(3, 3, 4, 4),
                                    Rect2f(3, 3, 4, 4)};
  const std::vector<float> conf = {0.9f, 0.6f, 0.95f, 0.2f, 0.1f, 0.8f};  // 0.95 ignored: no box
  const ev::LongTermScores s = ev::longTermScores(pred, conf, gt);
  EXPECT_EQ(s.frames, 6);
  EXPECT_EQ(s.present_frames, 4);
  ASSERT_EQ(s.thresholds.size(), 5u);
  // tau = 0.1: Pr = (1 + 1/3 + 1) / 5, Re = (1 + 1/3 + 1) / 4.
  EXPECT_NEAR(s.precision_curve[0], 7.0 / 15.0, 1e-12);
  EXPECT_NEAR(s.recall_curve[0], 7.0 / 12.0, 1e-12);
  // tau = 0.6: reports at 0.9, 0.6, 0.8: Pr = (4/3)/3, Re = (4/3)/4, F = 8/21.
  EXPECT_NEAR(s.fscore_curve[2], 8.0 / 21.0, 1e-12);
  // tau = 0.9: Pr 1, Re 1/4, F 0.4.
  EXPECT_NEAR(s.precision_curve[4], 1.0, 1e-12);
  EXPECT_NEAR(s.fscore_curve[4], 0.4, 1e-12);
  // Best: tau = 0.2 with Pr = Re = F = 7/12.
  EXPECT_NEAR(s.threshold, 0.2, 1e-6);
  EXPECT_NEAR(s.precision, 7.0 / 12.0, 1e-12);
  EXPECT_NEAR(s.recall, 7.0 / 12.0, 1e-12);
  EXPECT_NEAR(s.fscore, 7.0 / 12.0, 1e-12);
}

TEST(Metrics, LongTermPerfectAndSilent) {
  const std::vector<Rect2f> gt = {kGt, kNone, kGt};
  const ev::LongTermScores perfect = ev::longTermScores(gt, {0.7f, 0.0f, 0.7f}, gt);
  EXPECT_DOUBLE_EQ(perfect.fscore, 1.0);
  const ev::LongTermScores silent = ev::longTermScores({kNone, kNone, kNone}, {1.f, 1.f, 1.f}, gt);
  EXPECT_DOUBLE_EQ(silent.fscore, 0.0);
  EXPECT_TRUE(silent.thresholds.empty());
}

TEST(Metrics, LongTermThresholdCap) {
  std::vector<Rect2f> gt(500, kGt), pred(500, kGt);
  std::vector<float> conf(500);
  for (int i = 0; i < 500; ++i) conf[i] = i / 500.0f;
  const ev::LongTermScores s = ev::longTermScores(pred, conf, gt, 10);
  ASSERT_EQ(s.thresholds.size(), 10u);
  EXPECT_FLOAT_EQ(s.thresholds.front(), 0.0f);
  EXPECT_FLOAT_EQ(s.thresholds.back(), 499 / 500.0f);
  EXPECT_DOUBLE_EQ(s.fscore, 1.0);  // tau = 0 keeps every (perfect) report
}

TEST(Metrics, SenseAvoidKnownAnswer) {
  const cv::Rect2f none;
  const cv::Rect2f t(100, 100, 10, 10);
  // Frames: 0 no box (target present), 1 a far confident box (false confident), 2 the target
  // half-overlapped (IoU 1/3, centre 5 px off: the first correct start), 3 exact, 4 target absent
  // and no box (state 1), 5 target absent and a confident box (state 0, false confident).
  const std::vector<cv::Rect2f> gt = {t, t, t, t, none, none};
  const std::vector<cv::Rect2f> pred = {none, cv::Rect2f(300, 300, 10, 10), cv::Rect2f(105, 100, 10, 10), t, none,
                                        cv::Rect2f(5, 5, 10, 10)};
  const std::vector<float> conf = {0.0f, 0.9f, 0.6f, 1.0f, 0.0f, 0.7f};
  const ev::SenseAvoidScores s = ev::senseAvoidScores(pred, conf, gt);
  EXPECT_EQ(s.frames, 6);
  EXPECT_NEAR(s.state_accuracy, (0.0 + 0.0 + 50.0 / 150.0 + 1.0 + 1.0 + 0.0) / 6.0, 1e-9);
  EXPECT_EQ(s.first_present_frame, 0);
  EXPECT_EQ(s.first_correct_frame, 2);
  // The first box is the far one of frame 1 (centre 200 px off on each axis): a wrong start,
  // whatever comes later.
  EXPECT_EQ(s.first_box_frame, 1);
  EXPECT_NEAR(s.first_box_error, 200.0 * std::sqrt(2.0), 1e-9);
  EXPECT_FALSE(ev::firstBoxCorrect(s, 30));
  EXPECT_EQ(s.false_confident_frames, 2);
  EXPECT_NEAR(s.false_confident_rate, 2.0 / 6.0, 1e-12);
  // A box without confidence is not a confident one; a threshold above every confidence: none.
  EXPECT_EQ(ev::senseAvoidScores(pred, std::vector<float>(6, 0.49f), gt).false_confident_frames, 0);
  EXPECT_EQ(ev::senseAvoidScores(pred, conf, gt, 0.95).false_confident_frames, 0);
}

TEST(Metrics, SenseAvoidNeverCorrectAndSizes) {
  const std::vector<cv::Rect2f> gt(3, cv::Rect2f(0, 0, 10, 10));
  const std::vector<cv::Rect2f> far(3, cv::Rect2f(100, 100, 10, 10));
  const ev::SenseAvoidScores s = ev::senseAvoidScores(far, std::vector<float>(3, 0.2f), gt);
  EXPECT_EQ(s.first_correct_frame, -1);
  EXPECT_DOUBLE_EQ(s.state_accuracy, 0.0);
  EXPECT_EQ(s.false_confident_frames, 0);
  // Far boxes from the first frame on: the first box is frame 0's, 100 px off on each axis.
  EXPECT_EQ(s.first_box_frame, 0);
  EXPECT_NEAR(s.first_box_error, 100.0 * std::sqrt(2.0), 1e-9);
  EXPECT_THROW(ev::senseAvoidScores(far, std::vector<float>(2, 0.0f), gt), std::invalid_argument);
  // A target that enters late: its first frame in view is reported.
  const std::vector<cv::Rect2f> late = {cv::Rect2f(), cv::Rect2f(), cv::Rect2f(0, 0, 10, 10)};
  const ev::SenseAvoidScores on_late = ev::senseAvoidScores(late, std::vector<float>(3, 1.0f), late);
  EXPECT_EQ(on_late.first_present_frame, 2);
  // Its first box is on it: right, counted from the frame it came into view.
  EXPECT_EQ(on_late.first_box_frame, 2);
  EXPECT_DOUBLE_EQ(on_late.first_box_error, 0.0);
  EXPECT_TRUE(ev::firstBoxCorrect(on_late, 1));
  EXPECT_FALSE(ev::firstBoxCorrect(on_late, 30, -0.5));
  // A box before the target is in view: a wrong first box (error +inf), though later ones are right.
  const std::vector<cv::Rect2f> early = {cv::Rect2f(0, 0, 10, 10), cv::Rect2f(0, 0, 10, 10), cv::Rect2f(0, 0, 10, 10)};
  const ev::SenseAvoidScores too_early = ev::senseAvoidScores(early, std::vector<float>(3, 1.0f), late);
  EXPECT_EQ(too_early.first_box_frame, 0);
  EXPECT_TRUE(std::isinf(too_early.first_box_error));
  EXPECT_EQ(too_early.first_correct_frame, 2);
  EXPECT_FALSE(ev::firstBoxCorrect(too_early, 30));
  // Never a box: no first box, never correct.
  const ev::SenseAvoidScores no_box = ev::senseAvoidScores(std::vector<cv::Rect2f>(3), std::vector<float>(3, 0.0f), gt);
  EXPECT_EQ(no_box.first_box_frame, -1);
  EXPECT_DOUBLE_EQ(no_box.first_box_error, -1.0);
  EXPECT_FALSE(ev::firstBoxCorrect(no_box, 30));
  // Within 30 frames means frames 0-29 after the target's first frame in view: a right first
  // box 29 frames after it counts, one 30 frames after it does not.
  for (const int offset : {29, 30}) {
    std::vector<cv::Rect2f> boxes(40), truth(40, cv::Rect2f(0, 0, 10, 10));
    boxes[static_cast<std::size_t>(offset)] = truth[0];
    const ev::SenseAvoidScores late_box = ev::senseAvoidScores(boxes, std::vector<float>(40, 1.0f), truth);
    EXPECT_EQ(late_box.first_box_frame, offset);
    EXPECT_EQ(ev::firstBoxCorrect(late_box, 30), offset < 30) << offset;
  }
  const ev::SenseAvoidScores empty = ev::senseAvoidScores({}, {}, {});
  EXPECT_EQ(empty.frames, 0);
  EXPECT_DOUBLE_EQ(empty.false_confident_rate, 0.0);
}
