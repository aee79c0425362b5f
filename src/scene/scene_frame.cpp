// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The frames: obstacles composed far to near over the camera window of the panorama, clouds in
// front, then what the camera adds (motion blur, exposure changes, sensor noise, on-screen
// display); and the ground truth measured from the same drawing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/scene/raster.h"
#include "scene_generator_impl.h"

namespace obstacle_tracker {
namespace scene {

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

// illumination: smooth dimming and recovery, slightly warmer when dim.
void SceneGenerator::Impl::changeIllumination(cv::Mat& out, double t) const {
  const double D = duration;
  const double dim = smooth01(0.2 * D, 0.4 * D, t) - smooth01(0.6 * D, 0.75 * D, t);
  const double bright = smooth01(0.8 * D, 0.87 * D, t) - smooth01(0.9 * D, 0.97 * D, t);
  const double g = 1.0 - 0.5 * dim + 0.2 * bright;
  if (mono16) {
    // Thermal: gain / offset drift of the camera's automatic gain control around 5000 counts.
    const std::int64_t gq = static_cast<std::int64_t>(std::floor(g * 4096.0 + 0.5));
    for (int y = 0; y < H; ++y) {
      std::uint16_t* p = out.ptr<std::uint16_t>(y);
      for (int x = 0; x < W; ++x) {
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

// Temporal noise (the table read at a per-frame offset) + column fixed pattern.
void SceneGenerator::Impl::addSensorNoise(cv::Mat& out, int i) const {
  const int cn = mono16 ? 1 : 3;
  const std::size_t npx = static_cast<std::size_t>(W) * static_cast<std::size_t>(H) * static_cast<std::size_t>(cn);
  const std::size_t off = noise.empty() ? 0 : static_cast<std::size_t>(hashCombine(cfg.seed, 20, static_cast<std::uint64_t>(i)) % npx);
  const int rowlen = W * cn;
  for (int y = 0; y < H; ++y) {
    const std::int16_t* nz = noise.empty() ? nullptr : &noise[off + static_cast<std::size_t>(y) * static_cast<std::size_t>(rowlen)];
    const std::int16_t* fp = fpn.empty() ? nullptr : fpn.data();
    if (mono16) {
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

// overlay: drawn by the camera after the sensor, so crisp and without noise.
void SceneGenerator::Impl::drawOverlay(cv::Mat& out, int i, double t) const {
  const cv::Scalar col = mono16 ? cv::Scalar(15500) : cv::Scalar(245, 245, 245);
  const int lt = mono16 ? cv::LINE_8 : cv::LINE_AA;
  const double fs = 0.45 * H / 480.0;
  const int th = std::max(1, static_cast<int>(H / 480.0 + 0.5));
  const int tsec = static_cast<int>(std::floor(t));
  const int ms = static_cast<int>(std::floor((t - tsec) * 1000.0));
  char buf[128];
  std::snprintf(buf, sizeof(buf), "2026-06-14  10:%02d:%02d.%03d", (32 + tsec / 60) % 60, (5 + tsec) % 60, ms);
  cv::putText(out, buf, cv::Point(static_cast<int>(0.02 * W), static_cast<int>(0.06 * H)), cv::FONT_HERSHEY_SIMPLEX, fs, col, th, lt);
  std::snprintf(buf, sizeof(buf), "AZ %06.2f  EL %+05.2f", 123.4 + 0.8 * detSin(0.3 * t), 4.2 + 0.3 * detSin(0.2 * t));
  cv::putText(out, buf, cv::Point(static_cast<int>(0.62 * W), static_cast<int>(0.06 * H)), cv::FONT_HERSHEY_SIMPLEX, fs, col, th, lt);
  std::snprintf(buf, sizeof(buf), "FOV 12.0x9.6  IR WH  NUC");
  cv::putText(out, buf, cv::Point(static_cast<int>(0.02 * W), static_cast<int>(0.96 * H)), cv::FONT_HERSHEY_SIMPLEX, fs, col, th, lt);
  std::snprintf(buf, sizeof(buf), "#%06d", i);
  cv::putText(out, buf, cv::Point(static_cast<int>(0.8 * W), static_cast<int>(0.96 * H)), cv::FONT_HERSHEY_SIMPLEX, fs, col, th, lt);
  // Reticle: centre cross with a gap and corner brackets.
  const int cx = W / 2, cy = H / 2, g = std::max(2, H / 60), l = std::max(4, H / 20);
  cv::line(out, {cx - g - l, cy}, {cx - g, cy}, col, th, lt);
  cv::line(out, {cx + g, cy}, {cx + g + l, cy}, col, th, lt);
  cv::line(out, {cx, cy - g - l}, {cx, cy - g}, col, th, lt);
  cv::line(out, {cx, cy + g}, {cx, cy + g + l}, col, th, lt);
  const int bw = W / 8, bh = H / 8, bl = std::max(3, H / 30);
  for (int sx : {-1, 1})
    for (int sy : {-1, 1}) {
      const cv::Point c(cx + sx * bw, cy + sy * bh);
      cv::line(out, c, c - cv::Point(sx * bl, 0), col, th, lt);
      cv::line(out, c, c - cv::Point(0, sy * bl), col, th, lt);
    }
}

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
  // 4. Illumination change.
  if (m.flags.illumination) m.changeIllumination(out, t);
  // 5. Sensor noise.
  if (!m.noise.empty() || !m.fpn.empty()) m.addSensorNoise(out, i);
  // 6. On-screen display.
  if (m.flags.overlay) m.drawOverlay(out, i, t);
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

}  // namespace scene
}  // namespace obstacle_tracker
