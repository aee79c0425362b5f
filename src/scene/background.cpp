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

// Colour (BGR, 0..255) and thermal counts of one panorama pixel: every layer sets or blends both,
// and the output type picks one of them at the end.
struct Shade {
  V3 colour;
  float thermal;
};

struct NoiseFields {
  cv::Mat clouds;  // starts 4 rows above the panorama (its row y + 4 is panorama row y) so each
                   // pixel can compare with the cloud 4 rows higher: lit tops
  cv::Mat fine;    // fine texture of ground, trees and walls
  cv::Mat fields;  // wide, flat patches of the ground
};

// Everything the pixel pass reads, prepared once per panorama.
struct Scenery {
  float fh;         // frame height, at least 8: the scale of every feature
  float hy;         // horizon row
  Palette pal;
  NoiseFields noise;
  std::vector<float> hill_top, tree_top;  // per column: the row where hills / trees begin
  std::vector<Building> buildings;
  cv::Mat mast_cov;  // CV_32FC1 coverage of the mast, empty without one
  float c_lo, c_hi;  // cloud density ramps from 0 to 1 between these noise values
  cv::Point2f sun;
  float glare, sun_r;  // glare strength, sun disc radius in pixels
};

// Values shared by one panorama row.
struct SceneryRow {
  float fy;      // row centre
  V3 sky;        // sky colour without clouds
  float sky_th;  // sky thermal counts without clouds
  const float* cl;     // cloud noise at this row
  const float* cl_up;  // cloud noise 4 rows above (lit cloud tops)
  const float* fn;     // fine texture
  const float* field;  // ground fields
  const float* mc;     // mast coverage, null without a mast
};

// Noise fields: clouds (anisotropic, large), and a fine texture for ground and trees.
NoiseFields makeNoiseFields(const BackgroundSpec& spec, float fh) {
  const int W = spec.size.width, H = spec.size.height;
  NoiseFields nf{cv::Mat(H + 4, W, CV_32FC1), cv::Mat(H, W, CV_32FC1), cv::Mat(H, W, CV_32FC1)};
  const float cell = 0.45f * fh * spec.cloud_scale;
  fractalNoise(nf.clouds, 2.2f * cell, cell, 6, 0.52f, hashCombine(spec.seed, 11), cv::Point2f(0, -4));
  fractalNoise(nf.fine, std::max(2.0f, 0.02f * fh), std::max(2.0f, 0.012f * fh), 3, 0.6f, hashCombine(spec.seed, 12));
  fractalNoise(nf.fields, 0.5f * fh, 0.05f * fh, 4, 0.5f, hashCombine(spec.seed, 13));
  // Spread the fractal values (mean 0.5, small spread) so cloud_cover reads as a sky fraction.
  for (int r = 0; r < nf.clouds.rows; ++r) {
    float* p = nf.clouds.ptr<float>(r);
    for (int c = 0; c < W; ++c) p[c] = 0.5f + (p[c] - 0.5f) * 3.0f;
  }
  return nf;
}

// Horizon profile per column, distant hills: the row where they begin.
std::vector<float> traceHills(const BackgroundSpec& spec, float fh) {
  const int W = spec.size.width;
  std::vector<float> hill_top(static_cast<std::size_t>(W));
  const std::uint64_t s_hill = hashCombine(spec.seed, 21);
  for (int x = 0; x < W; ++x) {
    const float fx = static_cast<float>(x);
    hill_top[static_cast<std::size_t>(x)] = spec.horizon_y - 0.06f * fh * fractalNoise1D(fx, 0.9f * fh, 4, 0.5f, s_hill);
  }
  return hill_top;
}

// Horizon profile per column, tree line: the row where the crowns begin (the horizon where a
// slowly varying presence noise leaves a gap, so `trees` sets the share covered).
std::vector<float> traceTreeLine(const BackgroundSpec& spec, float fh) {
  const int W = spec.size.width;
  const float hy = spec.horizon_y;
  std::vector<float> tree_top(static_cast<std::size_t>(W));
  const std::uint64_t s_tree = hashCombine(spec.seed, 22), s_mask = hashCombine(spec.seed, 23);
  for (int x = 0; x < W; ++x) {
    const float fx = static_cast<float>(x);
    const float presence = fractalNoise1D(fx, 0.6f * fh, 3, 0.5f, s_mask);
    const float thr = 1.0f - spec.trees;
    float h = 0.0f;
    if (presence > thr * 0.9f + 0.1f * thr) {
      const float crowns = fractalNoise1D(fx, 0.018f * fh + 2.0f, 3, 0.55f, s_tree);
      h = (0.012f + 0.05f * clamp01((presence - thr) * 4.0f)) * fh * (0.55f + 0.9f * crowns);
    }
    tree_top[static_cast<std::size_t>(x)] = hy - h;
  }
  return tree_top;
}

// Buildings standing on the horizon; draws 6 numbers from rng per building.
std::vector<Building> placeBuildings(const BackgroundSpec& spec, float fh, Rng& rng) {
  const int W = spec.size.width;
  const float hy = spec.horizon_y;
  std::vector<Building> buildings;
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
  return buildings;
}

// Adds the coverage of a straight bar of width w from a to b.
void addBarCoverage(cv::Point2f a, cv::Point2f b, float w, cv::Mat& cov) {
  const cv::Point2f d = b - a;
  const float l = std::sqrt(d.x * d.x + d.y * d.y);
  const cv::Point2f n(-d.y / l * 0.5f * w, d.x / l * 0.5f * w);
  const cv::Point2f q[4] = {a + n, b + n, b - n, a - n};
  addPolygonCoverage(q, 4, cv::Point(0, 0), 8, cov);
}

// Lattice mast: a tall thin tapered tower drawn as coverage (anti-aliased), CV_32FC1 0..1.
// Draws 1 number from rng (its column).
cv::Mat drawMastCoverage(const BackgroundSpec& spec, float fh, Rng& rng) {
  const int W = spec.size.width, H = spec.size.height;
  const float hy = spec.horizon_y;
  cv::Mat mast_cov = cv::Mat::zeros(H, W, CV_32FC1);
  const float mx = static_cast<float>(rng.uniform(0.15, 0.85)) * static_cast<float>(W);
  const float top = hy - 0.28f * fh, base_w = 0.02f * fh, top_w = 0.004f * fh + 0.6f;
  const cv::Point2f legs[4] = {{mx - base_w, hy}, {mx - top_w, top}, {mx + top_w, top}, {mx + base_w, hy}};
  // Two legs and cross bracing as thin polygons.
  const float lw = std::max(0.7f, 0.0025f * fh);
  addBarCoverage(legs[0], legs[1], lw, mast_cov);
  addBarCoverage(legs[3], legs[2], lw, mast_cov);
  const int braces = 9;
  for (int k = 0; k < braces; ++k) {
    const float t0 = static_cast<float>(k) / braces, t1 = static_cast<float>(k + 1) / braces;
    const cv::Point2f l0 = legs[0] + (legs[1] - legs[0]) * t0, l1 = legs[0] + (legs[1] - legs[0]) * t1;
    const cv::Point2f r0 = legs[3] + (legs[2] - legs[3]) * t0, r1 = legs[3] + (legs[2] - legs[3]) * t1;
    addBarCoverage(l0, r1, 0.6f * lw, mast_cov);
    addBarCoverage(r0, l1, 0.6f * lw, mast_cov);
  }
  addBarCoverage(cv::Point2f(mx, top), cv::Point2f(mx, top - 0.05f * fh), lw, mast_cov);  // antenna
  // Overlapping bars add up; coverage stops at 1.
  for (int r = 0; r < H; ++r) {
    float* p = mast_cov.ptr<float>(r);
    for (int c = 0; c < W; ++c) p[c] = std::min(p[c], 1.0f);
  }
  return mast_cov;
}

Scenery prepareScenery(const BackgroundSpec& spec) {
  Scenery s{};
  s.fh = std::max(spec.frame_height, 8.0f);
  s.hy = spec.horizon_y;
  s.pal = palette(spec.palette);
  Rng rng(mix64(spec.seed ^ 0xB5C0FBCFEC4D3B2FULL));
  s.noise = makeNoiseFields(spec, s.fh);
  s.hill_top = traceHills(spec, s.fh);
  s.tree_top = traceTreeLine(spec, s.fh);
  // rng is drawn by the buildings first, then by the mast: existing scenes keep their bytes only
  // in this order.
  s.buildings = placeBuildings(spec, s.fh, rng);
  if (spec.mast) s.mast_cov = drawMastCoverage(spec, s.fh, rng);
  const float cover = spec.cloud_cover;
  s.c_lo = 1.0f - cover - 0.12f;
  s.c_hi = 1.0f - cover + 0.18f;
  s.sun = spec.sun;
  s.glare = spec.glare;
  s.sun_r = 0.018f * s.fh + 1.0f;
  return s;
}

// The sky gradient (zenith to horizon over 1.6 frame heights) and the noise rows of row y.
SceneryRow sceneryRow(const Scenery& s, int y) {
  SceneryRow row;
  row.fy = static_cast<float>(y) + 0.5f;
  const float sky_h = 1.6f * s.fh;
  const float t = clamp01((row.fy - (s.hy - sky_h)) / sky_h);
  const float tt = t * std::sqrt(t);
  row.sky = mix(s.pal.zenith, s.pal.horizon, tt);
  row.sky_th = mixf(6100.0f, 7500.0f, tt);
  row.cl = s.noise.clouds.ptr<float>(y + 4);
  row.cl_up = s.noise.clouds.ptr<float>(y);
  row.fn = s.noise.fine.ptr<float>(y);
  row.field = s.noise.fields.ptr<float>(y);
  row.mc = s.mast_cov.empty() ? nullptr : s.mast_cov.ptr<float>(y);
  return row;
}

// Ground: fields (a wide, flat noise), fine texture, haze growing towards the horizon.
Shade shadeGround(const Scenery& s, const SceneryRow& row, int x) {
  const float d = row.fy - s.hy;
  const float haze = 1.0f / (1.0f + d / (0.05f * s.fh));
  const float field = 0.5f + (row.field[x] - 0.5f) * 2.5f;
  V3 c = mix(s.pal.ground_a, s.pal.ground_b, smoothstep(0.35f, 0.65f, field));
  c *= 0.8f + 0.4f * row.fn[x];
  c = mix(c, s.pal.haze, 0.65f * haze);
  return {c, mixf(9300.0f + 900.0f * field + 300.0f * row.fn[x], 8200.0f, 0.5f * haze)};
}

// The building covering (fx, fy), or null; where buildings overlap, the one placed last.
const Building* buildingAt(const std::vector<Building>& buildings, float fx, float fy) {
  const Building* bld = nullptr;
  for (const auto& b : buildings)
    if (fx >= b.x0 && fx < b.x1 && fy >= b.top) bld = &b;
  return bld;
}

// A wall with a grid of dark (thermally warm) windows, no window touching the side edges.
Shade shadeBuilding(const Building& b, const Palette& pal, float fx, float fy, float fine) {
  const float lx = fx - b.x0, ly = fy - b.top;
  const bool window = std::fmod(lx, b.window_gap_x) < b.window_w && std::fmod(ly, b.window_gap_y) < b.window_h &&
                      lx > b.window_w && b.x1 - fx > b.window_w;
  V3 c = b.colour * (window ? 0.45f : (0.9f + 0.15f * fine));
  c = mix(c, pal.haze, 0.25f);
  return {c, b.thermal + (window ? 700.0f : 0.0f)};
}

Shade shadeTrees(const Palette& pal, float fine) {
  V3 c = pal.tree * (0.7f + 0.6f * fine);
  c = mix(c, pal.haze, 0.2f);
  return {c, 9400.0f + 400.0f * fine};
}

// Distant hills: flat, half lost in the haze.
Shade shadeHills(const Palette& pal) { return {mix(pal.hill, pal.haze, 0.45f), 8300.0f}; }

// Sky and clouds: density from the fractal field, lit tops, grey thick bottoms.
Shade shadeSky(const Scenery& s, const SceneryRow& row, int x) {
  const float n = row.cl[x];
  const float dens = smoothstep(s.c_lo, s.c_hi, n) * smoothstep(0.0f, 0.12f * s.fh, s.hy - row.fy + 0.02f * s.fh);
  const float lit = clamp01(0.6f + 2.0f * (n - row.cl_up[x]) + 0.5f * (s.c_hi - n));
  const V3 cloud = mix(s.pal.cloud_shade, s.pal.cloud_lit, lit);
  return {mix(row.sky, cloud, 0.96f * dens), mixf(row.sky_th, 7600.0f + 900.0f * clamp01((n - s.c_lo) * 3.0f), dens)};
}

// What pixel x of the row shows under the mast and the sun: the ground below the horizon;
// above it the nearest of buildings, trees and hills, else the sky.
Shade shadeScenery(const Scenery& s, const SceneryRow& row, int x) {
  if (row.fy >= s.hy) return shadeGround(s, row, x);
  const float fx = static_cast<float>(x) + 0.5f;
  const std::size_t xi = static_cast<std::size_t>(x);
  if (const Building* b = buildingAt(s.buildings, fx, row.fy)) return shadeBuilding(*b, s.pal, fx, row.fy, row.fn[x]);
  if (row.fy >= s.tree_top[xi]) return shadeTrees(s.pal, row.fn[x]);
  if (row.fy >= s.hill_top[xi]) return shadeHills(s.pal);
  return shadeSky(s, row, x);
}

void overlayMast(float coverage, Shade& px) {
  px.colour = mix(px.colour, V3(70, 70, 75), coverage);
  px.thermal = mixf(px.thermal, 10400.0f, coverage);
}

// Sun disc, glare halo and a horizontal lens streak (rational fall-offs, no exp/pow).
void addSunGlare(const Scenery& s, float fx, float fy, Shade& px) {
  const float fh = s.fh;
  const float dx = fx - s.sun.x, dy = fy - s.sun.y;
  const float r2 = (dx * dx + dy * dy) / (fh * fh);
  float g = s.glare * (0.55f / (1.0f + r2 / 0.0016f) + 0.35f / (1.0f + r2 / 0.04f));
  g += s.glare * 0.25f / (1.0f + dy * dy / (0.0001f * fh * fh + 1.0f)) / (1.0f + dx * dx / (0.16f * fh * fh));
  if (dx * dx + dy * dy < s.sun_r * s.sun_r) g = std::max(g, 1.2f);
  px.colour = mix(px.colour, V3(235, 248, 255), clamp01(g));
  px.thermal = px.thermal + (16000.0f - px.thermal) * clamp01(g * 0.9f);
}

// Row y of out: the scenery, the mast over it, the sun's glare over both.
void renderRow(const Scenery& s, int y, bool mono16, cv::Mat& out) {
  const SceneryRow row = sceneryRow(s, y);
  cv::Vec3b* o8 = mono16 ? nullptr : out.ptr<cv::Vec3b>(y);
  std::uint16_t* o16 = mono16 ? out.ptr<std::uint16_t>(y) : nullptr;
  // The width in a local: out.cols would be re-read after every byte store (a char store may alias
  // it).
  const int W = out.cols;
  for (int x = 0; x < W; ++x) {
    Shade px = shadeScenery(s, row, x);
    if (row.mc && row.mc[x] > 0.0f) overlayMast(row.mc[x], px);
    addSunGlare(s, static_cast<float>(x) + 0.5f, row.fy, px);
    if (mono16) {
      const float v = std::min(std::max(px.thermal, 0.0f), 65535.0f);
      o16[x] = static_cast<std::uint16_t>(v + 0.5f);
    } else {
      for (int k = 0; k < 3; ++k)
        o8[x][k] = static_cast<std::uint8_t>(std::min(std::max(px.colour[k], 0.0f), 255.0f) + 0.5f);
    }
  }
}

}  // namespace

void renderBackground(const BackgroundSpec& spec, bool mono16, cv::Mat& out) {
  CV_Assert(spec.size.width > 0 && spec.size.height > 0);
  const Scenery s = prepareScenery(spec);
  out.create(spec.size.height, spec.size.width, mono16 ? CV_16UC1 : CV_8UC3);
  for (int y = 0; y < out.rows; ++y) renderRow(s, y, mono16, out);
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
