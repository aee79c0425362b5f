// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// AutoInitializer::Impl (auto_init_impl.h), step 4: candidates associated with the tracks of
// earlier frames, and the cues a track is confirmed on (motion against image and background,
// vacated place, appearance change, steady growth).
#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "auto_init_impl.h"
#include "obstacle_tracker/core/box_geometry.h"

namespace obstacle_tracker {
namespace core {

using namespace auto_init_detail;  // NOLINT(build/namespaces): the auto-initialiser's own constants

void AutoInitializer::Impl::associate() {
  for (Candidate& c : candidates) {
    int best = -1;
    float best_d2 = 0.0f;
    for (size_t t = 0; t < tracks.size(); ++t) {
      Track& tr = tracks[t];
      if (tr.last_frame == frame_index) continue;  // already matched in this frame
      const float gap = static_cast<float>(frame_index - tr.last_frame);
      const cv::Point2f pred = tr.centre + tr.velocity * gap;  // image velocity (camera included)
      const float gate =
          std::max(kGateMinPx, kGateBoxShare * std::max(tr.box.width, tr.box.height)) + kGatePxPerMissed * gap;
      const cv::Point2f d = c.centre - pred;
      const float d2 = d.dot(d);
      if (d2 <= gate * gate && (best < 0 || d2 < best_d2)) {
        best = static_cast<int>(t);
        best_d2 = d2;
      }
    }
    if (best >= 0) {
      Track& tr = tracks[static_cast<size_t>(best)];
      const float gap = static_cast<float>(frame_index - tr.last_frame);
      const cv::Point2f v = (c.centre - tr.centre) * (1.0f / gap);
      tr.velocity = tr.hits == 1 ? v : 0.5f * tr.velocity + 0.5f * v;
      tr.centre = c.centre;
      tr.box = c.box;
      tr.area = c.area;
      tr.last_frame = frame_index;
      ++tr.hits;
      tr.sum_peak += c.strength;
      tr.last_mean = c.mean;
      tr.touches_border = c.touches_border;
      tr.still = c.still;
      tr.remember(frame_index, c.centre, image_to_first, c.size_px, contrastAround(c.centre));
    } else if (tracks.size() < kMaxTracks) {
      Track tr;
      tr.centre = c.centre;
      tr.velocity = cv::Point2f(0.0f, 0.0f);
      tr.box = c.box;
      tr.area = c.area;
      tr.first_frame = tr.last_frame = frame_index;
      tr.hits = 1;
      tr.sum_peak = c.strength;
      tr.last_mean = c.mean;
      tr.touches_border = c.touches_border;
      tr.still = c.still;
      tr.remember(frame_index, c.centre, image_to_first, c.size_px, contrastAround(c.centre));
      tracks.push_back(tr);
    }
  }
  tracks.erase(std::remove_if(tracks.begin(), tracks.end(),
                              [&](const Track& t) { return frame_index - t.last_frame > kMaxMissed; }),
               tracks.end());
}

// Appearance test of motion against the background: the box now against the same place of
// the frame kLag frames ago, displaced by the background's motion since. A static structure
// (or an overlay, once the background is accounted for) looks the same up to noise; a moving
// target's box held background then. Mean absolute difference over the box (grown by 2 px),
// relative to the mean local contrast there, must reach kMinChange. The region-centre motion
// fit alone is fooled by regions whose extent fluctuates along a static edge.
bool AutoInitializer::Impl::changedAgainstBackground(const cv::Rect& box) const {
  if (frame_index < kLag || contrast_map.empty()) return true;  // too early to tell
  const cv::Mat& now = past[static_cast<size_t>(frame_index % (kLag + 1))];
  const cv::Mat& then = past[static_cast<size_t>((frame_index - kLag) % (kLag + 1))];
  // Where the background at the box's centre was kLag frames ago, as a shift.
  const cv::Point2f centre = boxCentre(cv::Rect2f(box));
  const cv::Matx33d then_to_now =
      first_to_image * past_image_to_first[static_cast<size_t>((frame_index - kLag) % (kLag + 1))];
  const cv::Point2d shift = cv::Point2d(centre) - cv::Point2d(apply(then_to_now.inv(), centre));
  const cv::Rect frame_rect(0, 0, now.cols, now.rows);
  const cv::Rect a = cv::Rect(box.x - 2, box.y - 2, box.width + 4, box.height + 4) & frame_rect;
  const cv::Point d(static_cast<int>(std::lround(shift.x)), static_cast<int>(std::lround(shift.y)));
  const cv::Rect b = (a - d) & frame_rect;  // where that content was kLag frames ago
  const cv::Rect a2 = b + d;
  if (a2.area() <= 0) return true;
  double diff_sum = 0.0, contrast_sum = 0.0;
  for (int y = 0; y < a2.height; ++y) {
    const uchar* p = now.ptr<uchar>(a2.y + y) + a2.x;
    const uchar* q = then.ptr<uchar>(b.y + y) + b.x;
    const uchar* c = contrast_map.ptr<uchar>(a2.y + y) + a2.x;
    for (int x = 0; x < a2.width; ++x) {
      diff_sum += std::abs(p[x] - q[x]);
      contrast_sum += c[x];
    }
  }
  return diff_sum >= kMinChange * (contrast_sum + a2.area());
}

// Largest local contrast in the 5x5 px around c (-1 outside the frame).
int AutoInitializer::Impl::contrastAround(cv::Point2f c) const {
  if (contrast_map.empty()) return -1;
  const int cx = static_cast<int>(std::lround(c.x)), cy = static_cast<int>(std::lround(c.y));
  int best = -1;
  for (int y = std::max(0, cy - 2); y <= std::min(contrast_map.rows - 1, cy + 2); ++y) {
    const uchar* row = contrast_map.ptr<uchar>(y);
    for (int x = std::max(0, cx - 2); x <= std::min(contrast_map.cols - 1, cx + 2); ++x) {
      best = std::max(best, static_cast<int>(row[x]));
    }
  }
  return best;
}

// Vacated-position test for the motion cue: a mover leaves its old place to the background; a
// candidate whose peak wanders along a static structure (a lattice tower under camera jitter,
// an edge) leaves the structure where it was. The local contrast now at the track's oldest
// remembered position (carried with the background to this frame) must have fallen below
// kVacated x what it was when the track was there (maxima over 5x5 px).
bool AutoInitializer::Impl::vacated(const Track& t) const {
  const int n = std::min(t.count, kHistory);
  if (n < 2 || contrast_map.empty()) return true;
  const size_t oldest = static_cast<size_t>(t.count <= kHistory ? 0 : t.count % kHistory);
  const int now = contrastAround(apply(first_to_image, t.rel[oldest]));
  if (now < 0 || t.contrast[oldest] <= 0) return true;  // its old place has left the frame
  return now < kVacated * t.contrast[oldest];
}

// Displacement of a track over its remembered history, from least-squares lines through its
// positions against time (so that a region whose box jitters around a fixed point, e.g. a
// textured structure, does not count as moving): the smaller of the displacement in the image
// and the displacement against the background.
// `linearity` receives the share of the positions' variance the line explains (for the
// smaller displacement): near 1 for a target moving steadily, low for a jittering box.
double AutoInitializer::Impl::motionOf(const Track& t, double* linearity, bool* with_background) {
  const int n = std::min(t.count, kHistory);
  if (linearity) *linearity = 0.0;
  if (with_background) *with_background = false;
  if (n < 2) return 0.0;
  double mt = 0.0;
  cv::Point2d mi(0, 0), mr(0, 0);
  int t_lo = INT32_MAX, t_hi = INT32_MIN;
  for (int k = 0; k < n; ++k) {
    mt += t.frames[k];
    mi += cv::Point2d(t.img[k]);
    mr += cv::Point2d(t.rel[k]);
    t_lo = std::min(t_lo, t.frames[k]);
    t_hi = std::max(t_hi, t.frames[k]);
  }
  mt /= n;
  mi *= 1.0 / n;
  mr *= 1.0 / n;
  double stt = 0.0, vi = 0.0, vr = 0.0;
  cv::Point2d si(0, 0), sr(0, 0);
  for (int k = 0; k < n; ++k) {
    const double dt = t.frames[k] - mt;
    const cv::Point2d di = cv::Point2d(t.img[k]) - mi, dr = cv::Point2d(t.rel[k]) - mr;
    stt += dt * dt;
    si += dt * di;
    sr += dt * dr;
    vi += di.dot(di);
    vr += dr.dot(dr);
  }
  if (stt <= 0.0) return 0.0;
  const double span = t_hi - t_lo;
  const double ni = std::hypot(si.x, si.y), nr = std::hypot(sr.x, sr.y);
  const bool img_smaller = ni < nr;
  // Its positions scatter in the image (a pan, a shaking camera) but hold still against the
  // background (a quarter of the image's variance at most): a scene object the camera's motion
  // carries, world-fixed or drifting with the view.
  if (with_background) *with_background = vi >= kWithBackgroundMinPx * kWithBackgroundMinPx * n && vr < 0.25 * vi;
  if (linearity) {
    const double explained = (img_smaller ? ni * ni : nr * nr) / stt;
    const double total = img_smaller ? vi : vr;
    *linearity = total > 0.0 ? explained / total : 0.0;
  }
  return span * std::min(ni, nr) / stt;
}

// Growth of a track over its remembered history: the least-squares line through
// ln sqrt(size_px) (its object pixels, see findCandidates) against time, times the time span
// (so 0.2 = the size grew by e^0.2 = 22 %). An obstacle on a collision course keeps its bearing, so it has no motion across the image or against
// the background to confirm it by; its growth is the cue (looming, as in the TTC literature:
// Lee 1976). `fit` receives the share of the log sizes' variance the line explains (a region
// whose extent fluctuates grows and shrinks without a trend). Needs kMinGrowthSamples points.
double AutoInitializer::Impl::growthOf(const Track& t, double* fit) {
  const int n = std::min(t.count, kHistory);
  *fit = 0.0;
  if (n < kMinGrowthSamples) return 0.0;
  double mt = 0.0, ms = 0.0;
  int t_lo = INT32_MAX, t_hi = INT32_MIN;
  for (int k = 0; k < n; ++k) {
    mt += t.frames[k];
    ms += t.log_size[k];
    t_lo = std::min(t_lo, t.frames[k]);
    t_hi = std::max(t_hi, t.frames[k]);
  }
  mt /= n;
  ms /= n;
  double stt = 0.0, sts = 0.0, sss = 0.0;
  for (int k = 0; k < n; ++k) {
    const double dt = t.frames[k] - mt, ds = t.log_size[k] - ms;
    stt += dt * dt;
    sts += dt * ds;
    sss += ds * ds;
  }
  if (stt <= 0.0) return 0.0;
  const double slope = sts / stt;
  *fit = sss > 0.0 ? slope * sts / sss : 0.0;
  return slope * (t_hi - t_lo);
}

}  // namespace core
}  // namespace obstacle_tracker
