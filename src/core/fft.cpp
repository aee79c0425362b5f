// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Portable FFTs (fft.h): the same bits on every machine, for the correlation filter.
#include "obstacle_tracker/core/fft.h"

#include <algorithm>
#include <cmath>

namespace obstacle_tracker {
namespace core {

namespace {

inline ComplexF mul(ComplexF a, ComplexF b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
inline ComplexF add(ComplexF a, ComplexF b) { return {a.re + b.re, a.im + b.im}; }
inline ComplexF sub(ComplexF a, ComplexF b) { return {a.re - b.re, a.im - b.im}; }
inline ComplexF conj(ComplexF a) { return {a.re, -a.im}; }

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

// The butterflies of ComplexFft::butterfly, one per radix, on `count` transforms at once in the
// split layout (element i of transform b at re[i * count + b], im[i * count + b]): `p` transforms
// of length m (elements q m .. q m + m - 1) into one of length p m, with
// tw[j fstride] = e^(-+2 pi i j / (p m)). Each transform gets the operations of the one-at-a-time
// formula, in its order, through the same helpers (mul, add, sub); the loops over b only let the
// compiler run the transforms side by side in vector registers, which does not change a bit.
struct Split {
  float* re;
  float* im;
  int count;
  ComplexF get(long i, int b) const { return {re[i * count + b], im[i * count + b]}; }
  void set(long i, int b, ComplexF v) const {
    re[i * count + b] = v.re;
    im[i * count + b] = v.im;
  }
};

void butterfly2(const Split& x, int fstride, int m, const std::vector<ComplexF>& tw) {
  for (int u = 0; u < m; ++u) {
    const ComplexF w = tw[static_cast<std::size_t>(u * fstride)];
    for (int b = 0; b < x.count; ++b) {
      const ComplexF a0 = x.get(u, b);
      const ComplexF t = mul(x.get(u + m, b), w);
      x.set(u + m, b, sub(a0, t));
      x.set(u, b, add(a0, t));
    }
  }
}

void butterfly4(const Split& x, int fstride, int m, const std::vector<ComplexF>& tw) {
  // -i (forward) or +i (inverse) is the quarter turn tw[fstride m].
  const bool forward = tw[static_cast<std::size_t>(fstride * m)].im < 0.0f;
  for (int u = 0; u < m; ++u) {
    const ComplexF w1 = tw[static_cast<std::size_t>(u * fstride)];
    const ComplexF w2 = tw[static_cast<std::size_t>(2 * u * fstride)];
    const ComplexF w3 = tw[static_cast<std::size_t>(3 * u * fstride)];
    for (int b = 0; b < x.count; ++b) {
      const ComplexF a0 = x.get(u, b);
      const ComplexF a1 = mul(x.get(u + m, b), w1);
      const ComplexF a2 = mul(x.get(u + 2 * m, b), w2);
      const ComplexF a3 = mul(x.get(u + 3 * m, b), w3);
      const ComplexF s02 = add(a0, a2), d02 = sub(a0, a2);
      const ComplexF s13 = add(a1, a3), d13 = sub(a1, a3);
      // d13 times the quarter turn: -i d13 = (d13.im, -d13.re) forward, +i d13 inverse.
      const ComplexF rot = forward ? ComplexF{d13.im, -d13.re} : ComplexF{-d13.im, d13.re};
      x.set(u, b, add(s02, s13));
      x.set(u + m, b, add(d02, rot));
      x.set(u + 2 * m, b, sub(s02, s13));
      x.set(u + 3 * m, b, sub(d02, rot));
    }
  }
}

void butterfly3(const Split& x, int fstride, int m, const std::vector<ComplexF>& tw) {
  // w = tw[fstride m] = e^(-+2 pi i / 3) = (-1/2, -+sqrt(3)/2).
  const float h = tw[static_cast<std::size_t>(fstride * m)].im;
  for (int u = 0; u < m; ++u) {
    const ComplexF w1 = tw[static_cast<std::size_t>(u * fstride)];
    const ComplexF w2 = tw[static_cast<std::size_t>(2 * u * fstride)];
    for (int b = 0; b < x.count; ++b) {
      const ComplexF a0 = x.get(u, b);
      const ComplexF a1 = mul(x.get(u + m, b), w1);
      const ComplexF a2 = mul(x.get(u + 2 * m, b), w2);
      const ComplexF s = add(a1, a2), d = sub(a1, a2);
      const ComplexF mid = {a0.re - 0.5f * s.re, a0.im - 0.5f * s.im};
      const ComplexF rot = {-h * d.im, h * d.re};  // i h d
      x.set(u, b, add(a0, s));
      x.set(u + m, b, add(mid, rot));
      x.set(u + 2 * m, b, sub(mid, rot));
    }
  }
}

void butterfly5(const Split& x, int fstride, int m, const std::vector<ComplexF>& tw) {
  // w = tw[fstride m] = e^(-+2 pi i / 5), w^2; w^3 and w^4 are their conjugates, so the sums
  // pair a1 with a4 and a2 with a3.
  const ComplexF w1 = tw[static_cast<std::size_t>(fstride * m)];
  const ComplexF w2 = tw[static_cast<std::size_t>(2 * fstride * m)];
  for (int u = 0; u < m; ++u) {
    const ComplexF t1 = tw[static_cast<std::size_t>(u * fstride)];
    const ComplexF t2 = tw[static_cast<std::size_t>(2 * u * fstride)];
    const ComplexF t3 = tw[static_cast<std::size_t>(3 * u * fstride)];
    const ComplexF t4 = tw[static_cast<std::size_t>(4 * u * fstride)];
    for (int b = 0; b < x.count; ++b) {
      const ComplexF a0 = x.get(u, b);
      const ComplexF a1 = mul(x.get(u + m, b), t1);
      const ComplexF a2 = mul(x.get(u + 2 * m, b), t2);
      const ComplexF a3 = mul(x.get(u + 3 * m, b), t3);
      const ComplexF a4 = mul(x.get(u + 4 * m, b), t4);
      const ComplexF s14 = add(a1, a4), d14 = sub(a1, a4);
      const ComplexF s23 = add(a2, a3), d23 = sub(a2, a3);
      const ComplexF r1 = {a0.re + s14.re * w1.re + s23.re * w2.re, a0.im + s14.im * w1.re + s23.im * w2.re};
      const ComplexF i1 = {d14.im * w1.im + d23.im * w2.im, -(d14.re * w1.im) - d23.re * w2.im};
      const ComplexF r2 = {a0.re + s14.re * w2.re + s23.re * w1.re, a0.im + s14.im * w2.re + s23.im * w1.re};
      const ComplexF i2 = {d23.im * w1.im - d14.im * w2.im, d14.re * w2.im - d23.re * w1.im};
      x.set(u, b, add(a0, add(s14, s23)));
      x.set(u + m, b, sub(r1, i1));
      x.set(u + 2 * m, b, add(r2, i2));
      x.set(u + 3 * m, b, sub(r2, i2));
      x.set(u + 4 * m, b, add(r1, i1));
    }
  }
}

// Any other radix: the direct sum over the p inputs (p is a prime above 5 here); in holds the p
// inputs of one u (p x count, split).
void butterflyDirect(const Split& x, int fstride, int m, int p, const std::vector<ComplexF>& tw, const Split& in) {
  const long n = static_cast<long>(p) * m * fstride;
  for (int u = 0; u < m; ++u) {
    for (int q = 0; q < p; ++q) {
      for (int b = 0; b < x.count; ++b) in.set(q, b, x.get(u + static_cast<long>(q) * m, b));
    }
    for (int q1 = 0; q1 < p; ++q1) {
      const long k = u + static_cast<long>(q1) * m;
      for (int b = 0; b < x.count; ++b) x.set(k, b, in.get(0, b));
      long index = 0;
      for (int q = 1; q < p; ++q) {
        index += fstride * k;
        if (index >= n) index -= n;
        const ComplexF w = tw[static_cast<std::size_t>(index)];
        for (int b = 0; b < x.count; ++b) x.set(k, b, add(x.get(k, b), mul(in.get(q, b), w)));
      }
    }
  }
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
  for (int p : radices(n)) {
    span /= p;
    stages_.push_back({p, span});
  }
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

void ComplexFft::run(const ComplexF* in, int in_stride, ComplexF* out, const std::vector<ComplexF>& tw) const {
  single_.resize(2 * static_cast<std::size_t>(n_));
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
      scratch_.resize(2 * static_cast<std::size_t>(p) * count);
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
}

// Row spectra, columns 0 .. cols/2, two real rows per complex transform: with z = a + i b,
// A[k] = (Z[k] + conj Z[-k]) / 2 and B[k] = (Z[k] - conj Z[-k]) / (2 i). All row pairs are
// transformed side by side (ComplexFft::forwardBatch).
void RealFft2d::rowPairsForward(const cv::Mat& src, cv::Mat& dst) {
  const int half = cols_ / 2 + 1;
  const int pairs = (src.rows + 1) / 2;
  pair_in_.resize(static_cast<std::size_t>(pairs) * cols_);
  split_.resize(std::max(split_.size(), 2 * pair_in_.size()));
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
