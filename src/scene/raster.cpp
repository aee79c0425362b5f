// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/scene/raster.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "obstacle_tracker/scene/random.h"

namespace obstacle_tracker {
namespace scene {

double detSin(double x) {
  const double two_pi = 2.0 * kPi;
  double r = x - std::floor(x / two_pi + 0.5) * two_pi;  // [-pi, pi]
  if (r > 0.5 * kPi) r = kPi - r;
  if (r < -0.5 * kPi) r = -kPi - r;
  const double r2 = r * r;
  // Horner form of the Taylor series up to r^17.
  double p = 1.0 / 355687428096000.0;           // 1/17!
  p = p * r2 - 1.0 / 1307674368000.0;           // 1/15!
  p = p * r2 + 1.0 / 6227020800.0;              // 1/13!
  p = p * r2 - 1.0 / 39916800.0;                // 1/11!
  p = p * r2 + 1.0 / 362880.0;                  // 1/9!
  p = p * r2 - 1.0 / 5040.0;                    // 1/7!
  p = p * r2 + 1.0 / 120.0;                     // 1/5!
  p = p * r2 - 1.0 / 6.0;                       // 1/3!
  p = p * r2 + 1.0;
  return r * p;
}

double detCos(double x) { return detSin(x + 0.5 * kPi); }

std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 0x100000001B3ULL;
  }
  return h;
}

int subrowsForHeight(float height_px) {
  if (height_px < 24.0f) return 16;
  if (height_px < 96.0f) return 8;
  return 4;
}

void addPolygonCoverage(const cv::Point2f* pts, int n, cv::Point origin, int subrows, cv::Mat& cov) {
  if (n < 3 || cov.empty()) return;
  CV_Assert(cov.type() == CV_32FC1);
  if (subrows < 1) subrows = 1;
  float ymin = pts[0].y, ymax = pts[0].y;
  for (int i = 1; i < n; ++i) {
    ymin = std::min(ymin, pts[i].y);
    ymax = std::max(ymax, pts[i].y);
  }
  const int rows = cov.rows, cols = cov.cols;
  int r0 = static_cast<int>(std::floor(ymin)) - origin.y;
  int r1 = static_cast<int>(std::ceil(ymax)) - origin.y;  // exclusive
  r0 = std::max(r0, 0);
  r1 = std::min(r1, rows);
  const float w = 1.0f / static_cast<float>(subrows);
  const float fx0 = static_cast<float>(origin.x);
  // Crossings per sub-scanline: (x, direction). A polygon crosses a line at most n times.
  thread_local std::vector<std::pair<float, int>> xs;
  xs.resize(static_cast<std::size_t>(n));
  for (int r = r0; r < r1; ++r) {
    float* row = cov.ptr<float>(r);
    for (int s = 0; s < subrows; ++s) {
      const float ys = static_cast<float>(r + origin.y) + (static_cast<float>(s) + 0.5f) * w;
      int m = 0;
      for (int i = 0; i < n; ++i) {
        const cv::Point2f& a = pts[i];
        const cv::Point2f& b = pts[(i + 1) % n];
        if (a.y == b.y) continue;
        const bool up = b.y > a.y;
        const float lo = up ? a.y : b.y, hi = up ? b.y : a.y;
        if (ys < lo || ys >= hi) continue;
        const float x = a.x + (ys - a.y) * (b.x - a.x) / (b.y - a.y);
        xs[m++] = {x - fx0, up ? 1 : -1};
      }
      if (m < 2) continue;
      // Insertion sort (few crossings); ties keep a deterministic order.
      for (int i = 1; i < m; ++i) {
        auto v = xs[i];
        int j = i - 1;
        while (j >= 0 && (xs[j].first > v.first || (xs[j].first == v.first && xs[j].second > v.second))) {
          xs[j + 1] = xs[j];
          --j;
        }
        xs[j + 1] = v;
      }
      int winding = 0;
      for (int i = 0; i + 1 < m; ++i) {
        winding += xs[i].second;
        if (winding == 0) continue;
        float xa = xs[i].first, xb = xs[i + 1].first;
        if (xb <= 0.0f || xa >= static_cast<float>(cols) || xb <= xa) continue;
        xa = std::max(xa, 0.0f);
        xb = std::min(xb, static_cast<float>(cols));
        const int ia = static_cast<int>(xa), ib = static_cast<int>(xb);
        if (ia == ib) {
          row[ia] += (xb - xa) * w;
        } else {
          row[ia] += (static_cast<float>(ia + 1) - xa) * w;
          for (int c = ia + 1; c < ib; ++c) row[c] += w;
          if (ib < cols) row[ib] += (xb - static_cast<float>(ib)) * w;
        }
      }
    }
  }
}

namespace {

inline float lattice(std::uint64_t seed, int ix, int iy) {
  const std::uint64_t h = mix64(seed ^ (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix)) *
                                       0x9E3779B97F4A7C15ULL) ^
                                (static_cast<std::uint64_t>(static_cast<std::uint32_t>(iy)) * 0xC2B2AE3D27D4EB4FULL));
  return unitFloat(h);
}

inline float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

}  // namespace

void fractalNoise(cv::Mat& out, float cell_x, float cell_y, int octaves, float gain, std::uint64_t seed,
                  cv::Point2f origin) {
  CV_Assert(!out.empty() && out.type() == CV_32FC1);
  if (cell_x <= 0.0f || cell_y <= 0.0f || octaves < 1) throw std::invalid_argument("fractalNoise: bad cell or octaves");
  out.setTo(0.0f);
  float amp = 1.0f, total = 0.0f;
  std::vector<float> fx(static_cast<std::size_t>(out.cols));
  std::vector<int> ix(static_cast<std::size_t>(out.cols));
  std::vector<float> grid;
  for (int o = 0; o < octaves; ++o) {
    const std::uint64_t oseed = mix64(seed + static_cast<std::uint64_t>(o) * 0x51ED270B27A5C0A1ULL);
    const float cx = cell_x, cy = cell_y;
    // Lattice window needed for this octave.
    const int gx0 = static_cast<int>(std::floor(origin.x / cx));
    const int gy0 = static_cast<int>(std::floor(origin.y / cy));
    const int gx1 = static_cast<int>(std::floor((origin.x + static_cast<float>(out.cols)) / cx)) + 2;
    const int gy1 = static_cast<int>(std::floor((origin.y + static_cast<float>(out.rows)) / cy)) + 2;
    const int gw = gx1 - gx0 + 1, gh = gy1 - gy0 + 1;
    grid.resize(static_cast<std::size_t>(gw) * static_cast<std::size_t>(gh));
    for (int j = 0; j < gh; ++j)
      for (int i = 0; i < gw; ++i) grid[static_cast<std::size_t>(j * gw + i)] = lattice(oseed, gx0 + i, gy0 + j);
    for (int c = 0; c < out.cols; ++c) {
      const float x = (origin.x + static_cast<float>(c) + 0.5f) / cx;
      const float f = std::floor(x);
      ix[static_cast<std::size_t>(c)] = static_cast<int>(f) - gx0;
      fx[static_cast<std::size_t>(c)] = fade(x - f);
    }
    for (int r = 0; r < out.rows; ++r) {
      const float y = (origin.y + static_cast<float>(r) + 0.5f) / cy;
      const float fy0 = std::floor(y);
      const int iy = static_cast<int>(fy0) - gy0;
      const float ty = fade(y - fy0);
      const float* g0 = &grid[static_cast<std::size_t>(iy * gw)];
      const float* g1 = g0 + gw;
      float* o_row = out.ptr<float>(r);
      for (int c = 0; c < out.cols; ++c) {
        const int i = ix[static_cast<std::size_t>(c)];
        const float tx = fx[static_cast<std::size_t>(c)];
        const float a = g0[i] + (g0[i + 1] - g0[i]) * tx;
        const float b = g1[i] + (g1[i + 1] - g1[i]) * tx;
        o_row[c] += amp * (a + (b - a) * ty);
      }
    }
    total += amp;
    amp *= gain;
    cell_x *= 0.5f;
    cell_y *= 0.5f;
    if (cell_x < 1.0f || cell_y < 1.0f) break;
  }
  const float inv = 1.0f / total;
  for (int r = 0; r < out.rows; ++r) {
    float* o_row = out.ptr<float>(r);
    for (int c = 0; c < out.cols; ++c) o_row[c] *= inv;
  }
}

float fractalNoise1D(float x, float cell, int octaves, float gain, std::uint64_t seed) {
  float amp = 1.0f, total = 0.0f, sum = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    const std::uint64_t oseed = mix64(seed + static_cast<std::uint64_t>(o) * 0x51ED270B27A5C0A1ULL);
    const float u = x / cell;
    const float f = std::floor(u);
    const int i = static_cast<int>(f);
    const float t = fade(u - f);
    const float a = lattice(oseed, i, 7), b = lattice(oseed, i + 1, 7);
    sum += amp * (a + (b - a) * t);
    total += amp;
    amp *= gain;
    cell *= 0.5f;
  }
  return sum / total;
}

namespace {

template <typename T, typename Acc>
void shiftCropT(const cv::Mat& src, int ix, int iy, int wx, int wy, cv::Mat& dst) {
  const int cn = src.channels();
  const int n = dst.cols * cn;
  const Acc w00 = static_cast<Acc>((256 - wx) * (256 - wy)), w01 = static_cast<Acc>(wx * (256 - wy));
  const Acc w10 = static_cast<Acc>((256 - wx) * wy), w11 = static_cast<Acc>(wx * wy);
  for (int r = 0; r < dst.rows; ++r) {
    const T* a = src.ptr<T>(iy + r) + ix * cn;
    const T* b = src.ptr<T>(std::min(iy + r + 1, src.rows - 1)) + ix * cn;
    T* o = dst.ptr<T>(r);
    if (wx == 0 && wy == 0) {
      std::copy(a, a + n, o);
      continue;
    }
    for (int i = 0; i < n; ++i) {
      const Acc v = w00 * a[i] + w01 * a[i + cn] + w10 * b[i] + w11 * b[i + cn] + 32768u;
      o[i] = static_cast<T>(v >> 16);
    }
  }
}

}  // namespace

void shiftCrop(const cv::Mat& src, double ox, double oy, cv::Size size, cv::Mat& dst) {
  if (src.empty() || (src.type() != CV_8UC1 && src.type() != CV_8UC3 && src.type() != CV_16UC1))
    throw std::invalid_argument("shiftCrop: source must be CV_8UC1, CV_8UC3 or CV_16UC1");
  // Fixed point with 8 fractional bits, rounded to nearest.
  const long long qx = static_cast<long long>(std::floor(ox * 256.0 + 0.5));
  const long long qy = static_cast<long long>(std::floor(oy * 256.0 + 0.5));
  const int ix = static_cast<int>(qx >> 8), iy = static_cast<int>(qy >> 8);
  const int wx = static_cast<int>(qx & 255), wy = static_cast<int>(qy & 255);
  if (ix < 0 || iy < 0 || ix + size.width + 1 > src.cols || iy + size.height + (wy ? 1 : 0) > src.rows)
    throw std::invalid_argument("shiftCrop: window outside the source image");
  dst.create(size, src.type());
  if (src.depth() == CV_8U)
    shiftCropT<std::uint8_t, std::uint32_t>(src, ix, iy, wx, wy, dst);
  else
    shiftCropT<std::uint16_t, std::uint64_t>(src, ix, iy, wx, wy, dst);
}

std::vector<cv::Point> directionalBlurOffsets(float dx, float dy) {
  const float ax = std::fabs(dx), ay = std::fabs(dy);
  const int k = static_cast<int>(std::floor(std::max(ax, ay) + 0.5f));
  std::vector<cv::Point> off;
  for (int i = 0; i <= k; ++i) {
    const float t = k == 0 ? 0.0f : static_cast<float>(i) / static_cast<float>(k);
    off.emplace_back(static_cast<int>(std::floor(t * dx + 0.5f)), static_cast<int>(std::floor(t * dy + 0.5f)));
  }
  return off;
}

namespace {

template <typename T>
void directionalBlurT(cv::Mat& img, const std::vector<cv::Point>& off, std::vector<std::uint32_t>& acc) {
  const int cn = img.channels(), rows = img.rows, cols = img.cols;
  const std::size_t n = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols * cn);
  acc.assign(n, 0u);
  for (const cv::Point& o : off) {
    for (int r = 0; r < rows; ++r) {
      const int sr = std::min(std::max(r - o.y, 0), rows - 1);
      const T* s = img.ptr<T>(sr);
      std::uint32_t* a = &acc[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols * cn)];
      // Columns whose source c - o.x lies inside the image, then clamped edges.
      const int c_lo = std::max(0, o.x), c_hi = std::min(cols, cols + o.x);
      for (int c = 0; c < c_lo; ++c)
        for (int k = 0; k < cn; ++k) a[c * cn + k] += s[k];
      const T* sp = s + (c_lo - o.x) * cn;
      std::uint32_t* ap = a + c_lo * cn;
      const int len = (c_hi - c_lo) * cn;
      for (int i = 0; i < len; ++i) ap[i] += sp[i];
      for (int c = std::max(c_hi, 0); c < cols; ++c)
        for (int k = 0; k < cn; ++k) a[c * cn + k] += s[(cols - 1) * cn + k];
    }
  }
  const std::uint32_t cnt = static_cast<std::uint32_t>(off.size());
  for (int r = 0; r < rows; ++r) {
    T* d = img.ptr<T>(r);
    const std::uint32_t* a = &acc[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols * cn)];
    for (int i = 0; i < cols * cn; ++i) d[i] = static_cast<T>((a[i] + cnt / 2) / cnt);
  }
}

}  // namespace

void directionalBlur(cv::Mat& img, float dx, float dy, std::vector<std::uint32_t>& scratch) {
  const auto off = directionalBlurOffsets(dx, dy);
  if (off.size() <= 1) return;
  if (img.depth() == CV_8U)
    directionalBlurT<std::uint8_t>(img, off, scratch);
  else if (img.depth() == CV_16U)
    directionalBlurT<std::uint16_t>(img, off, scratch);
  else
    throw std::invalid_argument("directionalBlur: CV_8U or CV_16U images only");
}

}  // namespace scene
}  // namespace obstacle_tracker
