// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Minimum barrier distance (MBD) transforms with the image border as the seed set.
//
// The barrier of a path is (highest value on it) - (lowest value on it); the MBD of a pixel is the
// smallest barrier over all 4-connected paths from the pixel to the 1-pixel image border
// (Strand et al., CVIU 2013). FastMBD (Zhang, Sclaroff, Lin, Shen, Price, Mech, "Minimum Barrier
// Salient Object Detection at 80 FPS", ICCV 2015, Algorithm 1) approximates it with alternating
// forward / backward raster passes that keep, per pixel, the highest (U) and lowest (L) value of
// the pixel's current best path.
//
// Accuracy (checked in test_mbd.cpp): FastMBD never under-estimates (every value it reports is the
// barrier of a real path), so fastMbd >= exactMbd everywhere. It is exact when each pixel's best
// path is made of the raster scans' moves (e.g. separated rectangles on a flat background, closed
// rings); it is not exact in general (a best path that winds, e.g. along an isoline of a tilted
// plane, needs many direction changes). Once converged it over-estimates by less than 2*eps,
// eps = the largest difference between 4-neighbours (Zhang et al., Sec. 3, error bound); the test
// checks that bound on random smooth images.
#pragma once

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

// FastMBD on a CV_8UC1 or CV_8UC3 image (each channel transformed independently, interleaved:
// the three chains of a colour image run in the same serial sweep, which hides their latency).
// `dist` receives the barrier distances (same size and type as `image`); `upper` and `lower` are
// work buffers. All three are (re)created only when their size or type does not match, so
// calling again with the same size allocates nothing. passes >= 1; odd passes run top-left to
// bottom-right (neighbours up, left), even passes bottom-right to top-left (down, right).
// A pass that changes nothing means convergence (the state is then stable under both scan
// orders) and ends the loop early; returns the number of passes run.
// Throws std::invalid_argument for an empty image, another type, or passes < 1.
int fastMbd(const cv::Mat& image, int passes, cv::Mat& dist, cv::Mat& upper, cv::Mat& lower);

// Exact MBD by brute force (for tests; O(levels * N log N)): for every lower bound lo, the
// minimax path value from the border through pixels >= lo, minimised over lo <= I(x).
// CV_8UC1 in, CV_8UC1 out. Throws std::invalid_argument for an empty image or another type.
cv::Mat exactMbd(const cv::Mat& image);

}  // namespace core
}  // namespace obstacle_tracker
