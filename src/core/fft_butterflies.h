// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The portable FFT's complex arithmetic and butterflies (fft.h), shared by fft.cpp and
// fft_butterflies.cpp. Private to the core.
#pragma once

#include <vector>

#include "obstacle_tracker/core/fft.h"

namespace obstacle_tracker {
namespace core {
namespace fft_detail {

inline ComplexF mul(ComplexF a, ComplexF b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
inline ComplexF add(ComplexF a, ComplexF b) { return {a.re + b.re, a.im + b.im}; }
inline ComplexF sub(ComplexF a, ComplexF b) { return {a.re - b.re, a.im - b.im}; }
inline ComplexF conj(ComplexF a) { return {a.re, -a.im}; }

// `count` transforms side by side: element i of transform b at re[i * count + b], im[i * count + b].
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

// The butterflies of ComplexFft::butterfly, one per radix, on `count` transforms at once in the
// split layout (element i of transform b at re[i * count + b], im[i * count + b]): `p` transforms
// of length m (elements q m .. q m + m - 1) into one of length p m, with
// tw[j fstride] = e^(-+2 pi i j / (p m)). Each transform gets the operations of the one-at-a-time
// formula, in its order, through the same helpers (mul, add, sub); the loops over b only let the
// compiler run the transforms side by side in vector registers, which does not change a bit.
void butterfly2(const Split& x, int fstride, int m, const std::vector<ComplexF>& tw);
void butterfly3(const Split& x, int fstride, int m, const std::vector<ComplexF>& tw);
void butterfly4(const Split& x, int fstride, int m, const std::vector<ComplexF>& tw);
void butterfly5(const Split& x, int fstride, int m, const std::vector<ComplexF>& tw);
// Any other radix p (a prime above 5): the direct sum; `in` holds p x count values of scratch.
void butterflyDirect(const Split& x, int fstride, int m, int p, const std::vector<ComplexF>& tw, const Split& in);

}  // namespace fft_detail
}  // namespace core
}  // namespace obstacle_tracker
