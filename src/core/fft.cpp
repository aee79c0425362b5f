// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Portable FFTs (fft.h): the same bits on every machine, for the correlation filter.
#include "obstacle_tracker/core/fft.h"

#include <algorithm>
#include <cmath>

#include "fft_butterflies.h"

namespace obstacle_tracker {
namespace core {

using namespace fft_detail;  // NOLINT(build/namespaces): the FFT's own arithmetic and butterflies

namespace {

// cos and sin of t in [0, pi/4] by their Taylor series to t^20 (the first omitted term is below
// 1e-19 there, far under a float's rounding): plain double operations, the same on every machine.
void cosSinSeries(double t, double& c, double& s) {
  const double t2 = t * t;
  double cs = 1.0, ss = 1.0;  // Horner, highest term first
  for (int k = 10; k >= 1; --k) {
    cs = 1.0 - t2 / static_cast<double>((2 * k - 1) * (2 * k)) * cs;
    ss = 1.0 - t2 / static_cast<double>((2 * k) * (2 * k + 1)) * ss;
  }
  c = cs;
  s = t * ss;
}

// Radix order: 4 first (fewest operations), then 2, 3, 5, ...; outermost stage first.
std::vector<int> radices(int n) {
  std::vector<int> r;
  int p = 4;
  while (n > 1) {
    while (n % p != 0) {
      p = p == 4 ? 2 : p == 2 ? 3 : p + 2;
      if (static_cast<long>(p) * p > n) p = n;  // n is prime
    }
    r.push_back(p);
    n /= p;
  }
  return r;
}

}  // namespace

ComplexF unitRootTurn(long k, long n) {
  k %= n;
  if (k < 0) k += n;
  // 2 pi k / n = octant * pi / 4 + (pi / 4) * rest / n, rest in [0, n).
  const long octant = (8 * k) / n;
  const long rest = 8 * k - octant * n;
  const double quarter = 0.78539816339744830962;  // pi / 4
  double c, s;
  // Odd octants use the complement (pi/4 - t), so the series always runs on [0, pi/4].
  const bool odd = (octant % 2) != 0;
  cosSinSeries(quarter * static_cast<double>(odd ? n - rest : rest) / static_cast<double>(n), c, s);
  double cp, sp;  // cos and sin of the whole angle
  switch (octant) {
    case 0: cp = c; sp = s; break;
    case 1: cp = s; sp = c; break;
    case 2: cp = -s; sp = c; break;
    case 3: cp = -c; sp = s; break;
    case 4: cp = -c; sp = -s; break;
    case 5: cp = -s; sp = -c; break;
    case 6: cp = s; sp = -c; break;
    default: cp = c; sp = -s; break;
  }
  return {static_cast<float>(cp), static_cast<float>(-sp)};
}

void ComplexFft::configure(int n) {
  CV_Assert(n >= 1);
  if (n == n_) return;
  n_ = n;
  stages_.clear();
  int span = n;
  widest_radix_ = 1;
  for (int p : radices(n)) {
    span /= p;
    stages_.push_back({p, span});
    widest_radix_ = std::max(widest_radix_, p);
  }
  single_.resize(2 * static_cast<std::size_t>(n));
  scratch_.clear();
  reserveBatch(1);
  forward_.resize(static_cast<std::size_t>(n));
  inverse_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    forward_[static_cast<std::size_t>(k)] = unitRootTurn(k, n);
    inverse_[static_cast<std::size_t>(k)] = conj(forward_[static_cast<std::size_t>(k)]);
  }
  // Decimation in time reads the input in mixed-radix digit-reversed order: output block q of a
  // stage holds the sub-sequence starting at q fstride, every radix fstride-th value.
  input_order_.assign(static_cast<std::size_t>(n), 0);
  int fstride = 1;
  for (const Stage& st : stages_) {
    for (int i = 0; i < n; ++i) {
      const int q = (i / st.span) % st.radix;
      input_order_[static_cast<std::size_t>(i)] += q * fstride;
    }
    fstride *= st.radix;
  }
}

void ComplexFft::reserveBatch(int count) const {
  // Only the direct-sum butterfly (a radix above 5) needs scratch: its p inputs, split.
  const std::size_t needed = widest_radix_ > 5 ? 2 * static_cast<std::size_t>(widest_radix_) * count : 0;
  if (scratch_.size() < needed) scratch_.resize(needed);
}

void ComplexFft::run(const ComplexF* in, int in_stride, ComplexF* out, const std::vector<ComplexF>& tw) const {
  float* re = single_.data();
  float* im = re + n_;
  runBatch(in, in_stride, 0, 1, re, im, tw);
  for (int i = 0; i < n_; ++i) out[i] = {re[i], im[i]};
}

void ComplexFft::runBatch(const ComplexF* in, int in_stride, int batch_stride, int count, float* re, float* im,
                          const std::vector<ComplexF>& tw) const {
  // Decimation in time reads the input in mixed-radix digit-reversed order (input_order_).
  for (int i = 0; i < n_; ++i) {
    const ComplexF* src = in + static_cast<long>(input_order_[static_cast<std::size_t>(i)]) * in_stride;
    for (int b = 0; b < count; ++b) {
      re[static_cast<long>(i) * count + b] = src[static_cast<long>(b) * batch_stride].re;
      im[static_cast<long>(i) * count + b] = src[static_cast<long>(b) * batch_stride].im;
    }
  }
  // Innermost stage first: stage s combines, in each of its fstride sub-problems, `radix`
  // transforms of length `span` into one of length radix span.
  for (std::size_t s = stages_.size(); s-- > 0;) {
    const int p = stages_[s].radix, m = stages_[s].span;
    const int fstride = n_ / (p * m);
    for (int j = 0; j < fstride; ++j) {
      const long first = static_cast<long>(j) * p * m * count;
      butterfly(re + first, im + first, count, fstride, m, p, tw);
    }
  }
}

// Combines `radix` transforms of length `span` (elements q span ..) into one of length
// radix span, for `count` transforms side by side. tw[j fstride] = e^(-+2 pi i j / (radix span)).
void ComplexFft::butterfly(float* re, float* im, int count, int fstride, int m, int p,
                           const std::vector<ComplexF>& tw) const {
  const Split x{re, im, count};
  switch (p) {
    case 2: return butterfly2(x, fstride, m, tw);
    case 3: return butterfly3(x, fstride, m, tw);
    case 4: return butterfly4(x, fstride, m, tw);
    case 5: return butterfly5(x, fstride, m, tw);
    default: {
      reserveBatch(count);
      const Split in{scratch_.data(), scratch_.data() + static_cast<std::size_t>(p) * count, count};
      return butterflyDirect(x, fstride, m, p, tw, in);
    }
  }
}

void RealFft2d::configure(int rows, int cols) {
  CV_Assert(rows >= 1 && cols >= 1);
  if (rows == rows_ && cols == cols_) return;
  rows_ = rows;
  cols_ = cols;
  row_fft_.configure(cols);
  col_fft_.configure(rows);
  const std::size_t half = static_cast<std::size_t>(cols / 2 + 1);
  const std::size_t pairs = static_cast<std::size_t>((rows + 1) / 2);
  pair_in_.resize(pairs * static_cast<std::size_t>(cols));
  split_.resize(2 * std::max(static_cast<std::size_t>(rows) * half, pairs * static_cast<std::size_t>(cols)));
  row_fft_.reserveBatch(static_cast<int>(pairs));
  col_fft_.reserveBatch(static_cast<int>(half));
}

// Row spectra, columns 0 .. cols/2, two real rows per complex transform: with z = a + i b,
// A[k] = (Z[k] + conj Z[-k]) / 2 and B[k] = (Z[k] - conj Z[-k]) / (2 i). All row pairs are
// transformed side by side (ComplexFft::forwardBatch).
void RealFft2d::rowPairsForward(const cv::Mat& src, cv::Mat& dst) {
  const int half = cols_ / 2 + 1;
  const int pairs = (src.rows + 1) / 2;
  // More rows than configured (forwardEachRow) grow the buffers on the first call; they never shrink,
  // so inverse() keeps the room configure() gave it.
  const std::size_t needed = static_cast<std::size_t>(pairs) * cols_;
  if (pair_in_.size() < needed) pair_in_.resize(needed);
  if (split_.size() < 2 * needed) split_.resize(2 * needed);
  row_fft_.reserveBatch(pairs);
  for (int q = 0; q < pairs; ++q) {
    const float* a = src.ptr<float>(2 * q);
    const float* b = 2 * q + 1 < src.rows ? src.ptr<float>(2 * q + 1) : nullptr;
    ComplexF* line = &pair_in_[static_cast<std::size_t>(q) * cols_];
    for (int j = 0; j < cols_; ++j) line[j] = {a[j], b ? b[j] : 0.0f};
  }
  float* re = split_.data();
  float* im = re + static_cast<std::size_t>(pairs) * cols_;
  row_fft_.forwardBatch(pair_in_.data(), 1, cols_, pairs, re, im);
  for (int q = 0; q < pairs; ++q) {
    ComplexF* da = dst.ptr<ComplexF>(2 * q);
    ComplexF* db = 2 * q + 1 < src.rows ? dst.ptr<ComplexF>(2 * q + 1) : nullptr;
    for (int k = 0; k < half; ++k) {
      const long kc = (cols_ - k) % cols_;
      const ComplexF z = {re[k * pairs + q], im[k * pairs + q]};
      const ComplexF zc = conj({re[kc * pairs + q], im[kc * pairs + q]});
      const ComplexF s = add(z, zc), d = sub(z, zc);
      da[k] = {0.5f * s.re, 0.5f * s.im};
      if (db) db[k] = {0.5f * d.im, -0.5f * d.re};
    }
  }
}

void RealFft2d::forward(const cv::Mat& src, cv::Mat& dst) {
  CV_Assert(src.type() == CV_32F && src.rows == rows_ && src.cols == cols_);
  dst.create(rows_, cols_, CV_32FC2);
  rowPairsForward(src, dst);
  const int half = cols_ / 2 + 1;
  if (rows_ > 1) {
    // Columns 0 .. cols/2 side by side.
    const int stride = static_cast<int>(dst.step / sizeof(ComplexF));
    float* re = split_.data();
    float* im = re + static_cast<std::size_t>(rows_) * half;
    col_fft_.forwardBatch(dst.ptr<ComplexF>(0), stride, 1, half, re, im);
    for (int r = 0; r < rows_; ++r) {
      ComplexF* d = dst.ptr<ComplexF>(r);
      for (int k = 0; k < half; ++k) d[k] = {re[r * half + k], im[r * half + k]};
    }
  }
  // The other columns by symmetry: X[r][c] = conj X[-r][-c].
  for (int r = 0; r < rows_; ++r) {
    ComplexF* d = dst.ptr<ComplexF>(r);
    const ComplexF* mirror = dst.ptr<ComplexF>((rows_ - r) % rows_);
    for (int c = half; c < cols_; ++c) d[c] = conj(mirror[cols_ - c]);
  }
}

void RealFft2d::forwardEachRow(const cv::Mat& src, cv::Mat& dst) {
  CV_Assert(src.type() == CV_32F && src.cols == cols_);
  dst.create(src.rows, cols_, CV_32FC2);
  rowPairsForward(src, dst);
  for (int r = 0; r < src.rows; ++r) {
    ComplexF* d = dst.ptr<ComplexF>(r);
    for (int c = cols_ / 2 + 1; c < cols_; ++c) d[c] = conj(d[cols_ - c]);
  }
}

// Columns 0 .. cols/2 inverted first (side by side); each row of the result is then
// conjugate-symmetric, so two rows a and b are inverted as one complex row A + i B, whose inverse
// is a + i b (all row pairs side by side).
void RealFft2d::inverse(const cv::Mat& src, cv::Mat& dst) {
  CV_Assert(src.type() == CV_32FC2 && src.rows == rows_ && src.cols == cols_);
  dst.create(rows_, cols_, CV_32F);
  const int half = cols_ / 2 + 1;
  const int pairs = (rows_ + 1) / 2;
  const int stride = static_cast<int>(src.step / sizeof(ComplexF));
  float* cre = split_.data();
  float* cim = cre + static_cast<std::size_t>(rows_) * half;
  col_fft_.inverseBatch(src.ptr<ComplexF>(0), stride, 1, half, cre, cim);
  auto column_out = [&](int r, int c) -> ComplexF {  // row r of the column pass, column c
    return c < half ? ComplexF{cre[r * half + c], cim[r * half + c]}
                    : conj({cre[r * half + cols_ - c], cim[r * half + cols_ - c]});
  };
  for (int q = 0; q < pairs; ++q) {
    const bool has_b = 2 * q + 1 < rows_;
    ComplexF* line = &pair_in_[static_cast<std::size_t>(q) * cols_];
    for (int c = 0; c < cols_; ++c) {
      const ComplexF a = column_out(2 * q, c);
      const ComplexF b = has_b ? column_out(2 * q + 1, c) : ComplexF{};
      line[c] = {a.re - b.im, a.im + b.re};
    }
  }
  float* re = split_.data();
  float* im = re + static_cast<std::size_t>(pairs) * cols_;
  row_fft_.inverseBatch(pair_in_.data(), 1, cols_, pairs, re, im);
  const float scale = 1.0f / static_cast<float>(rows_ * cols_);
  for (int q = 0; q < pairs; ++q) {
    float* da = dst.ptr<float>(2 * q);
    float* db = 2 * q + 1 < rows_ ? dst.ptr<float>(2 * q + 1) : nullptr;
    for (int j = 0; j < cols_; ++j) {
      da[j] = re[j * pairs + q] * scale;
      if (db) db[j] = im[j * pairs + q] * scale;
    }
  }
}

}  // namespace core
}  // namespace obstacle_tracker
