// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Scene generator: the scenario list, per-frame rendering and ground truth, the public
// interface (scene_generator.h). The set-up is in the files that scene_generator_impl.h names.
#include "obstacle_tracker/scene/scene_generator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/scene/raster.h"
#include "scene_generator_impl.h"

namespace obstacle_tracker {
namespace scene {

const ObstacleTruth* FrameTruth::find(int id) const {
  for (const auto& o : obstacles)
    if (o.id == id) return &o;
  return nullptr;
}

std::vector<ScenarioDescription> listScenarios() {
  return {
      {"demo", false, "the README demo: a light aircraft approaching (time to contact known) in a sky with clouds above a tree line, mild camera jitter and sensor noise"},
      {"approach", false, "a fixed-wing aircraft on a collision course: size grows as s0*T/(T-t), time to contact T-t known per frame"},
      {"crossing", false, "a fixed-wing aircraft crossing the view at constant distance; the camera pans slowly after it"},
      {"rotation", false, "a multirotor hovering and drifting with planar rotation (image roll) and out-of-plane rotation (yaw, view elevation, tilt)"},
      {"out_of_view", false, "a multirotor that flies out of the frame on one side, comes back, leaves on the other side and comes back"},
      {"multi", false, "three obstacles (multirotor id 1, aircraft id 2, bird id 3) whose paths cross near the centre, hiding each other"},
      {"bird", false, "a flapping bird crossing the view with a wavy flight path"},
      {"tiny", false, "a multirotor a few pixels wide drifting just above a cluttered horizon (trees, buildings, a lattice mast)"},
      {"jitter", true, "camera shake: a sum of low- and high-frequency oscillations of a few pixels"},
      {"jerk", true, "sudden camera jerks (a tenth of the frame in two frames, held, then re-centred) with camera motion blur"},
      {"blur", true, "long exposure (a whole frame period) and an erratic zig-zag of the main obstacle: strong motion blur"},
      {"noise", true, "strong sensor noise (and column fixed-pattern noise in the thermal mode)"},
      {"illumination", true, "illumination change: the scene dims to about half and recovers (auto-exposure / sun behind cloud), with a colour shift"},
      {"occlusion", true, "a dense cloud drifts across the main obstacle: partial, then full, then partial occlusion"},
      {"flock", true, "a flock of birds (distractors, ids from 101) crosses close to the main obstacle"},
      {"overlay", true, "camera on-screen display: date/time, azimuth/elevation, field of view, frame counter and a reticle"},
      {"glare", true, "the sun next to the main obstacle's path, with strong glare and a lens streak"},
      {"clutter", true, "a high horizon (trees, buildings, a mast) with the obstacle in front of it"},
      {"small", true, "the main obstacle about a third of its usual size"},
      {"large", true, "the main obstacle about two and a half times its usual size"},
      {"as_fixed_wing", true, "the main obstacle is a fixed-wing aircraft"},
      {"as_multirotor", true, "the main obstacle is a multirotor"},
      {"as_bird", true, "the main obstacle is a bird"},
  };
}

namespace {

cv::Mat view(cv::Mat& store, cv::Size s, int type) {
  if (store.empty() || store.rows < s.height || store.cols < s.width || store.type() != type)
    store.create(std::max(s.height, store.type() == type ? store.rows : 0), std::max(s.width, store.type() == type ? store.cols : 0), type);
  return store(cv::Rect(0, 0, s.width, s.height));
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// Per-frame obstacle rendering.

void SceneGenerator::Impl::rasterize(int ti, double t, const cv::Point2d& cam, const std::vector<cv::Point>& blur_off,
                                     Rendered& ro) {
  const Track& tr = tracks[static_cast<std::size_t>(ti)];
  const double e = exposure / fps;
  const TrackPose mid = tr.at(t);
  const TrackPose pa = tr.at(t - 0.5 * e), pb = tr.at(t + 0.5 * e);
  const double move = std::sqrt(static_cast<double>((pb.pose.centre - pa.pose.centre).dot(pb.pose.centre - pa.pose.centre))) +
                      std::fabs(pb.pose.scale - pa.pose.scale) * 0.5;
  const int n = move < 0.75 ? 1 : std::min(16, static_cast<int>(std::ceil(move / 0.75)) + 1);
  if (samples.size() < static_cast<std::size_t>(n)) samples.resize(static_cast<std::size_t>(n));
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (int k = 0; k < n; ++k) {
    const double tk = n == 1 ? t : t - 0.5 * e + e * k / (n - 1);
    Pose p = (n == 1 ? mid : tr.at(tk)).pose;
    p.centre.x -= static_cast<float>(cam.x);
    p.centre.y -= static_cast<float>(cam.y);
    projectShape(tr.model, p, samples[static_cast<std::size_t>(k)]);
    const cv::Rect2f b = projectedBounds(samples[static_cast<std::size_t>(k)]);
    x0 = std::min(x0, b.x);
    y0 = std::min(y0, b.y);
    x1 = std::max(x1, b.x + b.width);
    y1 = std::max(y1, b.y + b.height);
  }
  ro.track = ti;
  ro.truth = ObstacleTruth();
  ro.truth.id = tr.id;
  ro.truth.cls = tr.model.cls;
  ro.truth.distractor = tr.distractor;
  ro.truth.scale_px = mid.pose.scale;
  ro.truth.distance_m = f_px * tr.model.size_m / std::max(1e-6, static_cast<double>(mid.pose.scale));
  ro.truth.time_to_contact = mid.ttc;
  ro.truth.shape_box = cv::Rect2f(x0, y0, x1 - x0, y1 - y0);
  // Patch: the unclipped extent (bounded to a generous window around the frame).
  int px0 = static_cast<int>(std::floor(x0)), py0 = static_cast<int>(std::floor(y0));
  int px1 = static_cast<int>(std::ceil(x1)), py1 = static_cast<int>(std::ceil(y1));
  px0 = std::max(px0, -2 * W);
  py0 = std::max(py0, -2 * H);
  px1 = std::min(px1, 3 * W);
  py1 = std::min(py1, 3 * H);
  if (px1 <= px0 || py1 <= py0 || x1 < x0) {
    ro.patch = cv::Rect();
    ro.total = 0.0;
    return;
  }
  ro.patch = cv::Rect(px0, py0, px1 - px0, py1 - py0);
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
    for (const ProjectedPlate& pl : samples[static_cast<std::size_t>(k)]) {
      float bx0 = 1e30f, by0 = 1e30f, bx1 = -1e30f, by1 = -1e30f;
      for (const auto& q : pl.pts) {
        bx0 = std::min(bx0, q.x);
        by0 = std::min(by0, q.y);
        bx1 = std::max(bx1, q.x);
        by1 = std::max(by1, q.y);
      }
      const cv::Rect pr = cv::Rect(cv::Point(static_cast<int>(std::floor(bx0)), static_cast<int>(std::floor(by0))),
                                   cv::Point(static_cast<int>(std::ceil(bx1)), static_cast<int>(std::ceil(by1)))) &
                          ro.patch;
      if (pr.empty()) continue;
      const cv::Rect lr(pr.x - ro.patch.x, pr.y - ro.patch.y, pr.width, pr.height);
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
  double total = 0.0;
  for (int r = 0; r < ro.patch.height; ++r) {
    const float* ar = ro.a.ptr<float>(r);
    for (int c = 0; c < ro.patch.width; ++c) total += ar[c];
  }
  ro.total = total;
  // The box is the extent of the drawn pixels (alpha >= half a grey level, the same test as the
  // mask), refined to sub-pixel: on a straight edge the coverage of the outermost pixel column is
  // the covered fraction of that column.
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

void SceneGenerator::Impl::computeObjects(int i) {
  const double t = i / fps;
  const cv::Point2d cam = cameraAt(t);
  const cv::Point2f bv = blurAt(i);
  const std::vector<cv::Point> off = directionalBlurOffsets(bv.x, bv.y);
  for (std::size_t k = 0; k < tracks.size(); ++k) rasterize(static_cast<int>(k), t, cam, off, objs[k]);
  // Far to near.
  order.resize(objs.size());
  for (std::size_t k = 0; k < objs.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return objs[static_cast<std::size_t>(a)].truth.distance_m > objs[static_cast<std::size_t>(b)].truth.distance_m;
  });
  // Visible fraction: the part inside the frame, not hidden by nearer obstacles or clouds.
  const cv::Rect frame(0, 0, W, H);
  for (std::size_t oi = 0; oi < order.size(); ++oi) {
    Rendered& ro = objs[static_cast<std::size_t>(order[oi])];
    if (ro.total <= 0.0 || ro.truth.box.area() <= 0.0f) {
      ro.truth.visible_fraction = 0.0f;
      ro.truth.visible = false;
      continue;
    }
    const cv::Rect in = ro.patch & frame;
    double vis = 0.0;
    for (int y = in.y; y < in.y + in.height; ++y) {
      const float* ar = ro.a.ptr<float>(y - ro.patch.y);
      for (int x = in.x; x < in.x + in.width; ++x) {
        const float a = ar[x - ro.patch.x];
        if (a <= 0.0f) continue;
        float trans = 1.0f;
        for (std::size_t oj = oi + 1; oj < order.size(); ++oj) {
          const Rendered& rj = objs[static_cast<std::size_t>(order[oj])];
          if (rj.total <= 0.0 || !rj.patch.contains(cv::Point(x, y))) continue;
          trans *= 1.0f - rj.a.ptr<float>(y - rj.patch.y)[x - rj.patch.x];
        }
        for (const auto& oc : occluders) {
          const cv::Point tl = oc.topLeft(t, cam);
          const int sx = x - tl.x, sy = y - tl.y;
          if (sx < 0 || sy < 0 || sx >= oc.alpha.cols || sy >= oc.alpha.rows) continue;
          trans *= 1.0f - oc.alpha.ptr<float>(sy)[sx];
        }
        vis += static_cast<double>(a) * trans;
      }
    }
    ro.truth.visible_fraction = static_cast<float>(std::min(1.0, vis / ro.total));
    ro.truth.visible = ro.truth.visible_fraction >= kVisibleThreshold;
  }
}

template <typename T, int CN>
void SceneGenerator::Impl::composite(cv::Mat& out) {
  const cv::Rect frame(0, 0, W, H);
  const float maxv = static_cast<float>(std::numeric_limits<T>::max());
  if (cfg.render_obstacles) {
    for (int idx : order) {
      const Rendered& ro = objs[static_cast<std::size_t>(idx)];
      if (ro.total <= 0.0) continue;
      const cv::Rect in = ro.patch & frame;
      for (int y = in.y; y < in.y + in.height; ++y) {
        const float* ar = ro.a.ptr<float>(y - ro.patch.y) + (in.x - ro.patch.x);
        const float* cr = ro.col.ptr<float>(y - ro.patch.y) + (in.x - ro.patch.x) * CN;
        T* o = out.ptr<T>(y) + in.x * CN;
        for (int c = 0; c < in.width; ++c) {
          const float a = ar[c];
          if (a <= 0.0f) continue;
          for (int k = 0; k < CN; ++k) {
            const float v = static_cast<float>(o[c * CN + k]) * (1.0f - a) + cr[c * CN + k];
            o[c * CN + k] = static_cast<T>(std::min(std::max(v, 0.0f), maxv) + 0.5f);
          }
        }
      }
    }
  }
}

// ------------------------------------------------------------------------------------------------

SceneGenerator::SceneGenerator(const ScenarioConfig& config) : impl_(new Impl) {
  if (config.size.width < 16 || config.size.height < 16 || config.size.width > 8192 || config.size.height > 8192)
    throw std::invalid_argument("scene: frame size must be between 16x16 and 8192x8192");
  if (!(config.fps > 0.0 && config.fps <= 1000.0)) throw std::invalid_argument("scene: fps must be in (0, 1000]");
  if (config.frames < 0) throw std::invalid_argument("scene: frames must be >= 0 (0 = default)");
  impl_->cfg = config;
  impl_->setup();
}

SceneGenerator::~SceneGenerator() = default;
SceneGenerator::SceneGenerator(SceneGenerator&&) noexcept = default;
SceneGenerator& SceneGenerator::operator=(SceneGenerator&&) noexcept = default;

const ScenarioConfig& SceneGenerator::config() const { return impl_->cfg; }
const ScenarioInfo& SceneGenerator::info() const { return impl_->info; }
int SceneGenerator::frameCount() const { return impl_->frames; }
double SceneGenerator::fps() const { return impl_->fps; }
cv::Size SceneGenerator::size() const { return cv::Size(impl_->W, impl_->H); }
int SceneGenerator::type() const { return impl_->mono16 ? CV_16UC1 : CV_8UC3; }

void SceneGenerator::thermalDisplayRange(double& lo, double& hi) const {
  lo = 5500.0;
  hi = 13500.0;
}

namespace {

void checkIndex(int i, int frames) {
  if (i < 0 || i >= frames)
    throw std::out_of_range("scene: frame " + std::to_string(i) + " outside [0, " + std::to_string(frames) + ")");
}

template <typename T, int CN>
void compositeOccluders(cv::Mat& out, const cv::Mat& premul, const cv::Mat& alpha, cv::Point tl) {
  const cv::Rect r = cv::Rect(tl, alpha.size()) & cv::Rect(0, 0, out.cols, out.rows);
  const float maxv = static_cast<float>(std::numeric_limits<T>::max());
  for (int y = r.y; y < r.y + r.height; ++y) {
    const float* a = alpha.ptr<float>(y - tl.y) + (r.x - tl.x);
    const float* c = premul.ptr<float>(y - tl.y) + (r.x - tl.x) * CN;
    T* o = out.ptr<T>(y) + r.x * CN;
    for (int x = 0; x < r.width; ++x) {
      if (a[x] <= 0.0f) continue;
      for (int k = 0; k < CN; ++k) {
        const float v = static_cast<float>(o[x * CN + k]) * (1.0f - a[x]) + c[x * CN + k];
        o[x * CN + k] = static_cast<T>(std::min(std::max(v, 0.0f), maxv) + 0.5f);
      }
    }
  }
}

}  // namespace

void SceneGenerator::renderFrame(int i, cv::Mat& out, FrameTruth* truth) {
  Impl& m = *impl_;
  checkIndex(i, m.frames);
  const double t = i / m.fps;
  const cv::Point2d cam = m.cameraAt(t);
  // 1. Scenery: the camera window over the panorama (sub-pixel, fixed-point bilinear).
  shiftCrop(m.pano, m.base.x + cam.x, m.base.y + cam.y, cv::Size(m.W, m.H), out);
  // 2. Obstacles far to near, then occluding clouds.
  m.computeObjects(i);
  if (m.mono16)
    m.composite<std::uint16_t, 1>(out);
  else
    m.composite<std::uint8_t, 3>(out);
  for (const auto& oc : m.occluders) {
    if (m.mono16)
      compositeOccluders<std::uint16_t, 1>(out, oc.premul, oc.alpha, oc.topLeft(t, cam));
    else
      compositeOccluders<std::uint8_t, 3>(out, oc.premul, oc.alpha, oc.topLeft(t, cam));
  }
  // 3. Camera motion blur (jerks).
  const cv::Point2f bv = m.blurAt(i);
  if (bv.x != 0.0f || bv.y != 0.0f) directionalBlur(out, bv.x, bv.y, m.blur_scratch);
  // 4. Illumination change: smooth dimming and recovery, slightly warmer when dim.
  if (m.flags.illumination) {
    const double D = m.duration;
    const double dim = smooth01(0.2 * D, 0.4 * D, t) - smooth01(0.6 * D, 0.75 * D, t);
    const double bright = smooth01(0.8 * D, 0.87 * D, t) - smooth01(0.9 * D, 0.97 * D, t);
    const double g = 1.0 - 0.5 * dim + 0.2 * bright;
    if (m.mono16) {
      // Thermal: gain / offset drift of the camera's automatic gain control around 5000 counts.
      const std::int64_t gq = static_cast<std::int64_t>(std::floor(g * 4096.0 + 0.5));
      for (int y = 0; y < m.H; ++y) {
        std::uint16_t* p = out.ptr<std::uint16_t>(y);
        for (int x = 0; x < m.W; ++x) {
          const std::int64_t v = 5000 + (((static_cast<std::int64_t>(p[x]) - 5000) * gq + 2048) >> 12);
          p[x] = static_cast<std::uint16_t>(std::min<std::int64_t>(std::max<std::int64_t>(v, 0), 65535));
        }
      }
    } else {
      cv::Mat lut(1, 256, CV_8UC3);
      const double gc[3] = {g * (1.0 - 0.08 * dim), g, g * (1.0 + 0.04 * dim)};
      for (int v = 0; v < 256; ++v)
        for (int k = 0; k < 3; ++k) {
          const double x = std::floor(v * gc[k] + 0.5);
          lut.at<cv::Vec3b>(0, v)[k] = static_cast<std::uint8_t>(std::min(255.0, std::max(0.0, x)));
        }
      cv::LUT(out, lut, out);
    }
  }
  // 5. Sensor noise: temporal (table read at a per-frame offset) + column fixed pattern.
  if (!m.noise.empty() || !m.fpn.empty()) {
    const int cn = m.mono16 ? 1 : 3;
    const std::size_t npx = static_cast<std::size_t>(m.W) * static_cast<std::size_t>(m.H) * static_cast<std::size_t>(cn);
    const std::size_t off = m.noise.empty() ? 0 : static_cast<std::size_t>(hashCombine(m.cfg.seed, 20, static_cast<std::uint64_t>(i)) % npx);
    const int rowlen = m.W * cn;
    for (int y = 0; y < m.H; ++y) {
      const std::int16_t* nz = m.noise.empty() ? nullptr : &m.noise[off + static_cast<std::size_t>(y) * static_cast<std::size_t>(rowlen)];
      const std::int16_t* fp = m.fpn.empty() ? nullptr : m.fpn.data();
      if (m.mono16) {
        std::uint16_t* p = out.ptr<std::uint16_t>(y);
        for (int x = 0; x < rowlen; ++x) {
          const int v = static_cast<int>(p[x]) + (nz ? nz[x] : 0) + (fp ? fp[x] : 0);
          p[x] = static_cast<std::uint16_t>(std::min(std::max(v, 0), 65535));
        }
      } else {
        std::uint8_t* p = out.ptr<std::uint8_t>(y);
        for (int x = 0; x < rowlen; ++x) {
          const int v = static_cast<int>(p[x]) + (nz ? nz[x] : 0) + (fp ? fp[x] : 0);
          p[x] = static_cast<std::uint8_t>(std::min(std::max(v, 0), 255));
        }
      }
    }
  }
  // 6. On-screen display (drawn by the camera after the sensor: crisp, no noise).
  if (m.flags.overlay) {
    const cv::Scalar col = m.mono16 ? cv::Scalar(15500) : cv::Scalar(245, 245, 245);
    const int lt = m.mono16 ? cv::LINE_8 : cv::LINE_AA;
    const double fs = 0.45 * m.H / 480.0;
    const int th = std::max(1, static_cast<int>(m.H / 480.0 + 0.5));
    const int tsec = static_cast<int>(std::floor(t));
    const int ms = static_cast<int>(std::floor((t - tsec) * 1000.0));
    char buf[128];
    std::snprintf(buf, sizeof(buf), "2026-06-14  10:%02d:%02d.%03d", (32 + tsec / 60) % 60, (5 + tsec) % 60, ms);
    cv::putText(out, buf, cv::Point(static_cast<int>(0.02 * m.W), static_cast<int>(0.06 * m.H)), cv::FONT_HERSHEY_SIMPLEX, fs, col, th, lt);
    std::snprintf(buf, sizeof(buf), "AZ %06.2f  EL %+05.2f", 123.4 + 0.8 * detSin(0.3 * t), 4.2 + 0.3 * detSin(0.2 * t));
    cv::putText(out, buf, cv::Point(static_cast<int>(0.62 * m.W), static_cast<int>(0.06 * m.H)), cv::FONT_HERSHEY_SIMPLEX, fs, col, th, lt);
    std::snprintf(buf, sizeof(buf), "FOV 12.0x9.6  IR WH  NUC");
    cv::putText(out, buf, cv::Point(static_cast<int>(0.02 * m.W), static_cast<int>(0.96 * m.H)), cv::FONT_HERSHEY_SIMPLEX, fs, col, th, lt);
    std::snprintf(buf, sizeof(buf), "#%06d", i);
    cv::putText(out, buf, cv::Point(static_cast<int>(0.8 * m.W), static_cast<int>(0.96 * m.H)), cv::FONT_HERSHEY_SIMPLEX, fs, col, th, lt);
    // Reticle: centre cross with a gap and corner brackets.
    const int cx = m.W / 2, cy = m.H / 2, g = std::max(2, m.H / 60), l = std::max(4, m.H / 20);
    cv::line(out, {cx - g - l, cy}, {cx - g, cy}, col, th, lt);
    cv::line(out, {cx + g, cy}, {cx + g + l, cy}, col, th, lt);
    cv::line(out, {cx, cy - g - l}, {cx, cy - g}, col, th, lt);
    cv::line(out, {cx, cy + g}, {cx, cy + g + l}, col, th, lt);
    const int bw = m.W / 8, bh = m.H / 8, bl = std::max(3, m.H / 30);
    for (int sx : {-1, 1})
      for (int sy : {-1, 1}) {
        const cv::Point c(cx + sx * bw, cy + sy * bh);
        cv::line(out, c, c - cv::Point(sx * bl, 0), col, th, lt);
        cv::line(out, c, c - cv::Point(0, sy * bl), col, th, lt);
      }
  }
  if (truth) {
    truth->frame = i;
    truth->time = t;
    truth->obstacles.clear();
    for (const auto& ro : m.objs) truth->obstacles.push_back(ro.truth);
  }
}

FrameTruth SceneGenerator::truth(int i) {
  Impl& m = *impl_;
  checkIndex(i, m.frames);
  m.computeObjects(i);
  FrameTruth ft;
  ft.frame = i;
  ft.time = i / m.fps;
  for (const auto& ro : m.objs) ft.obstacles.push_back(ro.truth);
  return ft;
}

void SceneGenerator::renderObstacleMask(int i, int id, cv::Mat& mask) {
  Impl& m = *impl_;
  checkIndex(i, m.frames);
  m.computeObjects(i);
  mask.create(m.H, m.W, CV_8UC1);
  mask.setTo(0);
  for (const auto& ro : m.objs) {
    if (ro.truth.id != id || ro.total <= 0.0) continue;
    const cv::Rect in = ro.patch & cv::Rect(0, 0, m.W, m.H);
    for (int y = in.y; y < in.y + in.height; ++y) {
      const float* ar = ro.a.ptr<float>(y - ro.patch.y) + (in.x - ro.patch.x);
      std::uint8_t* o = mask.ptr<std::uint8_t>(y) + in.x;
      for (int c = 0; c < in.width; ++c) {
        const float a = ar[c];
        if (a < 0.5f / 255.0f) continue;
        o[c] = static_cast<std::uint8_t>(std::min(255.0f, std::max(1.0f, std::floor(a * 255.0f + 0.5f))));
      }
    }
  }
  // The frame's camera blur spreads the shape: the support is the union over the offsets.
  const cv::Point2f bv = m.blurAt(i);
  const auto off = directionalBlurOffsets(bv.x, bv.y);
  if (off.size() > 1) {
    mask.copyTo(m.mask_tmp);
    for (int y = 0; y < m.H; ++y) {
      std::uint8_t* o = mask.ptr<std::uint8_t>(y);
      for (int x = 0; x < m.W; ++x) {
        std::uint8_t v = 0;
        for (const auto& d : off) {
          const int sx = std::min(std::max(x - d.x, 0), m.W - 1), sy = std::min(std::max(y - d.y, 0), m.H - 1);
          v = std::max(v, m.mask_tmp.ptr<std::uint8_t>(sy)[sx]);
        }
        o[x] = v;
      }
    }
  }
}

SceneGenerator makeScenario(const std::string& name, std::uint64_t seed, int frames, cv::Size size, bool mono16, double fps) {
  ScenarioConfig c;
  c.name = name;
  c.seed = seed;
  c.frames = frames;
  c.size = size;
  c.mono16 = mono16;
  c.fps = fps;
  return SceneGenerator(c);
}

}  // namespace scene
}  // namespace obstacle_tracker
