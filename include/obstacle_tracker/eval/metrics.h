// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Tracking metrics with the conventions of the public benchmarks, so that our numbers can be put
// beside published ones:
// - OTB (Wu, Lim, Yang, "Object Tracking Benchmark", TPAMI 2015): precision curve = fraction of
//   frames whose centre error is <= t pixels, t = 0..50 (precision@20 is the usual summary);
//   success curve = fraction of frames whose IoU is > o, o = 0, 0.05, ..., 1 (21 thresholds);
//   AUC = mean of the success curve. Frames whose ground truth is absent (0,0,0,0, NaN or a
//   non-positive size) are left out. A frame where the tracker reports no box counts as a failure
//   (centre error +inf, IoU 0).
// - VOT long-term (Lukezic et al., "Now you see me: evaluating performance in long-term visual
//   tracking", 2018): for a confidence threshold tau, tracking precision Pr(tau) = mean IoU over the
//   frames where the tracker reports a box with confidence >= tau (IoU 0 when the target is
//   absent there); tracking recall Re(tau) = mean IoU over the frames where the target is present
//   (IoU 0 when the tracker reports nothing >= tau); F(tau) = 2 Pr Re / (Pr + Re); the score is
//   the F at the tau that maximises it (with that tau's Pr and Re).
// - Sense and avoid: the Anti-UAV state accuracy (Jiang et al., "Anti-UAV: a large multi-modal
//   benchmark for UAV tracking", 2021: per frame the IoU where the target is present, 0 there for
//   no box; where it is absent 1 for no box and 0 for a box; mean over frames), the first frame
//   whose box is within 20 px of the target (a correct start), the first box reported at all and
//   its centre error (a wrong first box is a wrong start), and the false confident rate:
//   frames whose box has confidence >= 0.5 and IoU 0 with the target (or the target is absent),
//   over all frames -- the output a planner acting on confidence >= 0.5 must never get.
// IoU is core::boxIou<double> (box_geometry.h), the same computation as the tracking loop's in
// double precision. No ROS, no I/O: pure functions of boxes.
#pragma once

#include <vector>

#include <opencv2/core/types.hpp>

#include "obstacle_tracker/core/box_geometry.h"

namespace obstacle_tracker {
namespace eval {

// True when a box stands for "no target" (core::boxIsAbsent: a NaN or an infinity, or width or
// height <= 0).
inline bool isAbsent(const cv::Rect2f& box) { return core::boxIsAbsent(box); }

// Distance between box centres, pixels. +inf when either box is absent.
double centreError(const cv::Rect2f& a, const cv::Rect2f& b);

// Thresholds of the OTB curves.
constexpr int kPrecisionThresholdCount = 51;  // 0, 1, ..., 50 px
constexpr int kSuccessThresholdCount = 21;    // 0, 0.05, ..., 1
constexpr double kPrecisionSummaryPx = 20.0;
double precisionThreshold(int i);  // i px
double successThreshold(int i);    // i * 0.05

// Per-frame errors of one run against its ground truth, the input to every score below; runs of
// several segments (TRE) are pooled by appending their frames, as the OTB toolkit does.
struct FrameErrors {
  std::vector<double> centre_error;  // +inf when the tracker reported nothing
  std::vector<double> overlap;       // IoU, 0 when the tracker reported nothing
  int absent_gt_frames = 0;          // frames left out because the ground truth is absent
  void append(const FrameErrors& other);
};

// predicted[i] is compared with gt[i]; sizes must match (std::invalid_argument otherwise).
FrameErrors frameErrors(const std::vector<cv::Rect2f>& predicted, const std::vector<cv::Rect2f>& gt);

struct OtbScores {
  int frames = 0;                  // frames with ground truth present (the denominator)
  std::vector<double> precision;   // kPrecisionThresholdCount values
  std::vector<double> success;     // kSuccessThresholdCount values
  double precision20 = 0.0;        // precision at kPrecisionSummaryPx
  double auc = 0.0;                // mean of the success curve
  double mean_centre_error = 0.0;  // px, over frames where the tracker reported a box (NaN if none)
  double lost_fraction = 0.0;      // frames (GT present) where the tracker reported nothing
};

// Scores of the frames in `errors`. With no frame at all every curve is zero and frames is 0.
OtbScores otbScores(const FrameErrors& errors);
inline OtbScores otbScores(const std::vector<cv::Rect2f>& predicted, const std::vector<cv::Rect2f>& gt) {
  return otbScores(frameErrors(predicted, gt));
}

// Element-wise mean of several runs' curves and summaries (e.g. the mean over sequences).
OtbScores meanOtbScores(const std::vector<OtbScores>& runs);

struct LongTermScores {
  int frames = 0;            // all frames
  int present_frames = 0;    // frames where the target is present
  double precision = 0.0;    // Pr at the best threshold
  double recall = 0.0;       // Re at the best threshold
  double fscore = 0.0;       // max over thresholds of F
  double threshold = 0.0;    // the maximising tau
  std::vector<double> thresholds, precision_curve, recall_curve, fscore_curve;
};

// predicted[i] with confidence[i] against gt[i]. An absent predicted box (isAbsent) is "no
// report" whatever its confidence. Thresholds: the distinct confidences of the reported boxes
// (at most max_thresholds of them, evenly spaced in rank), ascending. Sizes must match.
LongTermScores longTermScores(const std::vector<cv::Rect2f>& predicted,
                              const std::vector<float>& confidence,
                              const std::vector<cv::Rect2f>& gt, int max_thresholds = 100);

struct SenseAvoidScores {
  int frames = 0;
  double state_accuracy = 0.0;
  int first_present_frame = -1;    // the target's first frame in view; -1: never
  int first_correct_frame = -1;    // -1: never within correct_px
  // The first box reported at all, right or wrong ("the first box within 20 px of the target": a wrong
  // first box is a wrong start even when a later one is right): its frame (-1: never a box) and
  // its centre error in px (+inf when the target is not in view there; -1: never a box).
  int first_box_frame = -1;
  double first_box_error = -1.0;
  int false_confident_frames = 0;
  double false_confident_rate = 0.0;
};

// Whether the first box came within `within_frames` of the target's first frame in view and
// within `correct_px` of it (the start a sense-and-avoid user sees first).
bool firstBoxCorrect(const SenseAvoidScores& s, int within_frames, double correct_px = kPrecisionSummaryPx);

// predicted[i] with confidence[i] against gt[i]; an absent predicted box (isAbsent) is "no box".
// Sizes must match (std::invalid_argument otherwise).
SenseAvoidScores senseAvoidScores(const std::vector<cv::Rect2f>& predicted, const std::vector<float>& confidence,
                                  const std::vector<cv::Rect2f>& gt, double confident = 0.5,
                                  double correct_px = kPrecisionSummaryPx);

}  // namespace eval
}  // namespace obstacle_tracker
