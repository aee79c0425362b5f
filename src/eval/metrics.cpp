// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// OTB and VOT long-term scores; definitions and references in metrics.h.
#include "obstacle_tracker/eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "obstacle_tracker/core/box_geometry.h"

namespace obstacle_tracker {
namespace eval {

double centreError(const cv::Rect2f& a, const cv::Rect2f& b) {
  if (isAbsent(a) || isAbsent(b)) return std::numeric_limits<double>::infinity();
  const cv::Point2d ca = core::boxCentre(cv::Rect2d(a)), cb = core::boxCentre(cv::Rect2d(b));
  const double dx = ca.x - cb.x;
  const double dy = ca.y - cb.y;
  return std::sqrt(dx * dx + dy * dy);
}

double precisionThreshold(int i) { return static_cast<double>(i); }
double successThreshold(int i) { return 0.05 * i; }

void FrameErrors::append(const FrameErrors& other) {
  centre_error.insert(centre_error.end(), other.centre_error.begin(), other.centre_error.end());
  overlap.insert(overlap.end(), other.overlap.begin(), other.overlap.end());
  absent_gt_frames += other.absent_gt_frames;
}

FrameErrors frameErrors(const std::vector<cv::Rect2f>& predicted, const std::vector<cv::Rect2f>& gt) {
  if (predicted.size() != gt.size()) {
    throw std::invalid_argument("frameErrors: " + std::to_string(predicted.size()) +
                                " predicted boxes for " + std::to_string(gt.size()) +
                                " ground-truth boxes");
  }
  FrameErrors e;
  e.centre_error.reserve(gt.size());
  e.overlap.reserve(gt.size());
  for (size_t i = 0; i < gt.size(); ++i) {
    if (isAbsent(gt[i])) {
      ++e.absent_gt_frames;
      continue;
    }
    e.centre_error.push_back(centreError(predicted[i], gt[i]));
    e.overlap.push_back(core::boxIou<double>(predicted[i], gt[i]));
  }
  return e;
}

OtbScores otbScores(const FrameErrors& errors) {
  if (errors.centre_error.size() != errors.overlap.size()) {
    throw std::invalid_argument("otbScores: centre_error and overlap differ in length");
  }
  OtbScores s;
  s.frames = static_cast<int>(errors.overlap.size());
  s.precision.assign(kPrecisionThresholdCount, 0.0);
  s.success.assign(kSuccessThresholdCount, 0.0);
  double err_sum = 0.0;
  int err_n = 0, lost = 0;
  for (int f = 0; f < s.frames; ++f) {
    const double ce = errors.centre_error[f];
    const double ov = errors.overlap[f];
    if (std::isfinite(ce)) {
      err_sum += ce;
      ++err_n;
    } else {
      ++lost;
    }
    // OTB perfPlot.m: errCenter <= t for precision, errCoverage > o for success.
    for (int i = 0; i < kPrecisionThresholdCount; ++i)
      if (ce <= precisionThreshold(i)) s.precision[i] += 1.0;
    for (int i = 0; i < kSuccessThresholdCount; ++i)
      if (ov > successThreshold(i)) s.success[i] += 1.0;
  }
  if (s.frames > 0) {
    for (auto& v : s.precision) v /= s.frames;
    for (auto& v : s.success) v /= s.frames;
    s.lost_fraction = static_cast<double>(lost) / s.frames;
  }
  s.precision20 = s.precision[static_cast<int>(kPrecisionSummaryPx)];
  double sum = 0.0;
  for (double v : s.success) sum += v;
  s.auc = sum / kSuccessThresholdCount;
  s.mean_centre_error = err_n > 0 ? err_sum / err_n : std::numeric_limits<double>::quiet_NaN();
  return s;
}

OtbScores meanOtbScores(const std::vector<OtbScores>& runs) {
  OtbScores m;
  m.precision.assign(kPrecisionThresholdCount, 0.0);
  m.success.assign(kSuccessThresholdCount, 0.0);
  if (runs.empty()) return m;
  double err_sum = 0.0;
  int err_n = 0;
  for (const auto& r : runs) {
    if (r.precision.size() != m.precision.size() || r.success.size() != m.success.size()) {
      throw std::invalid_argument("meanOtbScores: a run has curves of the wrong length");
    }
    m.frames += r.frames;
    for (int i = 0; i < kPrecisionThresholdCount; ++i) m.precision[i] += r.precision[i];
    for (int i = 0; i < kSuccessThresholdCount; ++i) m.success[i] += r.success[i];
    m.precision20 += r.precision20;
    m.auc += r.auc;
    m.lost_fraction += r.lost_fraction;
    if (std::isfinite(r.mean_centre_error)) {
      err_sum += r.mean_centre_error;
      ++err_n;
    }
  }
  const double n = static_cast<double>(runs.size());
  for (auto& v : m.precision) v /= n;
  for (auto& v : m.success) v /= n;
  m.precision20 /= n;
  m.auc /= n;
  m.lost_fraction /= n;
  m.mean_centre_error = err_n > 0 ? err_sum / err_n : std::numeric_limits<double>::quiet_NaN();
  return m;
}

LongTermScores longTermScores(const std::vector<cv::Rect2f>& predicted,
                              const std::vector<float>& confidence,
                              const std::vector<cv::Rect2f>& gt, int max_thresholds) {
  if (predicted.size() != gt.size() || confidence.size() != gt.size()) {
    throw std::invalid_argument("longTermScores: " + std::to_string(predicted.size()) + " boxes, " +
                                std::to_string(confidence.size()) + " confidences, " +
                                std::to_string(gt.size()) + " ground-truth boxes");
  }
  if (max_thresholds < 1) throw std::invalid_argument("longTermScores: max_thresholds < 1");
  LongTermScores s;
  const size_t n = gt.size();
  s.frames = static_cast<int>(n);
  std::vector<double> ov(n, 0.0);
  std::vector<float> reported;
  for (size_t i = 0; i < n; ++i) {
    if (!isAbsent(gt[i])) ++s.present_frames;
    ov[i] = core::boxIou<double>(predicted[i], gt[i]);
    if (!isAbsent(predicted[i])) {
      if (std::isnan(confidence[i])) {
        throw std::invalid_argument("longTermScores: NaN confidence at frame " + std::to_string(i));
      }
      reported.push_back(confidence[i]);
    }
  }
  std::sort(reported.begin(), reported.end());
  reported.erase(std::unique(reported.begin(), reported.end()), reported.end());
  if (reported.empty()) return s;
  // Evenly spaced in rank, always keeping the lowest and the highest confidence.
  const size_t k = std::min<size_t>(reported.size(), static_cast<size_t>(max_thresholds));
  for (size_t j = 0; j < k; ++j) {
    const size_t idx = k == 1 ? reported.size() - 1 : j * (reported.size() - 1) / (k - 1);
    s.thresholds.push_back(reported[idx]);
  }
  s.thresholds.erase(std::unique(s.thresholds.begin(), s.thresholds.end()), s.thresholds.end());
  bool have_best = false;
  for (double tau : s.thresholds) {
    double sum_reported = 0.0, sum_present = 0.0;
    int n_reported = 0;
    for (size_t i = 0; i < n; ++i) {
      const bool rep = !isAbsent(predicted[i]) && confidence[i] >= tau;
      const double o = rep ? ov[i] : 0.0;
      if (rep) {
        sum_reported += o;
        ++n_reported;
      }
      if (!isAbsent(gt[i])) sum_present += o;
    }
    const double pr = n_reported > 0 ? sum_reported / n_reported : 0.0;
    const double re = s.present_frames > 0 ? sum_present / s.present_frames : 0.0;
    const double f = pr + re > 0.0 ? 2.0 * pr * re / (pr + re) : 0.0;
    s.precision_curve.push_back(pr);
    s.recall_curve.push_back(re);
    s.fscore_curve.push_back(f);
    if (!have_best || f > s.fscore) {
      have_best = true;
      s.fscore = f;
      s.precision = pr;
      s.recall = re;
      s.threshold = tau;
    }
  }
  return s;
}

SenseAvoidScores senseAvoidScores(const std::vector<cv::Rect2f>& predicted, const std::vector<float>& confidence,
                                  const std::vector<cv::Rect2f>& gt, double confident, double correct_px) {
  if (predicted.size() != gt.size() || confidence.size() != gt.size()) {
    throw std::invalid_argument("senseAvoidScores: predicted, confidence and gt differ in length");
  }
  SenseAvoidScores s;
  s.frames = static_cast<int>(gt.size());
  double state_sum = 0.0;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    const bool reported = !isAbsent(predicted[i]);
    const bool present = !isAbsent(gt[i]);
    const double overlap = core::boxIou<double>(predicted[i], gt[i]);  // 0 when either is absent
    state_sum += present ? overlap : (reported ? 0.0 : 1.0);
    if (s.first_present_frame < 0 && present) s.first_present_frame = static_cast<int>(i);
    if (s.first_correct_frame < 0 && present && centreError(predicted[i], gt[i]) <= correct_px) {
      s.first_correct_frame = static_cast<int>(i);
    }
    if (s.first_box_frame < 0 && reported) {
      s.first_box_frame = static_cast<int>(i);
      s.first_box_error = present ? centreError(predicted[i], gt[i]) : std::numeric_limits<double>::infinity();
    }
    if (reported && confidence[i] >= confident && overlap <= 0.0) ++s.false_confident_frames;
  }
  if (s.frames > 0) {
    s.state_accuracy = state_sum / s.frames;
    s.false_confident_rate = static_cast<double>(s.false_confident_frames) / s.frames;
  }
  return s;
}

bool firstBoxCorrect(const SenseAvoidScores& s, int within_frames, double correct_px) {
  return s.first_box_frame >= 0 && s.first_present_frame >= 0 &&
         s.first_box_frame - s.first_present_frame < within_frames && s.first_box_error >= 0.0 &&
         s.first_box_error <= correct_px;
}

}  // namespace eval
}  // namespace obstacle_tracker
