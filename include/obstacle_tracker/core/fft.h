// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Discrete Fourier transforms of our own, for the correlation filter (kcf.h) and its DSST scale
// filter. Why not cv::dft: OpenCV's x86-64 build computes its butterflies with SSE, its arm64
// build in plain C (and with fused multiply-adds), so the same spectrum differs in the last bits
// between the two; the tracking loop's decisions (a peak above a threshold, the best of three
// scales) then flip and the same frames are tracked differently on the drone's ARM64 computer
// and on the x86-64 machine the figures come from (docs/portability.md). Here every sum is taken
// in one fixed order, in float, with one rounding per operation (the project builds with
// -ffp-contract=off), and the twiddle factors are computed from a series of our own rather than
// the C library's sin/cos: the same input gives the same bits on every machine.
//
// The complex transform is a mixed-radix decimation-in-time Cooley-Tukey FFT (Cooley & Tukey
// 1965; the stages as in KISS FFT, Borgerding, BSD-3-Clause): radix 4, 2, 3 and 5 butterflies
// written out, any other prime factor by its direct sum, so any length works and the lengths the
// filter uses (cv::getOptimalDFTSize: 2^a 3^b 5^c) cost O(n log n). Real input is transformed two
// rows at a time as one complex row (x_a + i x_b), and only the non-redundant half of the columns
// is transformed; the other half of the spectrum follows from its conjugate symmetry. The row
// pairs, and then the columns, are transformed side by side in a split (real / imaginary) layout:
// each transform gets the same operations in the same order as alone, and the loops across them
// run in vector registers.
//
// Layouts match what the filter used from OpenCV: forward() gives the full complex spectrum
// (CV_32FC2, rows x cols, as cv::dft with DFT_COMPLEX_OUTPUT), inverse() takes a conjugate-
// symmetric spectrum of that layout and gives the real signal scaled by 1 / (rows cols) (as
// DFT_INVERSE | DFT_REAL_OUTPUT | DFT_SCALE). Plans own their scratch, sized by configure(): no
// heap allocation per transform (forwardEachRow on more rows than configured grows it once), and
// one plan must not be used by two threads at once.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

struct ComplexF {
  float re = 0.0f;
  float im = 0.0f;
};

// e^(-2 pi i k / n) (forward twiddle), correctly rounded to float on every machine: the angle is
// reduced to [0, pi/4] exactly in integers and its cosine and sine summed as Taylor series in
// double. Exposed for the tests.
ComplexF unitRootTurn(long k, long n);

// A complex DFT of one length: out[k] = sum_j in[j] e^(-+2 pi i j k / n), unscaled.
class ComplexFft {
 public:
  explicit ComplexFft(int n = 1) { configure(n); }
  // Prepares length n (>= 1); nothing is done when it already has that length.
  void configure(int n);
  int size() const { return n_; }
  // in: n values spaced in_stride ComplexF apart; out: n contiguous values (not aliasing in).
  void forward(const ComplexF* in, int in_stride, ComplexF* out) const { run(in, in_stride, out, forward_); }
  void inverse(const ComplexF* in, int in_stride, ComplexF* out) const { run(in, in_stride, out, inverse_); }
  // `count` transforms side by side, the same bits as one at a time: element i of transform b is
  // read from in[i * in_stride + b * batch_stride] and written, split, to re[i * count + b] and
  // im[i * count + b] (n * count floats each, not aliasing in).
  void forwardBatch(const ComplexF* in, int in_stride, int batch_stride, int count, float* re, float* im) const {
    runBatch(in, in_stride, batch_stride, count, re, im, forward_);
  }
  void inverseBatch(const ComplexF* in, int in_stride, int batch_stride, int count, float* re, float* im) const {
    runBatch(in, in_stride, batch_stride, count, re, im, inverse_);
  }
  // Makes room for batches of up to `count` transforms (a larger batch grows it on its first call).
  void reserveBatch(int count) const;

 private:
  struct Stage {
    int radix;
    int span;  // length of each sub-transform combined by this stage's butterflies
  };
  void run(const ComplexF* in, int in_stride, ComplexF* out, const std::vector<ComplexF>& twiddles) const;
  void runBatch(const ComplexF* in, int in_stride, int batch_stride, int count, float* re, float* im,
                const std::vector<ComplexF>& twiddles) const;
  void butterfly(float* re, float* im, int count, int fstride, int span, int radix,
                 const std::vector<ComplexF>& tw) const;

  int n_ = 0;
  std::vector<Stage> stages_;
  std::vector<ComplexF> forward_;  // e^(-2 pi i k / n)
  std::vector<ComplexF> inverse_;  // e^(+2 pi i k / n)
  std::vector<int> input_order_;   // the input index each output position starts from
  int widest_radix_ = 1;
  mutable std::vector<float> scratch_;  // the generic butterfly's inputs (split)
  mutable std::vector<float> single_;   // run()'s split output
};

// Real 2-D transforms of one size (rows x cols), in OpenCV's layouts (see above).
class RealFft2d {
 public:
  RealFft2d() { configure(1, 1); }
  // Prepares the size; nothing is done when it already has it.
  void configure(int rows, int cols);
  int rows() const { return rows_; }
  int cols() const { return cols_; }

  // src CV_32F rows x cols -> dst CV_32FC2 rows x cols, the full spectrum (dst is created).
  void forward(const cv::Mat& src, cv::Mat& dst);
  // The 1-D spectrum of each row of src (CV_32F, any number of rows, cols columns) -> dst
  // CV_32FC2 of the same size (cv::dft's DFT_ROWS | DFT_COMPLEX_OUTPUT).
  void forwardEachRow(const cv::Mat& src, cv::Mat& dst);
  // src CV_32FC2 rows x cols, conjugate-symmetric -> dst CV_32F rows x cols, scaled by
  // 1 / (rows cols). Only the columns 0 .. cols/2 of src are read.
  void inverse(const cv::Mat& src, cv::Mat& dst);

 private:
  void rowPairsForward(const cv::Mat& src, cv::Mat& dst);

  int rows_ = 0, cols_ = 0;
  ComplexFft row_fft_, col_fft_;
  std::vector<ComplexF> pair_in_;  // row pairs as complex rows a + i b
  std::vector<float> split_;       // a batch's split output (ComplexFft::forwardBatch)
};

}  // namespace core
}  // namespace obstacle_tracker
