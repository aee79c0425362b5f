// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// fHOG's per-pixel stage (fhog_gradient.h).
#include "fhog_gradient.h"

#include <cmath>

#include <opencv2/core/hal/intrin.hpp>

namespace obstacle_tracker {
namespace core {
namespace fhog_detail {

namespace {

// Unit vectors of the 9 contrast-insensitive directions, k * 20 degrees (k = 0..8). A gradient's
// sensitive bin is the direction with the largest |dot| (+9 when the dot is negative), i.e. the
// nearest of 18 directions over 360 degrees (Felzenszwalb et al. 2010, sec. 6.1).
struct Directions {
  float cx[9];
  float cy[9];
  Directions() {
    for (int k = 0; k < 9; ++k) {
      const double a = k * M_PI / 9.0;
      cx[k] = static_cast<float>(std::cos(a));
      cy[k] = static_cast<float>(std::sin(a));
    }
  }
};

const Directions& directions() {
  static const Directions d;
  return d;
}

// The centred-difference gradient at pixel x of the channel with the largest magnitude (NC
// channels, interleaved; the row's ends are replicated); ties keep the first channel.
template <int NC>
inline void gradientAt(const uchar* row, const uchar* up, const uchar* down, int w, int x,
                       float* gdx, float* gdy, float* gm2) {
  const int xl = (x > 0 ? x - 1 : 0) * NC;
  const int xr = (x + 1 < w ? x + 1 : w - 1) * NC;
  float bx = 0.0f, by = 0.0f, bm = -1.0f;
  for (int c = 0; c < NC; ++c) {
    const float gx = static_cast<float>(row[xr + c]) - static_cast<float>(row[xl + c]);
    const float gy = static_cast<float>(down[x * NC + c]) - static_cast<float>(up[x * NC + c]);
    const float m = gx * gx + gy * gy;
    const bool better = m > bm;
    bm = better ? m : bm;
    bx = better ? gx : bx;
    by = better ? gy : by;
  }
  gdx[x] = bx;
  gdy[x] = by;
  gm2[x] = bm;
}

#if CV_SIMD
// 8-bit lanes of NC interleaved channels starting at p, one vector per channel.
template <int NC>
inline void loadChannels(const uchar* p, cv::v_uint8 (&ch)[NC]) {
  if constexpr (NC == 1) {
    ch[0] = cv::vx_load(p);
  } else {
    static_assert(NC == 3, "grey or BGR");
    cv::v_load_deinterleave(p, ch[0], ch[1], ch[2]);
  }
}

// a - b of 8-bit lanes as 16-bit lanes, low and high half (exact: |a - b| <= 255).
inline void difference16(const cv::v_uint8& a, const cv::v_uint8& b, cv::v_int16 (&d)[2]) {
  cv::v_uint16 a0, a1, b0, b1;
  cv::v_expand(a, a0, a1);
  cv::v_expand(b, b0, b1);
  d[0] = cv::v_reinterpret_as_s16(a0) - cv::v_reinterpret_as_s16(b0);
  d[1] = cv::v_reinterpret_as_s16(a1) - cv::v_reinterpret_as_s16(b1);
}

// gradientAt over the pixels [1, w - 1) that have both neighbours in the row, v_uint8::nlanes at
// a time, as far as whole blocks go; returns the first pixel not done. Written by hand because the
// compiler does not vectorise the scalar loop (clamped neighbour indices, a channel select), which
// was a large share of the filter's per-frame cost. Differences of 8-bit values and their squares
// are exact in float, and the channel select keeps the scalar order and strict >, so every pixel
// gets the scalar loop's bits.
template <int NC>
int gradientInterior(const uchar* row, const uchar* up, const uchar* down, int w, float* gdx,
                     float* gdy, float* gm2) {
  const int block = cv::v_uint8::nlanes;
  const int quarter = cv::v_float32::nlanes;
  int x = 1;
  for (; x + block <= w - 1; x += block) {
    cv::v_uint8 left[NC], right[NC], above[NC], below[NC];
    loadChannels<NC>(row + (x - 1) * NC, left);
    loadChannels<NC>(row + (x + 1) * NC, right);
    loadChannels<NC>(up + x * NC, above);
    loadChannels<NC>(down + x * NC, below);
    cv::v_int16 gx[NC][2], gy[NC][2];
    for (int c = 0; c < NC; ++c) {
      difference16(right[c], left[c], gx[c]);
      difference16(below[c], above[c], gy[c]);
    }
    for (int half = 0; half < 2; ++half) {
      cv::v_int32 gx32[NC][2], gy32[NC][2];
      for (int c = 0; c < NC; ++c) {
        cv::v_expand(gx[c][half], gx32[c][0], gx32[c][1]);
        cv::v_expand(gy[c][half], gy32[c][0], gy32[c][1]);
      }
      for (int q = 0; q < 2; ++q) {
        cv::v_float32 bx = cv::vx_setzero_f32(), by = cv::vx_setzero_f32();
        cv::v_float32 bm = cv::vx_setall_f32(-1.0f);
        for (int c = 0; c < NC; ++c) {
          const cv::v_float32 fx = cv::v_cvt_f32(gx32[c][q]);
          const cv::v_float32 fy = cv::v_cvt_f32(gy32[c][q]);
          const cv::v_float32 m = fx * fx + fy * fy;
          const cv::v_float32 better = m > bm;
          bm = cv::v_select(better, m, bm);
          bx = cv::v_select(better, fx, bx);
          by = cv::v_select(better, fy, by);
        }
        const int at = x + (2 * half + q) * quarter;
        cv::v_store(gdx + at, bx);
        cv::v_store(gdy + at, by);
        cv::v_store(gm2 + at, bm);
      }
    }
  }
  return x;
}
#endif

// gradientAt for every pixel of one row.
template <int NC>
void maxGradientOf(const uchar* row, const uchar* up, const uchar* down, int w, float* gdx,
                   float* gdy, float* gm2) {
  int x = 0;
#if CV_SIMD
  if (w >= 2) {
    gradientAt<NC>(row, up, down, w, 0, gdx, gdy, gm2);
    x = gradientInterior<NC>(row, up, down, w, gdx, gdy, gm2);
  }
#endif
  for (; x < w; ++x) gradientAt<NC>(row, up, down, w, x, gdx, gdy, gm2);
}

}  // namespace

void maxGradient(const uchar* row, const uchar* up, const uchar* down, int w, int nc, float* gdx,
                 float* gdy, float* gm2) {
  if (nc == 1) {
    maxGradientOf<1>(row, up, down, w, gdx, gdy, gm2);
  } else {
    maxGradientOf<3>(row, up, down, w, gdx, gdy, gm2);
  }
}

void nearestDirections(const float* gdx, const float* gdy, float* gm2, float* gbin, int w) {
  const Directions& dir = directions();
  int x = 0;
#if CV_SIMD
  {
    const int lanes = cv::v_float32::nlanes;
    const cv::v_float32 zero = cv::vx_setzero_f32();
    for (; x <= w - lanes; x += lanes) {
      const cv::v_float32 vdx = cv::vx_load(gdx + x);
      const cv::v_float32 vdy = cv::vx_load(gdy + x);
      cv::v_float32 best = zero;
      cv::v_float32 bin = zero;
      for (int k = 0; k < 9; ++k) {
        // Two roundings as in the scalar tail, never a fused multiply-add (NEON's may fuse).
        const cv::v_float32 d = cv::vx_setall_f32(dir.cx[k]) * vdx + cv::vx_setall_f32(dir.cy[k]) * vdy;
        const cv::v_float32 ad = cv::v_abs(d);
        const cv::v_float32 better = ad > best;
        best = cv::v_select(better, ad, best);
        const cv::v_float32 kb = cv::v_select(d >= zero, cv::vx_setall_f32(static_cast<float>(k)),
                                              cv::vx_setall_f32(static_cast<float>(k + 9)));
        bin = cv::v_select(better, kb, bin);
      }
      cv::v_store(gbin + x, bin);
      cv::v_store(gm2 + x, cv::v_sqrt(cv::vx_load(gm2 + x)));
    }
  }
#endif
  for (; x < w; ++x) {
    float best = 0.0f;
    float bin = 0.0f;
    for (int k = 0; k < 9; ++k) {
      const float d = dir.cx[k] * gdx[x] + dir.cy[k] * gdy[x];
      const float ad = std::fabs(d);
      if (ad > best) {
        best = ad;
        bin = static_cast<float>(d >= 0.0f ? k : k + 9);
      }
    }
    gbin[x] = bin;
    gm2[x] = std::sqrt(gm2[x]);
  }
}

}  // namespace fhog_detail
}  // namespace core
}  // namespace obstacle_tracker
