// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Felzenszwalb HOG per cell (see fhog.h for the paper and the exact recipe).
#include "obstacle_tracker/core/fhog.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace obstacle_tracker {
namespace core {

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

}  // namespace

void FhogExtractor::compute(const cv::Mat& patch, int cell, cv::Mat& out) {
  if (patch.empty()) throw std::invalid_argument("FhogExtractor::compute: empty patch");
  if (patch.type() != CV_8UC1 && patch.type() != CV_8UC3) {
    throw std::invalid_argument("FhogExtractor::compute: patch must be CV_8UC1 or CV_8UC3");
  }
  if (cell < 1) throw std::invalid_argument("FhogExtractor::compute: cell size must be >= 1");
  if (patch.rows < cell || patch.cols < cell) {
    throw std::invalid_argument("FhogExtractor::compute: patch smaller than one cell");
  }
  const int w = patch.cols;
  const int h = patch.rows;
  const int nc = patch.channels();
  const int cols = w / cell;
  const int rows = h / cell;
  const int ncell = rows * cols;

  hist_.assign(static_cast<size_t>(ncell) * kOrientations, 0.0f);
  energy_.assign(ncell, 0.0f);
  grey_.assign(ncell, 0.0f);
  out.create(kChannels * rows, cols, CV_32F);

  const Directions& dir = directions();
  const float inv_cell = 1.0f / static_cast<float>(cell);

  for (int y = 0; y < h; ++y) {
    const uchar* row = patch.ptr<uchar>(y);
    const uchar* up = patch.ptr<uchar>(std::max(y - 1, 0));
    const uchar* down = patch.ptr<uchar>(std::min(y + 1, h - 1));
    // Bilinear weights along y (cell centres at (i + 0.5) * cell).
    const float yp = (static_cast<float>(y) + 0.5f) * inv_cell - 0.5f;
    const int iy = static_cast<int>(std::floor(yp));
    const float vy0 = yp - static_cast<float>(iy);
    const float vy1 = 1.0f - vy0;
    const int grey_row = y / cell;
    for (int x = 0; x < w; ++x) {
      const int xl = std::max(x - 1, 0);
      const int xr = std::min(x + 1, w - 1);
      // Gradient of the channel with the largest magnitude (replicated border).
      float dx = 0.0f;
      float dy = 0.0f;
      float best = -1.0f;
      float grey = 0.0f;
      for (int c = 0; c < nc; ++c) {
        const float gx = static_cast<float>(row[xr * nc + c]) - static_cast<float>(row[xl * nc + c]);
        const float gy = static_cast<float>(down[x * nc + c]) - static_cast<float>(up[x * nc + c]);
        const float m = gx * gx + gy * gy;
        if (m > best) {
          best = m;
          dx = gx;
          dy = gy;
        }
        grey += static_cast<float>(row[x * nc + c]);
      }
      if (grey_row < rows && x / cell < cols) {
        grey_[grey_row * cols + x / cell] += grey / static_cast<float>(nc);
      }
      if (best <= 0.0f) continue;
      const float mag = std::sqrt(best);
      int bin = 0;
      float best_dot = 0.0f;
      for (int k = 0; k < 9; ++k) {
        const float d = dir.cx[k] * dx + dir.cy[k] * dy;
        if (d > best_dot) {
          best_dot = d;
          bin = k;
        } else if (-d > best_dot) {
          best_dot = -d;
          bin = k + 9;
        }
      }
      const float xp = (static_cast<float>(x) + 0.5f) * inv_cell - 0.5f;
      const int ix = static_cast<int>(std::floor(xp));
      const float vx0 = xp - static_cast<float>(ix);
      const float vx1 = 1.0f - vx0;
      const bool x0_in = ix >= 0;
      const bool x1_in = ix + 1 < cols;
      if (iy >= 0) {
        float* hr = hist_.data() + static_cast<size_t>(iy) * cols * kOrientations;
        if (x0_in) hr[ix * kOrientations + bin] += vx1 * vy1 * mag;
        if (x1_in) hr[(ix + 1) * kOrientations + bin] += vx0 * vy1 * mag;
      }
      if (iy + 1 < rows) {
        float* hr = hist_.data() + static_cast<size_t>(iy + 1) * cols * kOrientations;
        if (x0_in) hr[ix * kOrientations + bin] += vx1 * vy0 * mag;
        if (x1_in) hr[(ix + 1) * kOrientations + bin] += vx0 * vy0 * mag;
      }
    }
  }

  // Energy of each cell (contrast-insensitive histogram, squared).
  for (int i = 0; i < ncell; ++i) {
    const float* hc = hist_.data() + static_cast<size_t>(i) * kOrientations;
    float e = 0.0f;
    for (int o = 0; o < 9; ++o) {
      const float v = hc[o] + hc[o + 9];
      e += v * v;
    }
    energy_[i] = e;
  }

  const float eps = 1e-4f;  // as in the paper's reference features
  const float grey_scale = 1.0f / (255.0f * static_cast<float>(cell * cell));
  auto energy_at = [&](int r, int c) {
    r = std::min(std::max(r, 0), rows - 1);
    c = std::min(std::max(c, 0), cols - 1);
    return energy_[r * cols + c];
  };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      // The 4 2x2 blocks that contain cell (r, c): offsets (-1|0, -1|0).
      float n[4];
      int b = 0;
      for (int by = -1; by <= 0; ++by) {
        for (int bx = -1; bx <= 0; ++bx) {
          const float s = energy_at(r + by, c + bx) + energy_at(r + by, c + bx + 1) +
                          energy_at(r + by + 1, c + bx) + energy_at(r + by + 1, c + bx + 1);
          n[b++] = 1.0f / std::sqrt(s + eps);
        }
      }
      const float* hc = hist_.data() + (static_cast<size_t>(r) * cols + c) * kOrientations;
      const int idx = r * cols + c;
      float* o0 = out.ptr<float>(0);
      const size_t plane = static_cast<size_t>(rows) * cols;
      float texture[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      for (int o = 0; o < kOrientations; ++o) {
        float sum = 0.0f;
        for (int k = 0; k < 4; ++k) {
          const float v = std::min(hc[o] * n[k], kTruncation);
          sum += v;
          texture[k] += v;
        }
        o0[o * plane + idx] = 0.5f * sum;
      }
      for (int o = 0; o < 9; ++o) {
        const float hv = hc[o] + hc[o + 9];
        float sum = 0.0f;
        for (int k = 0; k < 4; ++k) sum += std::min(hv * n[k], kTruncation);
        o0[(kOrientations + o) * plane + idx] = 0.5f * sum;
      }
      for (int k = 0; k < 4; ++k) o0[(27 + k) * plane + idx] = 0.2357f * texture[k];
      o0[kGreyChannel * plane + idx] = grey_[idx] * grey_scale - 0.5f;
    }
  }
}

}  // namespace core
}  // namespace obstacle_tracker
