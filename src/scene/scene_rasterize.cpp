// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// One obstacle over one exposure: its outline sampled along the exposure, drawn as coverage and
// premultiplied colour into a patch, and its ground-truth box measured from the drawn pixels.
#include <algorithm>
#include <cmath>

#include "obstacle_tracker/scene/raster.h"
#include "scene_generator_impl.h"

namespace obstacle_tracker {
namespace scene {

namespace {

// A size-s view of store, which only grows (no reallocation from frame to frame).
cv::Mat view(cv::Mat& store, cv::Size s, int type) {
  if (store.empty() || store.rows < s.height || store.cols < s.width || store.type() != type)
    store.create(std::max(s.height, store.type() == type ? store.rows : 0), std::max(s.width, store.type() == type ? store.cols : 0), type);
  return store(cv::Rect(0, 0, s.width, s.height));
}

}  // namespace

void SceneGenerator::Impl::rasterize(int ti, double t, const cv::Point2d& cam, const std::vector<cv::Point>& blur_off,
                                     Rendered& ro) {
  const Track& tr = tracks[static_cast<std::size_t>(ti)];
  const TrackPose mid = tr.at(t);
  Extent ext;
  const int n = sampleExposure(tr, t, mid, cam, ext);
  ro.track = ti;
  ro.truth = ObstacleTruth();
  ro.truth.id = tr.id;
  ro.truth.cls = tr.model.cls;
  ro.truth.distractor = tr.distractor;
  ro.truth.scale_px = mid.pose.scale;
  ro.truth.distance_m = f_px * tr.model.size_m / std::max(1e-6, static_cast<double>(mid.pose.scale));
  ro.truth.time_to_contact = mid.ttc;
  ro.truth.shape_box = cv::Rect2f(ext.x0, ext.y0, ext.x1 - ext.x0, ext.y1 - ext.y0);
  if (!placePatch(ext, ro)) {
    ro.patch = cv::Rect();
    ro.total = 0.0;
    return;
  }
  drawSamples(n, ro);
  double total = 0.0;
  for (int r = 0; r < ro.patch.height; ++r) {
    const float* ar = ro.a.ptr<float>(r);
    for (int c = 0; c < ro.patch.width; ++c) total += ar[c];
  }
  ro.total = total;
  measureDrawnBox(blur_off, ro);
}

// Projects the outline at n times over the exposure into `samples` (enough that the outline
// moves less than 0.75 px between samples); returns n and the extent of all samples in frame
// coordinates. mid is the pose at t.
int SceneGenerator::Impl::sampleExposure(const Track& tr, double t, const TrackPose& mid, const cv::Point2d& cam, Extent& ext) {
  const double e = exposure / fps;
  const TrackPose pa = tr.at(t - 0.5 * e), pb = tr.at(t + 0.5 * e);
  const double move = std::sqrt(static_cast<double>((pb.pose.centre - pa.pose.centre).dot(pb.pose.centre - pa.pose.centre))) +
                      std::fabs(pb.pose.scale - pa.pose.scale) * 0.5;
  const int n = move < 0.75 ? 1 : std::min(16, static_cast<int>(std::ceil(move / 0.75)) + 1);
  if (samples.size() < static_cast<std::size_t>(n)) samples.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double tk = n == 1 ? t : t - 0.5 * e + e * k / (n - 1);
    Pose p = (n == 1 ? mid : tr.at(tk)).pose;
    p.centre.x -= static_cast<float>(cam.x);
    p.centre.y -= static_cast<float>(cam.y);
    projectShape(tr.model, p, samples[static_cast<std::size_t>(k)]);
    const cv::Rect2f b = projectedBounds(samples[static_cast<std::size_t>(k)]);
    ext.x0 = std::min(ext.x0, b.x);
    ext.y0 = std::min(ext.y0, b.y);
    ext.x1 = std::max(ext.x1, b.x + b.width);
    ext.y1 = std::max(ext.y1, b.y + b.height);
  }
  return n;
}

// Patch: the unclipped extent (bounded to a generous window around the frame). False: nothing
// to draw.
bool SceneGenerator::Impl::placePatch(const Extent& ext, Rendered& ro) const {
  int px0 = static_cast<int>(std::floor(ext.x0)), py0 = static_cast<int>(std::floor(ext.y0));
  int px1 = static_cast<int>(std::ceil(ext.x1)), py1 = static_cast<int>(std::ceil(ext.y1));
  px0 = std::max(px0, -2 * W);
  py0 = std::max(py0, -2 * H);
  px1 = std::min(px1, 3 * W);
  py1 = std::min(py1, 3 * H);
  if (px1 <= px0 || py1 <= py0 || ext.x1 < ext.x0) return false;
  ro.patch = cv::Rect(px0, py0, px1 - px0, py1 - py0);
  return true;
}

// The mean of the n samples' coverage and colour over the patch.
void SceneGenerator::Impl::drawSamples(int n, Rendered& ro) {
  const int cn = mono16 ? 1 : 3;
  ro.col = view(ro.col_store, ro.patch.size(), CV_32FC(cn));
  ro.a = view(ro.a_store, ro.patch.size(), CV_32FC1);
  ro.col.setTo(0.0f);
  ro.a.setTo(0.0f);
  cv::Mat scol, sa;
  if (n > 1) {
    scol = view(scol_store, ro.patch.size(), CV_32FC(cn));
    sa = view(sa_store, ro.patch.size(), CV_32FC1);
  }
  const float inv_n = 1.0f / static_cast<float>(n);
  for (int k = 0; k < n; ++k) {
    cv::Mat& C = n > 1 ? scol : ro.col;
    cv::Mat& A = n > 1 ? sa : ro.a;
    if (n > 1) {
      C.setTo(0.0f);
      A.setTo(0.0f);
    }
    for (const ProjectedPlate& pl : samples[static_cast<std::size_t>(k)]) drawPlate(pl, ro.patch, C, A);
    if (n > 1) {
      for (int r = 0; r < ro.patch.height; ++r) {
        const float* sc = scol.ptr<float>(r);
        const float* sar = sa.ptr<float>(r);
        float* dc = ro.col.ptr<float>(r);
        float* dar = ro.a.ptr<float>(r);
        for (int c = 0; c < ro.patch.width * cn; ++c) dc[c] += sc[c] * inv_n;
        for (int c = 0; c < ro.patch.width; ++c) dar[c] += sar[c] * inv_n;
      }
    }
  }
}

// One plate over what is drawn (C colour, A alpha; patch-sized), shaded across the plate.
void SceneGenerator::Impl::drawPlate(const ProjectedPlate& pl, const cv::Rect& patch, cv::Mat& C, cv::Mat& A) {
  const int cn = mono16 ? 1 : 3;
  float bx0 = 1e30f, by0 = 1e30f, bx1 = -1e30f, by1 = -1e30f;
  for (const auto& q : pl.pts) {
    bx0 = std::min(bx0, q.x);
    by0 = std::min(by0, q.y);
    bx1 = std::max(bx1, q.x);
    by1 = std::max(by1, q.y);
  }
  const cv::Rect pr = cv::Rect(cv::Point(static_cast<int>(std::floor(bx0)), static_cast<int>(std::floor(by0))),
                               cv::Point(static_cast<int>(std::ceil(bx1)), static_cast<int>(std::ceil(by1)))) &
                      patch;
  if (pr.empty()) return;
  const cv::Rect lr(pr.x - patch.x, pr.y - patch.y, pr.width, pr.height);
  cv::Mat cov = view(cov_store, pr.size(), CV_32FC1);
  cov.setTo(0.0f);
  addPolygonCoverage(pl.pts.data(), static_cast<int>(pl.pts.size()), pr.tl(), subrowsForHeight(by1 - by0), cov);
  for (int r = 0; r < pr.height; ++r) {
    const float* cv_ = cov.ptr<float>(r);
    float* ar = A.ptr<float>(lr.y + r) + lr.x;
    float* cr = C.ptr<float>(lr.y + r) + lr.x * cn;
    const float py = static_cast<float>(pr.y + r) + 0.5f - pl.centroid.y;
    for (int c = 0; c < pr.width; ++c) {
      const float a = std::min(cv_[c], 1.0f) * pl.alpha;
      if (a <= 0.0f) continue;
      const float px = static_cast<float>(pr.x + c) + 0.5f - pl.centroid.x;
      const float shade = 1.0f + pl.gradient.x * px + pl.gradient.y * py;
      ar[c] = ar[c] * (1.0f - a) + a;
      if (cn == 1) {
        cr[c] = cr[c] * (1.0f - a) + a * pl.thermal * (0.5f + 0.5f * shade);
      } else {
        for (int ch = 0; ch < 3; ++ch) cr[c * 3 + ch] = cr[c * 3 + ch] * (1.0f - a) + a * pl.bgr[ch] * shade;
      }
    }
  }
}

// The box is the extent of the drawn pixels (alpha >= half a grey level, the same test as the
// mask), refined to sub-pixel: on a straight edge the coverage of the outermost pixel column is
// the covered fraction of that column.
void SceneGenerator::Impl::measureDrawnBox(const std::vector<cv::Point>& blur_off, Rendered& ro) {
  const float tau = 0.5f / 255.0f;
  colmax_.assign(static_cast<std::size_t>(ro.patch.width), 0.0f);
  float r_first = -1.0f, r_last = -1.0f;
  int ry0 = -1, ry1 = -1;
  for (int r = 0; r < ro.patch.height; ++r) {
    const float* ar = ro.a.ptr<float>(r);
    float rm = 0.0f;
    for (int c = 0; c < ro.patch.width; ++c) {
      rm = std::max(rm, ar[c]);
      colmax_[static_cast<std::size_t>(c)] = std::max(colmax_[static_cast<std::size_t>(c)], ar[c]);
    }
    if (rm >= tau) {
      if (ry0 < 0) {
        ry0 = r;
        r_first = std::min(rm, 1.0f);
      }
      ry1 = r;
      r_last = std::min(rm, 1.0f);
    }
  }
  if (ry0 < 0) return;  // nothing visible was drawn
  int cx0i = -1, cx1i = -1;
  for (int c = 0; c < ro.patch.width; ++c)
    if (colmax_[static_cast<std::size_t>(c)] >= tau) {
      if (cx0i < 0) cx0i = c;
      cx1i = c;
    }
  float gx0 = static_cast<float>(ro.patch.x + cx0i) + 1.0f - std::min(colmax_[static_cast<std::size_t>(cx0i)], 1.0f);
  float gx1 = static_cast<float>(ro.patch.x + cx1i) + std::min(colmax_[static_cast<std::size_t>(cx1i)], 1.0f);
  float gy0 = static_cast<float>(ro.patch.y + ry0) + 1.0f - r_first;
  float gy1 = static_cast<float>(ro.patch.y + ry1) + r_last;
  // Camera motion blur spreads the drawn shape over the blur offsets.
  int ox0 = 0, oy0 = 0, ox1 = 0, oy1 = 0;
  for (const auto& o : blur_off) {
    ox0 = std::min(ox0, o.x);
    oy0 = std::min(oy0, o.y);
    ox1 = std::max(ox1, o.x);
    oy1 = std::max(oy1, o.y);
  }
  gx0 += static_cast<float>(ox0);
  gy0 += static_cast<float>(oy0);
  gx1 += static_cast<float>(ox1);
  gy1 += static_cast<float>(oy1);
  const float cx0 = std::max(gx0, 0.0f), cy0 = std::max(gy0, 0.0f);
  const float cx1 = std::min(gx1, static_cast<float>(W)), cy1 = std::min(gy1, static_cast<float>(H));
  if (cx1 > cx0 && cy1 > cy0) ro.truth.box = cv::Rect2f(cx0, cy0, cx1 - cx0, cy1 - cy0);
}

}  // namespace scene
}  // namespace obstacle_tracker
