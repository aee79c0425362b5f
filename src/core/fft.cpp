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

// The butterflies of ComplexFft::butterfly, one per radix: `p` transforms of length m (at
// out + q m) into one of length p m, with tw[j fstride] = e^(-+2 pi i j / (p m)).
void butterfly2(ComplexF* out, int fstride, int m, const std::vector<ComplexF>& tw) {
  for (int u = 0; u < m; ++u) {
    const ComplexF t = mul(out[u + m], tw[static_cast<std::size_t>(u * fstride)]);
    out[u + m] = sub(out[u], t);
    out[u] = add(out[u], t);
  }
}

void butterfly4(ComplexF* out, int fstride, int m, const std::vector<ComplexF>& tw) {
  // -i (forward) or +i (inverse) is the quarter turn tw[fstride m].
  const bool forward = tw[static_cast<std::size_t>(fstride * m)].im < 0.0f;
  for (int u = 0; u < m; ++u) {
    const ComplexF a0 = out[u];
    const ComplexF a1 = mul(out[u + m], tw[static_cast<std::size_t>(u * fstride)]);
    const ComplexF a2 = mul(out[u + 2 * m], tw[static_cast<std::size_t>(2 * u * fstride)]);
    const ComplexF a3 = mul(out[u + 3 * m], tw[static_cast<std::size_t>(3 * u * fstride)]);
    const ComplexF s02 = add(a0, a2), d02 = sub(a0, a2);
    const ComplexF s13 = add(a1, a3), d13 = sub(a1, a3);
    // d13 times the quarter turn: -i d13 = (d13.im, -d13.re) forward, +i d13 inverse.
    const ComplexF rot = forward ? ComplexF{d13.im, -d13.re} : ComplexF{-d13.im, d13.re};
    out[u] = add(s02, s13);
    out[u + m] = add(d02, rot);
    out[u + 2 * m] = sub(s02, s13);
    out[u + 3 * m] = sub(d02, rot);
  }
}

void butterfly3(ComplexF* out, int fstride, int m, const std::vector<ComplexF>& tw) {
  // w = tw[fstride m] = e^(-+2 pi i / 3) = (-1/2, -+sqrt(3)/2).
  const float h = tw[static_cast<std::size_t>(fstride * m)].im;
  for (int u = 0; u < m; ++u) {
    const ComplexF a0 = out[u];
    const ComplexF a1 = mul(out[u + m], tw[static_cast<std::size_t>(u * fstride)]);
    const ComplexF a2 = mul(out[u + 2 * m], tw[static_cast<std::size_t>(2 * u * fstride)]);
    const ComplexF s = add(a1, a2), d = sub(a1, a2);
    const ComplexF mid = {a0.re - 0.5f * s.re, a0.im - 0.5f * s.im};
    const ComplexF rot = {-h * d.im, h * d.re};  // i h d
    out[u] = add(a0, s);
    out[u + m] = add(mid, rot);
    out[u + 2 * m] = sub(mid, rot);
  }
}

void butterfly5(ComplexF* out, int fstride, int m, const std::vector<ComplexF>& tw) {
  // w = tw[fstride m] = e^(-+2 pi i / 5), w^2; w^3 and w^4 are their conjugates, so the sums
  // pair a1 with a4 and a2 with a3.
  const ComplexF w1 = tw[static_cast<std::size_t>(fstride * m)];
  const ComplexF w2 = tw[static_cast<std::size_t>(2 * fstride * m)];
  for (int u = 0; u < m; ++u) {
    const ComplexF a0 = out[u];
    const ComplexF a1 = mul(out[u + m], tw[static_cast<std::size_t>(u * fstride)]);
    const ComplexF a2 = mul(out[u + 2 * m], tw[static_cast<std::size_t>(2 * u * fstride)]);
    const ComplexF a3 = mul(out[u + 3 * m], tw[static_cast<std::size_t>(3 * u * fstride)]);
    const ComplexF a4 = mul(out[u + 4 * m], tw[static_cast<std::size_t>(4 * u * fstride)]);
    const ComplexF s14 = add(a1, a4), d14 = sub(a1, a4);
    const ComplexF s23 = add(a2, a3), d23 = sub(a2, a3);
    const ComplexF r1 = {a0.re + s14.re * w1.re + s23.re * w2.re, a0.im + s14.im * w1.re + s23.im * w2.re};
    const ComplexF i1 = {d14.im * w1.im + d23.im * w2.im, -(d14.re * w1.im) - d23.re * w2.im};
    const ComplexF r2 = {a0.re + s14.re * w2.re + s23.re * w1.re, a0.im + s14.im * w2.re + s23.im * w1.re};
    const ComplexF i2 = {d23.im * w1.im - d14.im * w2.im, d14.re * w2.im - d23.re * w1.im};
    out[u] = add(a0, add(s14, s23));
    out[u + m] = sub(r1, i1);
    out[u + 2 * m] = add(r2, i2);
    out[u + 3 * m] = sub(r2, i2);
    out[u + 4 * m] = add(r1, i1);
  }
}

// Any other radix: the direct sum over the p inputs (p is a prime above 5 here); x holds p values.
void butterflyDirect(ComplexF* out, int fstride, int m, int p, const std::vector<ComplexF>& tw, ComplexF* x) {
  const long n = static_cast<long>(p) * m * fstride;
  for (int u = 0; u < m; ++u) {
    for (int q = 0; q < p; ++q) x[q] = out[u + q * m];
    for (int q1 = 0; q1 < p; ++q1) {
      const long k = u + static_cast<long>(q1) * m;
      ComplexF acc = x[0];
      long index = 0;
      for (int q = 1; q < p; ++q) {
        index += fstride * k;
        if (index >= n) index -= n;
        acc = add(acc, mul(x[q], tw[static_cast<std::size_t>(index)]));
      }
      out[k] = acc;
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
  int widest = 1;
  for (int p : radices(n)) {
    span /= p;
    stages_.push_back({p, span});
    widest = std::max(widest, p);
  }
  forward_.resize(static_cast<std::size_t>(n));
  inverse_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    forward_[static_cast<std::size_t>(k)] = unitRootTurn(k, n);
    inverse_[static_cast<std::size_t>(k)] = conj(forward_[static_cast<std::size_t>(k)]);
  }
  scratch_.resize(static_cast<std::size_t>(widest));
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
  for (int i = 0; i < n_; ++i) out[i] = in[static_cast<long>(input_order_[static_cast<std::size_t>(i)]) * in_stride];
  // Innermost stage first: stage s combines, in each of its fstride sub-problems, `radix`
  // transforms of length `span` into one of length radix span.
  for (std::size_t s = stages_.size(); s-- > 0;) {
    const int p = stages_[s].radix, m = stages_[s].span;
    const int fstride = n_ / (p * m);
    for (int j = 0; j < fstride; ++j) butterfly(out + j * p * m, fstride, m, p, tw);
  }
}

// Combines `radix` transforms of length `span` (at out + q span) into one of length radix span.
// tw[j fstride] = e^(-+2 pi i j / (radix span)).
void ComplexFft::butterfly(ComplexF* out, int fstride, int m, int p, const std::vector<ComplexF>& tw) const {
  switch (p) {
    case 2: return butterfly2(out, fstride, m, tw);
    case 3: return butterfly3(out, fstride, m, tw);
    case 4: return butterfly4(out, fstride, m, tw);
    case 5: return butterfly5(out, fstride, m, tw);
    default: return butterflyDirect(out, fstride, m, p, tw, scratch_.data());
  }
}

void RealFft2d::configure(int rows, int cols) {
  CV_Assert(rows >= 1 && cols >= 1);
  if (rows == rows_ && cols == cols_) return;
  rows_ = rows;
  cols_ = cols;
  row_fft_.configure(cols);
  col_fft_.configure(rows);
  const std::size_t line = static_cast<std::size_t>(std::max(rows, cols));
  line_in_.resize(line);
  line_out_.resize(line);
  half_.resize(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols / 2 + 1));
}

// Row spectra, columns 0 .. cols/2, two real rows per complex transform: with z = a + i b,
// A[k] = (Z[k] + conj Z[-k]) / 2 and B[k] = (Z[k] - conj Z[-k]) / (2 i).
void RealFft2d::rowPairsForward(const cv::Mat& src, cv::Mat& dst) {
  const int half = cols_ / 2 + 1;
  for (int r = 0; r < src.rows; r += 2) {
    const float* a = src.ptr<float>(r);
    const float* b = r + 1 < src.rows ? src.ptr<float>(r + 1) : nullptr;
    for (int j = 0; j < cols_; ++j) line_in_[static_cast<std::size_t>(j)] = {a[j], b ? b[j] : 0.0f};
    row_fft_.forward(line_in_.data(), 1, line_out_.data());
    ComplexF* da = dst.ptr<ComplexF>(r);
    ComplexF* db = b ? dst.ptr<ComplexF>(r + 1) : nullptr;
    for (int k = 0; k < half; ++k) {
      const ComplexF z = line_out_[static_cast<std::size_t>(k)];
      const ComplexF zc = conj(line_out_[static_cast<std::size_t>((cols_ - k) % cols_)]);
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
    const int stride = static_cast<int>(dst.step / sizeof(ComplexF));
    ComplexF* base = dst.ptr<ComplexF>(0);
    for (int k = 0; k < half; ++k) {
      col_fft_.forward(base + k, stride, line_out_.data());
      for (int r = 0; r < rows_; ++r) base[r * stride + k] = line_out_[static_cast<std::size_t>(r)];
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

// Columns 0 .. cols/2 inverted first; each row of the result is then conjugate-symmetric, so two
// rows a and b are inverted as one complex row A + i B, whose inverse is a + i b.
void RealFft2d::inverse(const cv::Mat& src, cv::Mat& dst) {
  CV_Assert(src.type() == CV_32FC2 && src.rows == rows_ && src.cols == cols_);
  dst.create(rows_, cols_, CV_32F);
  const int half = cols_ / 2 + 1;
  const int stride = static_cast<int>(src.step / sizeof(ComplexF));
  const ComplexF* base = src.ptr<ComplexF>(0);
  for (int k = 0; k < half; ++k) {
    col_fft_.inverse(base + k, stride, line_out_.data());
    for (int r = 0; r < rows_; ++r) half_[static_cast<std::size_t>(r * half + k)] = line_out_[static_cast<std::size_t>(r)];
  }
  const float scale = 1.0f / static_cast<float>(rows_ * cols_);
  for (int r = 0; r < rows_; r += 2) {
    const ComplexF* ya = &half_[static_cast<std::size_t>(r * half)];
    const ComplexF* yb = r + 1 < rows_ ? &half_[static_cast<std::size_t>((r + 1) * half)] : nullptr;
    for (int c = 0; c < cols_; ++c) {
      const ComplexF a = c < half ? ya[c] : conj(ya[cols_ - c]);
      const ComplexF b = yb ? (c < half ? yb[c] : conj(yb[cols_ - c])) : ComplexF{};
      line_in_[static_cast<std::size_t>(c)] = {a.re - b.im, a.im + b.re};
    }
    row_fft_.inverse(line_in_.data(), 1, line_out_.data());
    float* da = dst.ptr<float>(r);
    float* db = yb ? dst.ptr<float>(r + 1) : nullptr;
    for (int j = 0; j < cols_; ++j) {
      da[j] = line_out_[static_cast<std::size_t>(j)].re * scale;
      if (db) db[j] = line_out_[static_cast<std::size_t>(j)].im * scale;
    }
  }
}

}  // namespace core
}  // namespace obstacle_tracker
