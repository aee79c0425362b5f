// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/scene/background.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "obstacle_tracker/scene/random.h"
#include "obstacle_tracker/scene/raster.h"

namespace obstacle_tracker {
namespace scene {

namespace {

using V3 = cv::Vec3f;

inline V3 mix(const V3& a, const V3& b, float t) { return a + (b - a) * t; }
inline float mixf(float a, float b, float t) { return a + (b - a) * t; }

struct Palette {
  V3 zenith, horizon, cloud_lit, cloud_shade, hill, tree, ground_a, ground_b, haze;
};

Palette palette(int k) {
  switch (k) {
    case 1:  // hazy
      return {V3(200, 170, 140), V3(215, 212, 205), V3(238, 238, 236), V3(170, 172, 176), V3(150, 150, 140),
              V3(55, 80, 60), V3(70, 110, 100), V3(80, 115, 125), V3(205, 205, 200)};
    case 2:  // late afternoon
      return {V3(185, 130, 85), V3(170, 205, 235), V3(215, 235, 250), V3(140, 150, 170), V3(120, 125, 130),
              V3(35, 60, 50), V3(50, 95, 110), V3(60, 100, 130), V3(165, 195, 220)};
    default:  // clear blue
      return {V3(205, 135, 70), V3(235, 215, 190), V3(248, 248, 248), V3(180, 178, 182), V3(140, 135, 120),
              V3(40, 75, 45), V3(60, 120, 90), V3(70, 110, 120), V3(225, 215, 200)};
  }
}

struct Building {
  float x0, x1, top;  // columns, roof row
  V3 colour;
  float thermal;
  float window_w, window_h, window_gap_x, window_gap_y;
};

}  // namespace

void renderBackground(const BackgroundSpec& spec, bool mono16, cv::Mat& out) {
  const int W = spec.size.width, H = spec.size.height;
  CV_Assert(W > 0 && H > 0);
  const float fh = std::max(spec.frame_height, 8.0f);
  const Palette pal = palette(spec.palette);
  Rng rng(mix64(spec.seed ^ 0xB5C0FBCFEC4D3B2FULL));

  // Noise fields: clouds (anisotropic, large), and a fine texture for ground and trees.
  cv::Mat clouds(H + 4, W, CV_32FC1), fine(H, W, CV_32FC1), fields(H, W, CV_32FC1);
  const float cell = 0.45f * fh * spec.cloud_scale;
  fractalNoise(clouds, 2.2f * cell, cell, 6, 0.52f, hashCombine(spec.seed, 11), cv::Point2f(0, -4));
  fractalNoise(fine, std::max(2.0f, 0.02f * fh), std::max(2.0f, 0.012f * fh), 3, 0.6f, hashCombine(spec.seed, 12));
  fractalNoise(fields, 0.5f * fh, 0.05f * fh, 4, 0.5f, hashCombine(spec.seed, 13));
  // Spread the fractal values (mean 0.5, small spread) so cloud_cover reads as a sky fraction.
  for (int r = 0; r < clouds.rows; ++r) {
    float* p = clouds.ptr<float>(r);
    for (int c = 0; c < W; ++c) p[c] = 0.5f + (p[c] - 0.5f) * 3.0f;
  }

  const float hy = spec.horizon_y;
  // Horizon profile per column: hills, tree line, buildings, mast.
  std::vector<float> hill_top(static_cast<std::size_t>(W)), tree_top(static_cast<std::size_t>(W));
  const std::uint64_t s_hill = hashCombine(spec.seed, 21), s_tree = hashCombine(spec.seed, 22),
                      s_mask = hashCombine(spec.seed, 23);
  for (int x = 0; x < W; ++x) {
    const float fx = static_cast<float>(x);
    hill_top[static_cast<std::size_t>(x)] = hy - 0.06f * fh * fractalNoise1D(fx, 0.9f * fh, 4, 0.5f, s_hill);
    const float presence = fractalNoise1D(fx, 0.6f * fh, 3, 0.5f, s_mask);
    const float thr = 1.0f - spec.trees;
    float h = 0.0f;
    if (presence > thr * 0.9f + 0.1f * thr) {
      const float crowns = fractalNoise1D(fx, 0.018f * fh + 2.0f, 3, 0.55f, s_tree);
      h = (0.012f + 0.05f * clamp01((presence - thr) * 4.0f)) * fh * (0.55f + 0.9f * crowns);
    }
    tree_top[static_cast<std::size_t>(x)] = hy - h;
  }
  std::vector<Building> buildings;
  {
    const int n = static_cast<int>(spec.buildings * static_cast<float>(W) / (0.12f * fh));
    for (int i = 0; i < n; ++i) {
      Building b;
      const float w = static_cast<float>(rng.uniform(0.03, 0.12)) * fh;
      b.x0 = static_cast<float>(rng.uniform(0.0, W));
      b.x1 = b.x0 + w;
      b.top = hy - static_cast<float>(rng.uniform(0.02, 0.1)) * fh;
      const float g = static_cast<float>(rng.uniform(120, 200));
      b.colour = V3(g * 0.95f, g, g * static_cast<float>(rng.uniform(0.95, 1.1)));
      b.thermal = static_cast<float>(rng.uniform(9800, 10600));
      b.window_w = std::max(1.0f, 0.006f * fh);
      b.window_h = std::max(1.0f, 0.008f * fh);
      b.window_gap_x = b.window_w * 2.2f;
      b.window_gap_y = b.window_h * 2.0f;
      buildings.push_back(b);
    }
  }
  // Lattice mast: a tall thin tapered tower drawn as coverage (anti-aliased).
  cv::Mat mast_cov;
  if (spec.mast) {
    mast_cov = cv::Mat::zeros(H, W, CV_32FC1);
    const float mx = static_cast<float>(rng.uniform(0.15, 0.85)) * static_cast<float>(W);
    const float top = hy - 0.28f * fh, base_w = 0.02f * fh, top_w = 0.004f * fh + 0.6f;
    const cv::Point2f legs[4] = {{mx - base_w, hy}, {mx - top_w, top}, {mx + top_w, top}, {mx + base_w, hy}};
    // Two legs and cross bracing as thin polygons.
    auto bar = [&](cv::Point2f a, cv::Point2f b, float w) {
      const cv::Point2f d = b - a;
      const float l = std::sqrt(d.x * d.x + d.y * d.y);
      const cv::Point2f n(-d.y / l * 0.5f * w, d.x / l * 0.5f * w);
      const cv::Point2f q[4] = {a + n, b + n, b - n, a - n};
      addPolygonCoverage(q, 4, cv::Point(0, 0), 8, mast_cov);
    };
    const float lw = std::max(0.7f, 0.0025f * fh);
    bar(legs[0], legs[1], lw);
    bar(legs[3], legs[2], lw);
    const int braces = 9;
    for (int k = 0; k < braces; ++k) {
      const float t0 = static_cast<float>(k) / braces, t1 = static_cast<float>(k + 1) / braces;
      const cv::Point2f l0 = legs[0] + (legs[1] - legs[0]) * t0, l1 = legs[0] + (legs[1] - legs[0]) * t1;
      const cv::Point2f r0 = legs[3] + (legs[2] - legs[3]) * t0, r1 = legs[3] + (legs[2] - legs[3]) * t1;
      bar(l0, r1, 0.6f * lw);
      bar(r0, l1, 0.6f * lw);
    }
    bar(cv::Point2f(mx, top), cv::Point2f(mx, top - 0.05f * fh), lw);  // antenna
    for (int r = 0; r < H; ++r) {
      float* p = mast_cov.ptr<float>(r);
      for (int c = 0; c < W; ++c) p[c] = std::min(p[c], 1.0f);
    }
  }

  out.create(H, W, mono16 ? CV_16UC1 : CV_8UC3);
  const float sky_h = 1.6f * fh;
  const float glare = spec.glare;
  const float sun_r = 0.018f * fh + 1.0f;
  const float cover = spec.cloud_cover;
  const float c_lo = 1.0f - cover - 0.12f, c_hi = 1.0f - cover + 0.18f;
  for (int y = 0; y < H; ++y) {
    const float fy = static_cast<float>(y) + 0.5f;
    const float t = clamp01((fy - (hy - sky_h)) / sky_h);
    const float tt = t * std::sqrt(t);
    const V3 sky = mix(pal.zenith, pal.horizon, tt);
    const float sky_th = mixf(6100.0f, 7500.0f, tt);
    const float* cl = clouds.ptr<float>(y + 4);
    const float* cl_up = clouds.ptr<float>(y);
    const float* fn = fine.ptr<float>(y);
    const float* mc = spec.mast ? mast_cov.ptr<float>(y) : nullptr;
    cv::Vec3b* o8 = mono16 ? nullptr : out.ptr<cv::Vec3b>(y);
    std::uint16_t* o16 = mono16 ? out.ptr<std::uint16_t>(y) : nullptr;
    for (int x = 0; x < W; ++x) {
      const float fx = static_cast<float>(x) + 0.5f;
      V3 c;
      float th;
      if (fy >= hy) {
        // Ground: fields from the cloud field reused at another place, fine texture, haze.
        const float d = fy - hy;
        const float haze = 1.0f / (1.0f + d / (0.05f * fh));
        const float field = 0.5f + (fields.ptr<float>(y)[x] - 0.5f) * 2.5f;
        c = mix(pal.ground_a, pal.ground_b, smoothstep(0.35f, 0.65f, field));
        c *= 0.8f + 0.4f * fn[x];
        c = mix(c, pal.haze, 0.65f * haze);
        th = mixf(9300.0f + 900.0f * field + 300.0f * fn[x], 8200.0f, 0.5f * haze);
      } else {
        const std::size_t xi = static_cast<std::size_t>(x);
        const Building* bld = nullptr;
        for (const auto& b : buildings)
          if (fx >= b.x0 && fx < b.x1 && fy >= b.top) bld = &b;
        if (bld) {
          const float lx = fx - bld->x0, ly = fy - bld->top;
          const bool window = std::fmod(lx, bld->window_gap_x) < bld->window_w && std::fmod(ly, bld->window_gap_y) < bld->window_h &&
                              lx > bld->window_w && bld->x1 - fx > bld->window_w;
          c = bld->colour * (window ? 0.45f : (0.9f + 0.15f * fn[x]));
          c = mix(c, pal.haze, 0.25f);
          th = bld->thermal + (window ? 700.0f : 0.0f);
        } else if (fy >= tree_top[xi]) {
          c = pal.tree * (0.7f + 0.6f * fn[x]);
          c = mix(c, pal.haze, 0.2f);
          th = 9400.0f + 400.0f * fn[x];
        } else if (fy >= hill_top[xi]) {
          c = mix(pal.hill, pal.haze, 0.45f);
          th = 8300.0f;
        } else {
          // Sky and clouds: density from the fractal field, lit tops, grey thick bottoms.
          const float n = cl[x];
          const float dens = smoothstep(c_lo, c_hi, n) * smoothstep(0.0f, 0.12f * fh, hy - fy + 0.02f * fh);
          const float lit = clamp01(0.6f + 2.0f * (n - cl_up[x]) + 0.5f * (c_hi - n));
          const V3 cloud = mix(pal.cloud_shade, pal.cloud_lit, lit);
          c = mix(sky, cloud, 0.96f * dens);
          th = mixf(sky_th, 7600.0f + 900.0f * clamp01((n - c_lo) * 3.0f), dens);
        }
      }
      if (mc && mc[x] > 0.0f) {
        c = mix(c, V3(70, 70, 75), mc[x]);
        th = mixf(th, 10400.0f, mc[x]);
      }
      // Sun disc, glare halo and a horizontal lens streak (rational fall-offs, no exp/pow).
      const float dx = fx - spec.sun.x, dy = fy - spec.sun.y;
      const float r2 = (dx * dx + dy * dy) / (fh * fh);
      float g = glare * (0.55f / (1.0f + r2 / 0.0016f) + 0.35f / (1.0f + r2 / 0.04f));
      g += glare * 0.25f / (1.0f + dy * dy / (0.0001f * fh * fh + 1.0f)) / (1.0f + dx * dx / (0.16f * fh * fh));
      if (dx * dx + dy * dy < sun_r * sun_r) g = std::max(g, 1.2f);
      c = mix(c, V3(235, 248, 255), clamp01(g));
      th = th + (16000.0f - th) * clamp01(g * 0.9f);
      if (mono16) {
        const float v = std::min(std::max(th, 0.0f), 65535.0f);
        o16[x] = static_cast<std::uint16_t>(v + 0.5f);
      } else {
        for (int k = 0; k < 3; ++k) o8[x][k] = static_cast<std::uint8_t>(std::min(std::max(c[k], 0.0f), 255.0f) + 0.5f);
      }
    }
  }
}

void renderCloudSprite(cv::Size size, std::uint64_t seed, bool mono16, cv::Mat& premultiplied, cv::Mat& alpha) {
  const int W = std::max(size.width, 4), H = std::max(size.height, 4);
  cv::Mat n(H, W, CV_32FC1), n_up(H, W, CV_32FC1);
  const float cell = 0.35f * static_cast<float>(std::min(W, H));
  fractalNoise(n, cell * 1.3f, cell, 5, 0.55f, hashCombine(seed, 31));
  fractalNoise(n_up, cell * 1.3f, cell, 5, 0.55f, hashCombine(seed, 31), cv::Point2f(0, -3));
  alpha.create(H, W, CV_32FC1);
  premultiplied.create(H, W, mono16 ? CV_32FC1 : CV_32FC3);
  const float cx = 0.5f * W, cy = 0.5f * H;
  for (int y = 0; y < H; ++y) {
    const float* np = n.ptr<float>(y);
    const float* nu = n_up.ptr<float>(y);
    float* a = alpha.ptr<float>(y);
    for (int x = 0; x < W; ++x) {
      const float dx = (static_cast<float>(x) + 0.5f - cx) / cx, dy = (static_cast<float>(y) + 0.5f - cy) / cy;
      const float r2 = dx * dx + dy * dy;
      const float env = 1.0f - r2;  // 1 at the centre, 0 at the ellipse border
      // Opaque where the envelope is strong (the core), ragged fractal edges outside it.
      const float v = clamp01((env * 1.6f + (np[x] - 0.5f) * 1.2f) * 1.8f);
      a[x] = v * v * (3.0f - 2.0f * v);
      const float lit = clamp01(0.6f + 5.0f * (np[x] - nu[x]) - 0.3f * dy);
      if (mono16) {
        premultiplied.ptr<float>(y)[x] = a[x] * (7900.0f + 500.0f * np[x]);
      } else {
        const cv::Vec3f col = cv::Vec3f(176, 176, 180) + (cv::Vec3f(246, 246, 246) - cv::Vec3f(176, 176, 180)) * lit;
        premultiplied.ptr<cv::Vec3f>(y)[x] = col * a[x];
      }
    }
  }
}

}  // namespace scene
}  // namespace obstacle_tracker
