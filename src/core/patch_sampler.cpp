// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/patch_sampler.h"

#include <algorithm>
#include <cmath>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/frame_check.h"

namespace obstacle_tracker {
namespace core {

void PatchSampler::reserve(int max_width, int max_height, int frame_type, int frame_width) {
  if (static_cast<int>(col_a_.size()) < max_width) {
    col_a_.resize(max_width);
    col_i0_.resize(max_width);
    col_i1_.resize(max_width);
  }
  // The shrunk region is at most about twice the patch (fx / floor(fx) < 2); a row of the
  // accumulator at most a frame row.
  if (shrunk_.type() != frame_type || shrunk_.rows < 2 * max_height + 8 || shrunk_.cols < 2 * max_width + 8) {
    shrunk_.create(std::max(2 * max_height + 8, shrunk_.rows), std::max(2 * max_width + 8, shrunk_.cols), frame_type);
  }
  if (static_cast<int>(row_acc_.size()) < frame_width * 3) row_acc_.resize(frame_width * 3);
  for (std::vector<float>& buffer : cached_rows_) {
    if (static_cast<int>(buffer.size()) < max_width * 3) buffer.resize(static_cast<size_t>(max_width) * 3);
  }
}

void PatchSampler::sample(const cv::Mat& frame, cv::Point2f c, cv::Size2f ws, int tw, int th, cv::Mat& dst) {
  requireFrame(frame, "PatchSampler::sample");  // the row buffers hold 1 or 3 channels
  const int nc = frame.channels();
  dst.create(th, tw, frame.type());
  if (static_cast<int>(col_a_.size()) < tw) reserve(tw, th, frame.type(), frame.cols);
  const double fx = ws.width / tw;
  const double fy = ws.height / th;
  const cv::Point2d origin = boxCentredAt(cv::Point2d(c), cv::Size2d(ws)).tl();
  const double x0 = origin.x, y0 = origin.y;
  int qx = std::max(1, static_cast<int>(std::floor(fx)));
  int qy = std::max(1, static_cast<int>(std::floor(fy)));
  // Source image and its coordinate map: source pixel j has its centre at frame x = ox + (j +
  // 0.5) * qx - 0.5.
  const uchar* src = frame.data;
  size_t src_step = frame.step;
  int sw = frame.cols, sh = frame.rows;
  int ox = 0, oy = 0;
  if (qx > 1 || qy > 1) {
    const int rx0 = std::max(0, static_cast<int>(std::floor(x0)) - qx);
    const int ry0 = std::max(0, static_cast<int>(std::floor(y0)) - qy);
    const int rx1 = std::min(frame.cols, static_cast<int>(std::ceil(x0 + ws.width)) + qx);
    const int ry1 = std::min(frame.rows, static_cast<int>(std::ceil(y0 + ws.height)) + qy);
    const int nw = (rx1 - rx0) / qx;
    const int nh = (ry1 - ry0) / qy;
    if (nw >= 1 && nh >= 1) {
      shrinkBox(frame, rx0, ry0, nw, nh, qx, qy);
      src = shrunk_.data;
      src_step = shrunk_.step;
      sw = nw;
      sh = nh;
      ox = rx0;
      oy = ry0;
    } else {
      qx = qy = 1;
    }
  }
  // Column and row tables: frame x = x0 + (u + 0.5) fx - 0.5 -> source j = (x - ox + 0.5)/qx - 0.5.
  for (int u = 0; u < tw; ++u) {
    const double j = (x0 + (u + 0.5) * fx - ox) / qx - 0.5;
    const double jf = std::floor(j);
    const int j0 = static_cast<int>(jf);
    col_a_[u] = static_cast<float>(j - jf);
    col_i0_[u] = std::min(std::max(j0, 0), sw - 1) * nc;
    col_i1_[u] = std::min(std::max(j0 + 1, 0), sw - 1) * nc;
  }
  // Separable: a source row serves one to several patch rows (several when the window is
  // upsampled), so its horizontal interpolation is computed once and kept while they need it;
  // the vertical blend then runs over contiguous floats.
  cached_row_index_[0] = cached_row_index_[1] = -1;
  const int n = tw * nc;
  for (int v = 0; v < th; ++v) {
    const double i = (y0 + (v + 0.5) * fy - oy) / qy - 0.5;
    const double iff = std::floor(i);
    const int i0 = static_cast<int>(iff);
    const float b = static_cast<float>(i - iff);
    const int top_row = std::min(std::max(i0, 0), sh - 1), bottom_row = std::min(std::max(i0 + 1, 0), sh - 1);
    const float* top = interpolatedRow(src, src_step, top_row, top_row, tw, nc);
    const float* bot = interpolatedRow(src, src_step, bottom_row, top_row, tw, nc);
    uchar* out = dst.ptr<uchar>(v);
    for (int k = 0; k < n; ++k) out[k] = static_cast<uchar>(top[k] + b * (bot[k] - top[k]) + 0.5f);
  }
}

// The horizontal interpolation of source row `row`: one of the two kept rows when it is there,
// else computed into the slot that does not hold row `keep` (the other row the current patch row
// blends).
const float* PatchSampler::interpolatedRow(const uchar* src, size_t src_step, int row, int keep, int width, int nc) {
  for (int k = 0; k < 2; ++k) {
    if (cached_row_index_[k] == row) return cached_rows_[k].data();
  }
  const int slot = cached_row_index_[0] == keep ? 1 : 0;
  std::vector<float>& buffer = cached_rows_[slot];
  if (static_cast<int>(buffer.size()) < width * nc) buffer.resize(static_cast<size_t>(width) * nc);
  const uchar* r = src + static_cast<size_t>(row) * src_step;
  if (nc == 1) {
    horizontalRow<1>(r, width, buffer.data());
  } else {
    horizontalRow<3>(r, width, buffer.data());
  }
  cached_row_index_[slot] = row;
  return buffer.data();
}

template <int NC>
void PatchSampler::horizontalRow(const uchar* r, int width, float* out) const {
  for (int u = 0; u < width; ++u) {
    const float a = col_a_[u];
    const int k0 = col_i0_[u], k1 = col_i1_[u];
    for (int ch = 0; ch < NC; ++ch) out[u * NC + ch] = r[k0 + ch] + a * (static_cast<float>(r[k1 + ch]) - r[k0 + ch]);
  }
}

// Mean of qx x qy blocks of frame starting at (rx0, ry0) -> shrunk_ (nh x nw), reusing buffers.
void PatchSampler::shrinkBox(const cv::Mat& frame, int rx0, int ry0, int nw, int nh, int qx, int qy) {
  const int nc = frame.channels();
  if (shrunk_.type() != frame.type() || shrunk_.rows < nh || shrunk_.cols < nw) {
    shrunk_.create(std::max(nh, shrunk_.rows), std::max(nw, shrunk_.cols), frame.type());
  }
  const int row_len = nw * qx * nc;
  if (static_cast<int>(row_acc_.size()) < row_len) row_acc_.resize(row_len);
  const float inv = 1.0f / static_cast<float>(qx * qy);
  for (int y = 0; y < nh; ++y) {
    std::fill(row_acc_.begin(), row_acc_.begin() + row_len, 0);
    for (int k = 0; k < qy; ++k) {
      const uchar* r = frame.ptr<uchar>(ry0 + y * qy + k) + static_cast<size_t>(rx0) * nc;
      for (int i = 0; i < row_len; ++i) row_acc_[i] += r[i];
    }
    uchar* out = shrunk_.ptr<uchar>(y);
    for (int x = 0; x < nw; ++x) {
      for (int ch = 0; ch < nc; ++ch) {
        int sum = 0;
        const int* acc = row_acc_.data() + x * qx * nc + ch;
        for (int k = 0; k < qx; ++k) sum += acc[k * nc];
        out[x * nc + ch] = static_cast<uchar>(static_cast<float>(sum) * inv + 0.5f);
      }
    }
  }
}

}  // namespace core
}  // namespace obstacle_tracker
