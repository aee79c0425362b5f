// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Low-level drawing for the scene generator, written with basic arithmetic only so the output is
// bit-identical across machines: anti-aliased polygon coverage, fractal value noise, sub-pixel
// image shifts, directional blur.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace scene {

// Coordinates convention: pixel (col, row) covers the square [col, col+1) x [row, row+1); its
// centre is (col + 0.5, row + 0.5).
//
// Adds the area coverage (0..1) of a simple or self-intersecting polygon (non-zero winding rule)
// to `cov`, a CV_32FC1 buffer whose pixel (0, 0) sits at image position `origin`. Coverage is
// exact along x (analytic span ends) and sampled with `subrows` sub-scanlines per pixel row
// along y. Only pixels of `cov` are touched; parts of the polygon outside it are ignored.
void addPolygonCoverage(const cv::Point2f* pts, int n, cv::Point origin, int subrows, cv::Mat& cov);

// Sub-scanlines that give good anti-aliasing for a shape of the given height in pixels.
int subrowsForHeight(float height_px);

// Fractal (multi-octave) value noise, roughly in [0, 1], written into out (CV_32FC1, its size
// is kept). Cell size of the first octave cell_x x cell_y pixels; each octave halves the cell
// and multiplies the amplitude by gain. Lattice values come from hashes of (seed, octave, cell),
// so a field is a pure function of its arguments; `origin` shifts the sampled window.
void fractalNoise(cv::Mat& out, float cell_x, float cell_y, int octaves, float gain,
                  std::uint64_t seed, cv::Point2f origin = cv::Point2f(0.0f, 0.0f));

// 1-D fractal value noise at x (roughly [0, 1]).
float fractalNoise1D(float x, float cell, int octaves, float gain, std::uint64_t seed);

// dst = src shifted by (-ox, -oy) with bilinear interpolation in fixed point (8-bit weights):
// dst(x, y) = src(x + ox, y + oy). dst gets the given size and src's type (CV_8UC1/3,
// CV_16UC1); the sampled window must lie inside src (throws std::invalid_argument otherwise).
void shiftCrop(const cv::Mat& src, double ox, double oy, cv::Size size, cv::Mat& dst);

// In-place directional (linear motion) blur: each pixel becomes the mean of the image sampled at
// the integer offsets round(k/K * (dx, dy)), k = 0..K, K = max(|dx|, |dy|) rounded (edges
// clamped). `scratch` is reused between calls. No effect when K == 0.
void directionalBlur(cv::Mat& img, float dx, float dy, std::vector<std::uint32_t>& scratch);

// Integer offsets used by directionalBlur (for ground truth bookkeeping).
std::vector<cv::Point> directionalBlurOffsets(float dx, float dy);

// Clamp helpers.
inline float clamp01(float v) { return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v); }
inline float smoothstep(float e0, float e1, float x) {
  const float t = clamp01((x - e0) / (e1 - e0));
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace scene
}  // namespace obstacle_tracker
