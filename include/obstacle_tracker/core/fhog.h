// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Felzenszwalb HOG ("fHOG") per cell, for correlation filters, plus a grey-level channel.
//
// Written from Felzenszwalb, Girshick, McAllester, Ramanan, "Object Detection with
// Discriminatively Trained Part-Based Models", TPAMI 32(9), 2010, section 6 ("Features"):
// - per pixel, the centred-difference gradient of the colour channel with the largest magnitude;
// - its orientation snapped to one of 18 contrast-sensitive directions (20 degree bins);
// - each pixel votes its magnitude into the 4 nearest cells with bilinear weights;
// - each cell's histogram is normalised by the energy of each of the 4 2x2-cell blocks that
//   contain it (energy = squared sum of the contrast-insensitive histogram), values truncated at
//   0.2; the 4 x 27 normalised values are projected as in the paper's analytic PCA: 18 sensitive
//   + 9 insensitive orientation channels (each summed over the 4 normalisations, times 0.5) and
//   4 texture channels (each normalisation summed over the 18 sensitive bins, times 0.2357).
// Unlike the paper's detector, no border cells are dropped: the output has one cell per
// `cell` x `cell` block of the patch, and block energies at the grid border use the nearest cell
// (replication), which a correlation filter with a cosine window needs.
// Channel 31 is the mean grey level of the cell, in [-0.5, 0.5].
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

class FhogExtractor {
 public:
  static constexpr int kOrientations = 18;      // contrast-sensitive bins
  static constexpr int kHogChannels = 31;       // 18 + 9 + 4
  static constexpr int kChannels = 32;          // + grey level
  static constexpr int kGreyChannel = 31;
  static constexpr float kTruncation = 0.2f;

  // Computes the features of `patch` (CV_8UC1 or CV_8UC3 BGR) with square cells of `cell` pixels.
  // The grid is (patch.rows / cell) x (patch.cols / cell) cells (integer division; at least 1x1).
  // `out` becomes CV_32F of (kChannels * rows) x cols, planar: channel c is the contiguous block of
  // rows [c * rows, (c + 1) * rows). Buffers are reused: no allocation once sizes stop changing.
  // Throws std::invalid_argument for an empty patch, another type, a cell < 1 or a patch smaller
  // than one cell.
  void compute(const cv::Mat& patch, int cell, cv::Mat& out);

 private:
  void accumulateRow(const uchar* row, int y, int cell, int nc, int rows, int cols);
  void normalise(int rows, int cols, int cell, cv::Mat& out);
  void blockNorms(int rows, int cols);

  std::vector<float> hist_;   // 18 orientation planes of rows x cols cells
  std::vector<float> energy_; // rows x cols: sum over 9 of (h[o] + h[o+9])^2
  std::vector<float> grey_;   // rows x cols grey sums
  std::vector<float> block_norm_;  // (rows + 1) x (cols + 1) blocks (see blockNorms())
  std::vector<float> texture_;     // 4 x cols: one row of cells' texture sums
  // Per-column tables and per-row scratch (see compute()).
  std::vector<int> col_cell_;
  std::vector<float> col_w0_;
  std::vector<float> row_dx_, row_dy_, row_m2_, row_bin_;
};

}  // namespace core
}  // namespace obstacle_tracker
