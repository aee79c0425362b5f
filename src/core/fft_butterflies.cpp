// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The portable FFT's butterflies (fft_butterflies.h), one per radix, on transforms side by side.
#include "fft_butterflies.h"

namespace obstacle_tracker {
namespace core {
namespace fft_detail {

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

// The p inputs of one u are copied to `in` first: the sums overwrite them.
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

}  // namespace fft_detail
}  // namespace core
}  // namespace obstacle_tracker
