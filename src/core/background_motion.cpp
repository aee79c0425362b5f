// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Background motion from sparse feature tracks (background_motion.h).
#include "obstacle_tracker/core/background_motion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace obstacle_tracker {
namespace core {

namespace {

constexpr int kMinWorkingSide = 32;    // px; smaller frames carry no usable background
constexpr int kGridColumns = 6;        // corners are taken per cell of this grid
constexpr int kGridRows = 4;
constexpr int kRansacIterations = 500;  // enough for 4 DOF at 50 % outliers many times over
constexpr double kRansacConfidence = 0.995;
constexpr int kRefineIterations = 10;   // Levenberg-Marquardt steps on the inliers
constexpr int kRefitPasses = 2;         // tight refits after RANSAC
constexpr int kFlowIterations = 20;
constexpr double kFlowEpsilon = 0.02;   // working px
constexpr double kPhaseSupport = 0.2;   // net share of pixels a phase-correlation shift must explain better

}  // namespace

cv::Point2d BackgroundMotionEstimate::displacementAt(const cv::Point2d& p) const {
  const cv::Matx23d& a = previous_to_current;
  return {a(0, 0) * p.x + a(0, 1) * p.y + a(0, 2) - p.x, a(1, 0) * p.x + a(1, 1) * p.y + a(1, 2) - p.y};
}

BackgroundMotion::BackgroundMotion(const BackgroundMotionSettings& settings) : settings_(settings) {
  if (settings_.working_width < kMinWorkingSide || settings_.max_features < settings_.min_tracks ||
      settings_.min_tracks < 3 || settings_.flow_window < 5 || settings_.flow_levels < 0 ||
      !(settings_.max_forward_backward_error > 0.0) || !(settings_.ransac_threshold > 0.0) ||
      !(settings_.refine_threshold > 0.0)) {
    throw std::invalid_argument("BackgroundMotionSettings: out of range");
  }
}

void BackgroundMotion::reset() {
  previous_.release();
  current_.release();
  kept_.clear();
  estimate_ = BackgroundMotionEstimate();
}

cv::Size BackgroundMotion::workingSize(cv::Size full) const {
  if (full.width <= settings_.working_width) return full;
  const double s = static_cast<double>(settings_.working_width) / full.width;
  return {settings_.working_width, std::max(1, static_cast<int>(std::lround(full.height * s)))};
}

namespace {

// x_working = S x_full + c, S = diag(scale), c = (scale - 1) / 2 (see workingScale()). A motion
// x' = L x + t in one frame's coordinates is, in the other's, x' = S L S^-1 x + S t + c - S L S^-1 c
// (to working) or S^-1 L S x + S^-1 (L c + t - c) (to full).
cv::Matx23d changeCoordinates(const cv::Matx23d& a, cv::Point2d scale, bool to_working) {
  const double sx = to_working ? scale.x : 1.0 / scale.x, sy = to_working ? scale.y : 1.0 / scale.y;
  // The offset of the working frame's pixel centres, in the target coordinates' terms.
  const double cx = to_working ? 0.5 * (scale.x - 1.0) : -0.5 * (scale.x - 1.0) / scale.x;
  const double cy = to_working ? 0.5 * (scale.y - 1.0) : -0.5 * (scale.y - 1.0) / scale.y;
  // y = T x, with T = diag(sx, sy) x + (cx, cy); returns T A T^-1.
  const cv::Matx22d l(a(0, 0), a(0, 1), a(1, 0), a(1, 1));
  const cv::Matx22d s(sx, 0.0, 0.0, sy), s_inv(1.0 / sx, 0.0, 0.0, 1.0 / sy);
  const cv::Matx22d lt = s * l * s_inv;
  const cv::Vec2d c(cx, cy), t(a(0, 2), a(1, 2));
  const cv::Vec2d tt = s * t + c - lt * c;
  return {lt(0, 0), lt(0, 1), tt[0], lt(1, 0), lt(1, 1), tt[1]};
}

}  // namespace

cv::Matx23d BackgroundMotion::workingTransform() const {
  return changeCoordinates(estimate_.previous_to_current, scale_, true);
}

const BackgroundMotionEstimate& BackgroundMotion::update(const cv::Mat& grey, const cv::Mat& excluded) {
  if (grey.empty() || grey.type() != CV_8UC1) throw std::invalid_argument("BackgroundMotion::update: CV_8UC1 frame");
  const cv::Size working = workingSize(grey.size());
  if (!excluded.empty() && (excluded.type() != CV_8UC1 || excluded.size() != working)) {
    throw std::invalid_argument("BackgroundMotion::update: excluded mask must be CV_8UC1 of the working size");
  }
  std::swap(previous_, current_);
  if (working == grey.size()) {
    grey.copyTo(current_);
  } else {
    cv::resize(grey, current_, working, 0, 0, cv::INTER_AREA);
  }
  scale_ = cv::Point2d(static_cast<double>(working.width) / grey.cols, static_cast<double>(working.height) / grey.rows);
  estimate_ = BackgroundMotionEstimate();
  if (previous_.size() != current_.size() || working.width < kMinWorkingSide || working.height < kMinWorkingSide) {
    kept_.clear();
    return estimate_;
  }
  if (!fromFeatures(excluded) && !fromPhaseCorrelation()) {
    estimate_.quality = 0.0;  // tracks and inliers stay: they say why
    estimate_.inliers = 0;
  }
  return estimate_;
}

bool BackgroundMotion::fromFeatures(const cv::Mat& excluded) {
  if (excluded.empty()) {
    corner_mask_.release();
  } else {
    cv::compare(excluded, 0, corner_mask_, cv::CMP_EQ);  // goodFeaturesToTrack: non-zero = allowed
  }
  // Corners per cell of a kGridColumns x kGridRows grid, each cell's strength relative to its
  // own best: one strongly textured region (on-screen text, a building) would otherwise take all
  // the corners and decide the motion alone, however small it is. The background points of the
  // last estimate are followed on (as in Shi & Tomasi's tracker); a cell is searched for new
  // corners only when it holds fewer than half its share (finding corners costs as much as
  // following them).
  const int per_cell = std::max(1, settings_.max_features / (kGridColumns * kGridRows));
  const auto cellOf = [&](const cv::Point2f& p) {
    const int gx = std::min(kGridColumns - 1, std::max(0, static_cast<int>(p.x * kGridColumns / previous_.cols)));
    const int gy = std::min(kGridRows - 1, std::max(0, static_cast<int>(p.y * kGridRows / previous_.rows)));
    return gy * kGridColumns + gx;
  };
  corners_.clear();
  cell_count_.assign(kGridColumns * kGridRows, 0);
  const cv::Rect2f inside(0.0f, 0.0f, static_cast<float>(previous_.cols - 1), static_cast<float>(previous_.rows - 1));
  for (const cv::Point2f& p : kept_) {
    if (!inside.contains(p)) continue;
    if (!corner_mask_.empty() && corner_mask_.at<uchar>(cvRound(p.y), cvRound(p.x)) == 0) continue;
    int& n = cell_count_[static_cast<size_t>(cellOf(p))];
    if (n >= per_cell) continue;
    ++n;
    corners_.push_back(p);
  }
  for (int gy = 0; gy < kGridRows; ++gy) {
    for (int gx = 0; gx < kGridColumns; ++gx) {
      const int have = cell_count_[static_cast<size_t>(gy * kGridColumns + gx)];
      if (2 * have >= per_cell) continue;
      const cv::Rect cell(cv::Point(gx * previous_.cols / kGridColumns, gy * previous_.rows / kGridRows),
                          cv::Point((gx + 1) * previous_.cols / kGridColumns, (gy + 1) * previous_.rows / kGridRows));
      cv::goodFeaturesToTrack(previous_(cell), cell_corners_, per_cell - have, settings_.feature_quality,
                              settings_.feature_spacing, corner_mask_.empty() ? cv::noArray() : corner_mask_(cell));
      for (const cv::Point2f& c : cell_corners_) corners_.push_back(c + cv::Point2f(cell.tl()));
    }
  }
  kept_.clear();
  if (static_cast<int>(corners_.size()) < settings_.min_tracks) return false;
  const cv::Size window(settings_.flow_window, settings_.flow_window);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, kFlowIterations, kFlowEpsilon);
  cv::calcOpticalFlowPyrLK(previous_, current_, corners_, forward_, forward_status_, flow_error_, window,
                           settings_.flow_levels, stop);
  cv::calcOpticalFlowPyrLK(current_, previous_, forward_, backward_, backward_status_, flow_error_, window,
                           settings_.flow_levels, stop);
  from_.clear();
  to_.clear();
  const double max_fb2 = settings_.max_forward_backward_error * settings_.max_forward_backward_error;
  for (size_t i = 0; i < corners_.size(); ++i) {
    if (!forward_status_[i] || !backward_status_[i]) continue;
    const cv::Point2f round_trip = backward_[i] - corners_[i];
    if (round_trip.dot(round_trip) > max_fb2) continue;
    from_.push_back(corners_[i]);
    to_.push_back(forward_[i]);
  }
  estimate_.tracks = static_cast<int>(from_.size());
  if (estimate_.tracks < settings_.min_tracks) return false;
  const cv::Mat fitted = cv::estimateAffinePartial2D(from_, to_, inlier_flags_, cv::RANSAC, settings_.ransac_threshold,
                                                     kRansacIterations, kRansacConfidence, kRefineIterations);
  if (fitted.empty()) return false;
  estimate_.inliers = cv::countNonZero(inlier_flags_);
  estimate_.quality = static_cast<double>(estimate_.inliers) / estimate_.tracks;
  if (estimate_.inliers < settings_.min_tracks || estimate_.quality < settings_.min_inlier_share) return false;
  for (size_t i = 0; i < to_.size(); ++i) {
    if (inlier_flags_[i]) kept_.push_back(to_[i]);
  }
  cv::Matx23d a;
  fitted.convertTo(cv::Mat(2, 3, CV_64F, a.val), CV_64F);
  estimate_.previous_to_current = changeCoordinates(refitOnTightInliers(a), scale_, false);
  estimate_.source = BackgroundMotionEstimate::Source::kFeatures;
  return true;
}

cv::Matx23d BackgroundMotion::refitOnTightInliers(const cv::Matx23d& fitted) {
  cv::Matx23d a = fitted;
  const double tight2 = settings_.refine_threshold * settings_.refine_threshold;
  for (int pass = 0; pass < kRefitPasses; ++pass) {
    tight_from_.clear();
    tight_to_.clear();
    for (size_t i = 0; i < from_.size(); ++i) {
      const cv::Point2f& p = from_[i];
      const double dx = a(0, 0) * p.x + a(0, 1) * p.y + a(0, 2) - to_[i].x;
      const double dy = a(1, 0) * p.x + a(1, 1) * p.y + a(1, 2) - to_[i].y;
      if (dx * dx + dy * dy > tight2) continue;
      tight_from_.push_back(p);
      tight_to_.push_back(to_[i]);
    }
    if (static_cast<int>(tight_from_.size()) < settings_.min_tracks) break;
    // Every selected track is an inlier at this threshold, so this is the least-squares fit
    // (Levenberg-Marquardt) over them.
    const cv::Mat refit = cv::estimateAffinePartial2D(tight_from_, tight_to_, cv::noArray(), cv::RANSAC,
                                                      4.0 * settings_.refine_threshold, kRansacIterations,
                                                      kRansacConfidence, kRefineIterations);
    if (refit.empty()) break;
    refit.convertTo(cv::Mat(2, 3, CV_64F, a.val), CV_64F);
  }
  return a;
}

bool BackgroundMotion::fromPhaseCorrelation() {
  // Zero mean: the window would otherwise print the same bright bump on both frames, and its
  // correlation peak at zero shift answers for a sky that says nothing.
  previous_.convertTo(previous_float_, CV_32F, 1.0, -cv::mean(previous_)[0]);
  current_.convertTo(current_float_, CV_32F, 1.0, -cv::mean(current_)[0]);
  if (hann_.size() != current_.size()) cv::createHanningWindow(hann_, current_.size(), CV_32F);
  double response = 0.0;
  const cv::Point2d shift = cv::phaseCorrelate(previous_float_, current_float_, hann_, &response);
  const bool plausible = std::abs(shift.x) < current_.cols / 3.0 && std::abs(shift.y) < current_.rows / 3.0;
  if (!(response >= settings_.min_phase_response) || !plausible) return false;
  // Over a plain sky the one textured thing in view, often the target, decides the correlation
  // peak: its motion would be taken for the background's. The shift is kept only when the
  // background agrees: among the pixels both frames see, those it explains better than no motion
  // does (by a grey level or more) must outnumber those it explains worse by kPhaseSupport of all.
  const int mx = static_cast<int>(std::ceil(std::abs(shift.x))) + 1, my = static_cast<int>(std::ceil(std::abs(shift.y))) + 1;
  const cv::Rect inner(mx, my, current_.cols - 2 * mx, current_.rows - 2 * my);
  if (inner.width <= 0 || inner.height <= 0) return false;
  cv::warpAffine(previous_, shifted_, cv::Matx23d(1, 0, shift.x, 0, 1, shift.y), current_.size(), cv::INTER_LINEAR,
                 cv::BORDER_REPLICATE);
  cv::absdiff(current_(inner), shifted_(inner), moved_error_);
  cv::absdiff(current_(inner), previous_(inner), still_error_);
  cv::subtract(still_error_, moved_error_, gain_, cv::noArray(), CV_16S);
  const int better = cv::countNonZero(gain_ >= 1), worse = cv::countNonZero(gain_ <= -1);
  if (better - worse < kPhaseSupport * inner.area()) return false;
  estimate_.previous_to_current = changeCoordinates(cv::Matx23d(1, 0, shift.x, 0, 1, shift.y), scale_, false);
  estimate_.source = BackgroundMotionEstimate::Source::kPhaseCorrelation;
  estimate_.quality = response;
  return true;
}

}  // namespace core
}  // namespace obstacle_tracker
