// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// FastMBD (Zhang et al., ICCV 2015, Algorithm 1) and a brute-force exact MBD for tests. See mbd.h.
#include "obstacle_tracker/core/mbd.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <stdexcept>
#include <utility>
#include <vector>

#include <opencv2/core/hal/intrin.hpp>

#include "obstacle_tracker/core/frame_check.h"

namespace obstacle_tracker {
namespace core {
namespace {

// The distance is not stored: a pixel's D is always U - L of its current path. Unreached pixels
// start with U = 255, L = 0 (D = 255, "infinite"): a path through them has barrier 255 and never
// improves anything, and their own first relaxation replaces U and L. One array less to load and
// store per pixel and pass.

// Relaxes pixels [0, n) of one row against the row `nb` (the row above in a forward pass, below in
// a backward pass). Independent across the row: OpenCV's universal intrinsics (16/32/64 bytes at
// a time, whatever the build's SIMD), then a scalar tail.
inline std::uint8_t relaxRow(const std::uint8_t* __restrict img, const std::uint8_t* __restrict nb_u,
                             const std::uint8_t* __restrict nb_l, std::uint8_t* __restrict u,
                             std::uint8_t* __restrict l, int n) {
  int j = 0;
  std::uint8_t changed = 0;
#if CV_SIMD
  const int lanes = cv::v_uint8::nlanes;
  cv::v_uint8 any = cv::vx_setzero_u8();
  for (; j + lanes <= n; j += lanes) {
    const cv::v_uint8 v = cv::vx_load(img + j);
    const cv::v_uint8 cu = cv::v_max(cv::vx_load(nb_u + j), v);
    const cv::v_uint8 cl = cv::v_min(cv::vx_load(nb_l + j), v);
    const cv::v_uint8 ou = cv::vx_load(u + j), ol = cv::vx_load(l + j);
    const cv::v_uint8 m = (cu - cl) < (ou - ol);  // U >= L everywhere: no saturation
    cv::v_store(u + j, cv::v_select(m, cu, ou));
    cv::v_store(l + j, cv::v_select(m, cl, ol));
    any |= m;
  }
  changed = cv::v_check_any(any) ? 1 : 0;
#endif
  for (; j < n; ++j) {
    const std::uint8_t cu = std::max(nb_u[j], img[j]);
    const std::uint8_t cl = std::min(nb_l[j], img[j]);
    if (cu - cl < u[j] - l[j]) {
      u[j] = cu;
      l[j] = cl;
      changed = 1;
    }
  }
  return changed;
}

// Serial sweep along one row: pixel c against its neighbour c - 1 (forward) or c + 1 (backward).
// CN channels are independent chains interleaved in memory. The neighbour's U and L are carried
// in registers and the update is a conditional move, not a branch (the comparison is data
// dependent and mispredicts on real images).
template <int CN, bool kForward>
inline std::uint8_t sweepRow(const std::uint8_t* __restrict img, std::uint8_t* __restrict u,
                             std::uint8_t* __restrict l, int cols) {
  unsigned changed = 0;
  unsigned pu[CN], pl[CN];
  const int first = kForward ? 1 : cols - 2;
  const int step = kForward ? 1 : -1;
  for (int k = 0; k < CN; ++k) {
    pu[k] = u[(first - step) * CN + k];
    pl[k] = l[(first - step) * CN + k];
  }
  for (int i = 0, c = first; i < cols - 2; ++i, c += step) {
    for (int k = 0; k < CN; ++k) {
      const int j = c * CN + k;
      const unsigned v = img[j];
      const unsigned cu = pu[k] > v ? pu[k] : v;
      const unsigned cl = pl[k] < v ? pl[k] : v;
      const unsigned ou = u[j], ol = l[j];
      const bool better = cu - cl < ou - ol;
      const unsigned nu = better ? cu : ou;
      const unsigned nl = better ? cl : ol;
      u[j] = static_cast<std::uint8_t>(nu);
      l[j] = static_cast<std::uint8_t>(nl);
      pu[k] = nu;
      pl[k] = nl;
      changed |= better;
    }
  }
  return static_cast<std::uint8_t>(changed);
}

template <int CN>
int fastMbdImpl(const cv::Mat& image, int passes, cv::Mat& dist, cv::Mat& upper, cv::Mat& lower) {
  const int rows = image.rows, cols = image.cols;
  image.copyTo(upper);
  image.copyTo(lower);
  if (rows >= 3 && cols >= 3) {
    for (int r = 1; r < rows - 1; ++r) {
      std::fill(upper.ptr<std::uint8_t>(r) + CN, upper.ptr<std::uint8_t>(r) + (cols - 1) * CN, std::uint8_t(255));
      std::fill(lower.ptr<std::uint8_t>(r) + CN, lower.ptr<std::uint8_t>(r) + (cols - 1) * CN, std::uint8_t(0));
    }
  }
  int run = 0;
  if (rows >= 3 && cols >= 3) {  // otherwise every pixel is a seed
    // Interior bytes of a row: columns 1 .. cols-2.
    const int n = (cols - 2) * CN;
    for (int p = 0; p < passes; ++p) {
      const bool forward = (p % 2) == 0;
      std::uint8_t changed = 0;
      for (int i = 1; i < rows - 1; ++i) {
        const int r = forward ? i : rows - 1 - i;
        const int rn = forward ? r - 1 : r + 1;
        const std::uint8_t* img = image.ptr<std::uint8_t>(r);
        std::uint8_t* u = upper.ptr<std::uint8_t>(r);
        std::uint8_t* l = lower.ptr<std::uint8_t>(r);
        changed |= relaxRow(img + CN, upper.ptr<std::uint8_t>(rn) + CN, lower.ptr<std::uint8_t>(rn) + CN, u + CN,
                            l + CN, n);
        changed |= forward ? sweepRow<CN, true>(img, u, l, cols) : sweepRow<CN, false>(img, u, l, cols);
      }
      ++run;
      if (!changed && p > 0) break;  // stable under both scan orders: converged
    }
  }
  cv::subtract(upper, lower, dist);  // D = U - L (0 on the seeds)
  return run;
}

}  // namespace

int fastMbd(const cv::Mat& image, int passes, cv::Mat& dist, cv::Mat& upper, cv::Mat& lower) {
  requireFrame(image, "fastMbd");
  if (passes < 1) throw std::invalid_argument("fastMbd: passes must be >= 1");
  dist.create(image.size(), image.type());
  upper.create(image.size(), image.type());
  lower.create(image.size(), image.type());
  return image.channels() == 1 ? fastMbdImpl<1>(image, passes, dist, upper, lower)
                               : fastMbdImpl<3>(image, passes, dist, upper, lower);
}

cv::Mat exactMbd(const cv::Mat& image) {
  if (image.empty()) throw std::invalid_argument("exactMbd: empty image");
  if (image.type() != CV_8UC1) throw std::invalid_argument("exactMbd: image must be CV_8UC1");
  const int rows = image.rows, cols = image.cols, n = rows * cols;
  std::vector<int> value(n);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) value[r * cols + c] = image.at<std::uint8_t>(r, c);
  std::vector<int> best(n, 255);
  std::vector<int> minimax(n);
  using Item = std::pair<int, int>;  // (path maximum, pixel)
  const int dr[4] = {-1, 1, 0, 0}, dc[4] = {0, 0, -1, 1};
  for (int lo = 0; lo < 256; ++lo) {
    // Minimax (bottleneck) Dijkstra from the border seeds through pixels with value >= lo.
    std::fill(minimax.begin(), minimax.end(), 1 << 20);
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    bool any = false;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const int i = r * cols + c;
        if (value[i] < lo) continue;
        any = true;
        if (r == 0 || c == 0 || r == rows - 1 || c == cols - 1) {
          minimax[i] = value[i];
          queue.push({value[i], i});
        }
      }
    if (!any) break;
    while (!queue.empty()) {
      const Item top = queue.top();
      queue.pop();
      if (top.first != minimax[top.second]) continue;
      const int r = top.second / cols, c = top.second % cols;
      for (int k = 0; k < 4; ++k) {
        const int rr = r + dr[k], cc = c + dc[k];
        if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
        const int j = rr * cols + cc;
        if (value[j] < lo) continue;
        const int m = std::max(top.first, value[j]);
        if (m < minimax[j]) {
          minimax[j] = m;
          queue.push({m, j});
        }
      }
    }
    for (int i = 0; i < n; ++i)
      if (value[i] >= lo && minimax[i] < (1 << 20)) best[i] = std::min(best[i], minimax[i] - lo);
  }
  cv::Mat out(rows, cols, CV_8UC1);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const bool border = r == 0 || c == 0 || r == rows - 1 || c == cols - 1;
      out.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(border ? 0 : best[r * cols + c]);
    }
  return out;
}

}  // namespace core
}  // namespace obstacle_tracker
