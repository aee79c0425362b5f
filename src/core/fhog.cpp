// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Felzenszwalb HOG per cell (see fhog.h for the paper and the exact recipe).
#include "obstacle_tracker/core/fhog.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/core/hal/intrin.hpp>

#include "fhog_gradient.h"
#include "obstacle_tracker/core/frame_check.h"

namespace obstacle_tracker {
namespace core {

namespace {

// One orientation along a row of `cols` cells: dst[c] = 0.5 sum_k min(h[c] n_k[c], 0.2) with
// h = ha (+ hb when given, the contrast-insensitive sum), and each term added to texture (4 rows of
// `cols`) when given. OpenCV's universal intrinsics run it along the cells; the scalar tail does
// the same operations in the same order, so every cell gets the same bits either way.
void truncatedSums(const float* ha, const float* hb, const float* const n[4], float* texture,
                   int cols, float* dst) {
  const float trunc = FhogExtractor::kTruncation;
  int c = 0;
#if CV_SIMD
  {
    const int lanes = cv::v_float32::nlanes;
    const cv::v_float32 vtrunc = cv::vx_setall_f32(trunc);
    const cv::v_float32 half = cv::vx_setall_f32(0.5f);
    for (; c <= cols - lanes; c += lanes) {
      const cv::v_float32 h = hb ? cv::vx_load(ha + c) + cv::vx_load(hb + c) : cv::vx_load(ha + c);
      cv::v_float32 sum = cv::vx_setzero_f32();
      for (int k = 0; k < 4; ++k) {
        const cv::v_float32 v = cv::v_min(h * cv::vx_load(n[k] + c), vtrunc);
        sum = sum + v;
        if (texture) cv::v_store(texture + k * cols + c, cv::vx_load(texture + k * cols + c) + v);
      }
      cv::v_store(dst + c, half * sum);
    }
  }
#endif
  for (; c < cols; ++c) {
    const float h = hb ? ha[c] + hb[c] : ha[c];
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      const float v = std::min(h * n[k][c], trunc);
      sum += v;
      if (texture) texture[k * cols + c] += v;
    }
    dst[c] = 0.5f * sum;
  }
}

}  // namespace

void FhogExtractor::compute(const cv::Mat& patch, int cell, cv::Mat& out) {
  requireFrame(patch, "FhogExtractor::compute");
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
  texture_.resize(static_cast<size_t>(4) * cols);
  out.create(kChannels * rows, cols, CV_32F);

  const float inv_cell = 1.0f / static_cast<float>(cell);

  // Per-column tables (neighbour offsets, cell index and bilinear weights along x), made once per
  // width; per-row scratch for the winning gradient. Cell centres are at (i + 0.5) * cell.
  col_cell_.resize(w);
  col_w0_.resize(w);
  row_dx_.resize(w);
  row_dy_.resize(w);
  row_m2_.resize(w);
  row_bin_.resize(w);
  for (int x = 0; x < w; ++x) {
    const float xp = (static_cast<float>(x) + 0.5f) * inv_cell - 0.5f;
    const int ix = static_cast<int>(std::floor(xp));
    col_cell_[x] = ix;
    col_w0_[x] = xp - static_cast<float>(ix);  // weight of cell ix + 1
  }
  float* gdx = row_dx_.data();
  float* gdy = row_dy_.data();
  float* gm2 = row_m2_.data();
  float* gbin = row_bin_.data();

  for (int y = 0; y < h; ++y) {
    const uchar* row = patch.ptr<uchar>(y);
    const uchar* up = patch.ptr<uchar>(std::max(y - 1, 0));
    const uchar* down = patch.ptr<uchar>(std::min(y + 1, h - 1));
    fhog_detail::maxGradient(row, up, down, w, nc, gdx, gdy, gm2);
    fhog_detail::nearestDirections(gdx, gdy, gm2, gbin, w);
    accumulateRow(row, y, cell, nc, rows, cols);
  }
  normalise(rows, cols, cell, out);
}

// One row's share of the cells: its grey levels summed per cell, and each pixel's magnitude voted
// bilinearly into the 4 nearest cells' orientation histograms (row_m2_ holds magnitudes, row_bin_
// the bins).
void FhogExtractor::accumulateRow(const uchar* row, int y, int cell, int nc, int rows, int cols) {
  const int w = static_cast<int>(row_m2_.size());
  const float inv_cell = 1.0f / static_cast<float>(cell);
  const float* gm2 = row_m2_.data();
  const float* gbin = row_bin_.data();
  // Grey level (mean over the colour channels) summed per cell.
  const int grey_row = y / cell;
  if (grey_row < rows) {
    float* gr = grey_.data() + static_cast<size_t>(grey_row) * cols;
    const float inv_nc = 1.0f / static_cast<float>(nc);
    for (int k = 0; k < cols; ++k) {
      const uchar* p = row + static_cast<size_t>(k) * cell * nc;
      int g = 0;
      for (int i = 0; i < cell * nc; ++i) g += p[i];
      gr[k] += static_cast<float>(g) * inv_nc;
    }
  }
  // Bilinear votes into the 4 nearest cells.
  const float yp = (static_cast<float>(y) + 0.5f) * inv_cell - 0.5f;
  const int iy = static_cast<int>(std::floor(yp));
  const float vy0 = yp - static_cast<float>(iy);
  const float vy1 = 1.0f - vy0;
  // hist_ is orientation-major (hist_[o * ncell + cell]) so that normalise() runs along cells.
  const size_t ncell = static_cast<size_t>(rows) * cols;
  // Pixels past the last whole cell (a patch side that is not a multiple of the cell) vote only
  // into cells of the grid, as in the paper's reference features; a cell index past the grid
  // would land in the next row's cells or past the histogram's end. (iy and ix are >= -1.)
  float* h0 = iy >= 0 && iy < rows ? hist_.data() + static_cast<size_t>(iy) * cols : nullptr;
  float* h1 = iy + 1 < rows ? hist_.data() + static_cast<size_t>(iy + 1) * cols : nullptr;
  for (int x = 0; x < w; ++x) {
    const float mag = gm2[x];  // now the magnitude
    if (mag <= 0.0f) continue;
    const size_t plane = static_cast<size_t>(gbin[x]) * ncell;
    const int ix = col_cell_[x];
    const float vx0 = col_w0_[x];
    const float vx1 = 1.0f - vx0;
    const bool x0_in = ix >= 0 && ix < cols;
    const bool x1_in = ix + 1 < cols;
    if (h0 != nullptr) {
      const float m = vy1 * mag;
      if (x0_in) h0[plane + ix] += vx1 * m;
      if (x1_in) h0[plane + ix + 1] += vx0 * m;
    }
    if (h1 != nullptr) {
      const float m = vy0 * mag;
      if (x0_in) h1[plane + ix] += vx1 * m;
      if (x1_in) h1[plane + ix + 1] += vx0 * m;
    }
  }
}

// Per cell: the 18 contrast-sensitive and 9 insensitive orientations, each normalised by the 4
// 2x2 blocks around the cell and truncated, 4 texture sums, and the grey level (fhog.h).
// Each block's norm is computed once for the 4 cells it normalises, and the loops run along a row of
// cells (truncatedSums) so that they vectorise; every cell's own sums keep their order.
void FhogExtractor::normalise(int rows, int cols, int cell, cv::Mat& out) {
  const size_t ncell = static_cast<size_t>(rows) * cols;
  // Energy of each cell (contrast-insensitive histogram, squared); compute() zeroed energy_.
  for (int o = 0; o < 9; ++o) {
    const float* hs = hist_.data() + o * ncell;
    const float* hi = hist_.data() + (o + 9) * ncell;
    for (size_t i = 0; i < ncell; ++i) {
      const float v = hs[i] + hi[i];
      energy_[i] += v * v;
    }
  }
  blockNorms(rows, cols);

  const float grey_scale = 1.0f / (255.0f * static_cast<float>(cell * cell));
  float* o0 = out.ptr<float>(0);
  const size_t bstride = static_cast<size_t>(cols) + 1;
  for (int r = 0; r < rows; ++r) {
    // The 4 blocks that contain cell (r, c), top-left corner offsets (-1|0, -1|0): block (i, j)
    // is block_norm_[(i + 1) * (cols + 1) + j + 1].
    const float* n[4] = {&block_norm_[r * bstride], &block_norm_[r * bstride + 1],
                         &block_norm_[(r + 1) * bstride], &block_norm_[(r + 1) * bstride + 1]};
    const size_t idx = static_cast<size_t>(r) * cols;
    std::fill(texture_.begin(), texture_.end(), 0.0f);
    for (int o = 0; o < kOrientations; ++o) {
      const float* hc = hist_.data() + o * ncell + idx;
      truncatedSums(hc, nullptr, n, texture_.data(), cols, o0 + o * ncell + idx);
    }
    for (int o = 0; o < 9; ++o) {
      const float* hs = hist_.data() + o * ncell + idx;
      const float* hi = hist_.data() + (o + 9) * ncell + idx;
      truncatedSums(hs, hi, n, nullptr, cols, o0 + (kOrientations + o) * ncell + idx);
    }
    for (int k = 0; k < 4; ++k) {
      float* dst = o0 + (27 + k) * ncell + idx;
      for (int c = 0; c < cols; ++c) dst[c] = 0.2357f * texture_[k * cols + c];
    }
    float* grey_dst = o0 + kGreyChannel * ncell + idx;
    for (int c = 0; c < cols; ++c) grey_dst[c] = grey_[idx + c] * grey_scale - 0.5f;
  }
}

// 1 / sqrt(energy + eps) of every 2x2-cell block with its top-left cell in [-1, rows) x
// [-1, cols); cells outside the grid take the nearest cell's energy (fhog.h).
void FhogExtractor::blockNorms(int rows, int cols) {
  const float eps = 1e-4f;  // as in the paper's reference features
  auto energy_at = [&](int r, int c) {
    r = std::min(std::max(r, 0), rows - 1);
    c = std::min(std::max(c, 0), cols - 1);
    return energy_[static_cast<size_t>(r) * cols + c];
  };
  block_norm_.resize(static_cast<size_t>(rows + 1) * (cols + 1));
  for (int i = -1; i < rows; ++i) {
    for (int j = -1; j < cols; ++j) {
      const float s =
          energy_at(i, j) + energy_at(i, j + 1) + energy_at(i + 1, j) + energy_at(i + 1, j + 1);
      block_norm_[static_cast<size_t>(i + 1) * (cols + 1) + (j + 1)] = 1.0f / std::sqrt(s + eps);
    }
  }
}

}  // namespace core
}  // namespace obstacle_tracker
