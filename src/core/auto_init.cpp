// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Multi-frame auto-initialisation (auto_init.h, AutoInitializer): the frame's steps in order,
// background motion and still pixels, and the confirmation of candidate tracks with their refined
// boxes. Design and cues: auto_init_impl.h.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "auto_init_impl.h"
#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/frame_check.h"

namespace obstacle_tracker {
namespace core {

using namespace auto_init_detail;  // NOLINT(build/namespaces): the auto-initialiser's own constants

void AutoInitializer::Impl::reset() {
  motion.reset();
  overlay.reset();
  prev_grey.release();
  contrast_map.release();  // of the old size: changedAgainstBackground must not read it
  background = cv::Point2d(0.0, 0.0);
  background_base = cv::Point2d(0.0, 0.0);
  first_to_image = image_to_first = cv::Matx33d::eye();
  frame_index = 0;
  tracks.clear();
  confirmed.clear();
  raw.clear();
  persistent = -1;
}

// Step 0 (auto_init_impl.h): the working size for frames of `frame_size`.
void AutoInitializer::Impl::setWorkingSize(cv::Size frame_size) {
  work_size = frame_size;
  if (frame_size.width > params.auto_init_max_width) {
    const double s = static_cast<double>(params.auto_init_max_width) / frame_size.width;
    work_size = cv::Size(params.auto_init_max_width,
                         std::max(1, static_cast<int>(std::lround(frame_size.height * s))));
  }
  work_scale = cv::Point2d(static_cast<double>(work_size.width) / frame_size.width,
                           static_cast<double>(work_size.height) / frame_size.height);
}

// The frame as grey at the working size: one area resize (before the colour conversion, which
// then runs on the small image) when the frame is wider than auto_init_max_width.
cv::Mat AutoInitializer::Impl::workingGrey(const cv::Mat& frame) {
  cv::Mat small = frame;
  if (work_size != frame.size()) {
    small = work_arena.get(work_size.height, work_size.width, frame.type());
    cv::resize(frame, small, work_size, 0, 0, cv::INTER_AREA);
  }
  if (small.channels() == 1) return small;
  cv::Mat grey = grey_arena.get(small.rows, small.cols, CV_8U);
  cv::cvtColor(small, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

// Boxes between working and frame pixels (edges scale; pixel centres follow cv::resize's
// convention, so a box's edges are where its pixels' outer borders are in both).
cv::Rect2f AutoInitializer::Impl::toFrame(const cv::Rect2f& b) const {
  const float sx = static_cast<float>(work_scale.x), sy = static_cast<float>(work_scale.y);
  return {b.x / sx, b.y / sy, b.width / sx, b.height / sy};
}

SalientRegion AutoInitializer::Impl::toFrame(SalientRegion r) const {
  r.box = toFrame(r.box);
  r.area = static_cast<float>(r.area / (work_scale.x * work_scale.y));
  return r;
}

cv::Rect2f AutoInitializer::Impl::toWorking(const cv::Rect2f& b) const {
  const float sx = static_cast<float>(work_scale.x), sy = static_cast<float>(work_scale.y);
  return {b.x * sx, b.y * sy, b.width * sx, b.height * sy};
}

void AutoInitializer::Impl::globalMotion(const cv::Mat& grey) {
  // The background's motion since the previous frame (background_motion.h), with no corner on
  // the overlay; the overlay mask learns from the same pair of frames. `background` follows the
  // frame centre's displacement, summed frame to frame.
  const BackgroundMotionEstimate& e = motion.update(grey, overlay.mask());
  if (e.known()) {
    overlay.update(motion.previousWorkingFrame(), motion.currentWorkingFrame(), motion.workingTransform());
    background += e.displacementAt(cv::Point2d(0.5 * (grey.cols - 1), 0.5 * (grey.rows - 1)));
    const cv::Matx23d& a = e.previous_to_current;
    first_to_image = cv::Matx33d(a(0, 0), a(0, 1), a(0, 2), a(1, 0), a(1, 1), a(1, 2), 0, 0, 1) * first_to_image;
    image_to_first = first_to_image.inv();
  }
}

// Share of a region's pixels (working-frame indices y * cols + x) on the overlay mask.
double AutoInitializer::Impl::overlayShare(const std::vector<int>& pixels, int cols) const {
  const cv::Mat& mask = overlay.mask();
  if (mask.empty() || pixels.empty()) return 0.0;
  const cv::Point2d s = motion.workingScale();
  int on = 0;
  for (const int q : pixels) {
    const int x = std::min(mask.cols - 1, static_cast<int>(s.x * (q % cols)));
    const int y = std::min(mask.rows - 1, static_cast<int>(s.y * (q / cols)));
    on += mask.ptr<uchar>(y)[x] != 0;
  }
  return static_cast<double>(on) / pixels.size();
}

// Per-pixel count of consecutive frames without change (saturating at 255).
void AutoInitializer::Impl::updateStill(const cv::Mat& grey) {
  if (!params.auto_init_reject_static) return;
  if (prev_grey.size() != grey.size()) {
    grey.copyTo(prev_grey);
    still.create(grey.size(), CV_8U);
    still.setTo(0);
    return;
  }
  // still = unchanged ? min(255, still + 1) : 0, with OpenCV's vectorised element-wise ops.
  cv::absdiff(grey, prev_grey, diff);
  cv::compare(diff, kStillLevel, diff, cv::CMP_LE);  // 255 where unchanged
  cv::add(still, cv::Scalar(1), still);              // saturating
  cv::bitwise_and(still, diff, still);
  grey.copyTo(prev_grey);
}

// Pixels of r (inside the frame) unchanged for kStillFrames frames.
int AutoInitializer::Impl::stillPixels(const cv::Rect& r) const {
  int n = 0;
  for (int y = r.y; y < r.y + r.height; ++y) {
    const uchar* sc = still.ptr<uchar>(y);
    for (int x = r.x; x < r.x + r.width; ++x) n += sc[x] >= kStillFrames;
  }
  return n;
}

SalientRegion AutoInitializer::Impl::toRegion(const cv::Rect& box, int area, double mean, double score, bool border) {
  SalientRegion r;
  r.box = cv::Rect2f(box);
  r.area = static_cast<float>(area);
  r.mean_saliency = static_cast<float>(mean / 255.0);
  r.score = static_cast<float>(score);
  r.touches_border = border;
  return r;
}

// The candidate's region is the core of the target (>= 0.3 x the peak of P); the saliency
// detector in a window around it, at native resolution, gives the object's own extent. Kept
// when the best region there contains the candidate's centre.
void AutoInitializer::Impl::refine(const cv::Mat& frame, SalientRegion& region) {
  const auto& found = refiner.detectInWindow(frame, region.box);
  const cv::Point2f c = boxCentre(region.box);
  const float max_area = kRefineMaxGrowth * std::max(16.0f, region.box.area());
  for (const SalientRegion& r : found) {
    if (!r.box.contains(c) || r.box.area() > max_area) continue;
    region.box = r.box;
    region.area = r.area;
    break;
  }
  region.box = extent.grow(frame, region.box, params.extent_contrast);
}

void AutoInitializer::Impl::confirm(const cv::Mat& frame) {
  confirmed.clear();
  raw.clear();
  persistent = -1;
  persistent_score = 0.0;
  int set_aside_best = -1;
  double set_aside_score = 0.0;
  for (const Candidate& c : candidates) {
    raw.push_back(toFrame(toRegion(c.box, c.area, c.mean, c.strength / 255.0, c.touches_border)));
  }
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const Track& t = tracks[i];
    if (t.last_frame != frame_index || t.hits < params.auto_init_frames) continue;
    const int age = frame_index - t.first_frame + 1;
    const double seen = static_cast<double>(t.hits) / age;
    if (params.auto_init_frames > 1 && seen < kMinSeenShare) continue;

    double score = t.sum_peak / (255.0 * t.hits) * seen;
    if (params.auto_init_min_motion > 0.0) {
      double linearity = 0.0;
      bool with_background = false;
      const double motion = motionOf(t, &linearity, &with_background);
      // At least auto_init_min_motion and half the candidate's size: a region whose extent
      // fluctuates (a textured structure grown at 0.3 x its peak) moves its centre by a
      // fraction of its size without going anywhere.
      const double needed = std::max(params.auto_init_min_motion, 0.5 * std::max(t.box.width, t.box.height));
      if (!t.still && motion >= needed && linearity >= kMinLinearity && changedAgainstBackground(t.box) &&
          vacated(t)) {
        // Steady motion raises the score up to 3x the threshold.
        score *= std::min(1.0, motion / (kCueSaturation * params.auto_init_min_motion));
      } else {
        // No motion: a collision course shows as steady growth instead.
        double fit = 0.0;
        const double growth = params.auto_init_min_growth > 0.0 ? growthOf(t, &fit) : 0.0;
        if (!(growth >= params.auto_init_min_growth) || fit < kMinGrowthFit) {
          if (!t.still && !with_background && t.hits >= 2 * params.auto_init_frames) {
            int& best = t.set_aside ? set_aside_best : persistent;
            double& best_score = t.set_aside ? set_aside_score : persistent_score;
            if (score > best_score) {
              best = static_cast<int>(i);
              best_score = score;
            }
          }
          continue;
        }
        score *= std::min(1.0, growth / (kCueSaturation * params.auto_init_min_growth));
      }
    }
    SalientRegion region = toFrame(toRegion(t.box, t.area, t.last_mean, score, t.touches_border));
    refine(frame, region);
    confirmed.push_back(region);
  }
  // Every persistent candidate has had its chance: the round starts again.
  if (persistent < 0 && set_aside_best >= 0) {
    for (Track& t : tracks) t.set_aside = false;
    persistent = set_aside_best;
    persistent_score = set_aside_score;
  }
  std::sort(confirmed.begin(), confirmed.end(),
            [](const SalientRegion& a, const SalientRegion& b) { return a.score > b.score; });
}

AutoInitializer::AutoInitializer(const SaliencyParams& params) : impl_(new Impl) { setParams(params); }
AutoInitializer::~AutoInitializer() { delete impl_; }

void AutoInitializer::setParams(const SaliencyParams& params) {
  Impl& m = *impl_;
  const cv::Size old_work = m.work_size;
  m.params = params;
  clampGroup(m.params);
  if (!m.size.empty()) {
    const cv::Point2d carried = backgroundMotion();
    m.setWorkingSize(m.size);
    if (m.work_size != old_work) {
      // Every image of the state has the old working size: start again at the new one, with the
      // background's displacement so far carried over (tracks being verified measure from it).
      m.reset();
      m.background_base = carried;
    }
  }
  SaliencyParams refine = impl_->params;
  refine.search_window_scale = kRefineWindowScale;
  refine.min_object_area = 1.0;
  impl_->refiner.setParams(refine);
}

void AutoInitializer::reset() { impl_->reset(); }

const std::vector<SalientRegion>& AutoInitializer::update(const cv::Mat& frame, double stamp) {
  (void)stamp;
  requireFrame(frame, "AutoInitializer::update");
  Impl& m = *impl_;
  if (frame.size() != m.size) {
    m.reset();
    m.size = frame.size();
    m.setWorkingSize(m.size);
  }
  const cv::Mat grey = m.workingGrey(frame);
  m.globalMotion(grey);
  m.updateStill(grey);
  {
    cv::Mat& slot = m.past[static_cast<size_t>(m.frame_index % (kLag + 1))];
    grey.copyTo(slot);  // allocates once per frame size
    m.past_image_to_first[static_cast<size_t>(m.frame_index % (kLag + 1))] = m.image_to_first;
  }
  const cv::Mat p = m.candidateMap(grey);
  m.findCandidates(p);
  m.associate();
  m.confirm(frame);
  ++m.frame_index;
  return m.confirmed;
}

bool AutoInitializer::persistentRegion(const cv::Mat& frame, SalientRegion* region) {
  Impl& m = *impl_;
  if (m.persistent < 0 || region == nullptr) return false;
  const Impl::Track& t = m.tracks[static_cast<std::size_t>(m.persistent)];
  *region = m.toFrame(Impl::toRegion(t.box, t.area, t.last_mean, m.persistent_score, t.touches_border));
  m.refine(frame, *region);
  return true;
}

void AutoInitializer::setAsidePersistent(const cv::Rect2f& frame_box) {
  const cv::Rect2f box = impl_->toWorking(frame_box);
  const cv::Point2f c = boxCentre(box);
  for (Impl::Track& t : impl_->tracks) {
    if (cv::Rect2f(t.box).contains(c) || box.contains(t.centre)) t.set_aside = true;
  }
}

// Central differences summed over the box by hand: only the three tensor sums are needed, and
// cv::Sobel / cv::cornerEigenValsAndVecs would allocate gradient images on every call (once per
// frame per unverified track, on the tracking path).
double AutoInitializer::lineCoherence(const cv::Rect2f& box_f) const {
  const Impl& m = *impl_;
  if (m.frame_index == 0) return 0.0;
  const cv::Mat& grey = m.past[static_cast<std::size_t>((m.frame_index - 1) % (Impl::kLag + 1))];
  const cv::Rect box = cv::Rect(m.toWorking(box_f)) & cv::Rect(1, 1, grey.cols - 2, grey.rows - 2);
  double xx = 0.0, yy = 0.0, xy = 0.0;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const uchar* up = grey.ptr<uchar>(y - 1);
    const uchar* row = grey.ptr<uchar>(y);
    const uchar* down = grey.ptr<uchar>(y + 1);
    for (int x = box.x; x < box.x + box.width; ++x) {
      const double gx = row[x + 1] - row[x - 1], gy = down[x] - up[x];
      xx += gx * gx;
      yy += gy * gy;
      xy += gx * gy;
    }
  }
  const double trace = xx + yy;
  return trace > 0.0 ? std::sqrt((xx - yy) * (xx - yy) + 4.0 * xy * xy) / trace : 0.0;
}

double AutoInitializer::stillShare(const cv::Rect2f& box) const {
  const cv::Mat& still = impl_->still;
  if (still.empty() || still.size() != impl_->work_size || !impl_->params.auto_init_reject_static) return 0.0;
  const cv::Rect r = cv::Rect(impl_->toWorking(box)) & cv::Rect(0, 0, still.cols, still.rows);
  if (r.area() <= 0) return 0.0;
  return static_cast<double>(impl_->stillPixels(r)) / r.area();
}

double AutoInitializer::overlayShare(const cv::Rect2f& frame_box) const {
  const cv::Rect2f box = impl_->toWorking(frame_box);
  const cv::Point2d s = impl_->motion.workingScale();
  const cv::Rect working(cv::Point(static_cast<int>(box.x * s.x), static_cast<int>(box.y * s.y)),
                         cv::Point(static_cast<int>(std::ceil((box.x + box.width) * s.x)),
                                   static_cast<int>(std::ceil((box.y + box.height) * s.y))));
  return impl_->overlay.share(working);
}

const std::vector<SalientRegion>& AutoInitializer::candidates() const { return impl_->raw; }
double AutoInitializer::framePixelsPerWorkingPixel() const { return 1.0 / impl_->work_scale.x; }

cv::Point2d AutoInitializer::backgroundMotion() const {
  const Impl& m = *impl_;
  return m.background_base + cv::Point2d(m.background.x / m.work_scale.x, m.background.y / m.work_scale.y);
}

}  // namespace core
}  // namespace obstacle_tracker
