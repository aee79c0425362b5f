// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// fHOG's per-pixel stage (fhog.h): the gradient of the strongest channel and its nearest of 18
// directions, one row at a time. Private to the core (fhog.cpp).
#pragma once

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {
namespace fhog_detail {

// Per pixel of one row (nc = 1 or 3 interleaved channels; `up` and `down` are the rows above and
// below, the frame's edge replicated): the centred-difference gradient of the channel with the
// largest magnitude (ties keep the first channel) into gdx, gdy, and its squared magnitude into gm2.
void maxGradient(const uchar* row, const uchar* up, const uchar* down, int w, int nc, float* gdx,
                 float* gdy, float* gm2);

// Per pixel of one row: the nearest of the 18 directions (largest |dot| over the 9 axes, its sign
// picks the half) into gbin, and gm2 (squared magnitude) replaced by the magnitude. Bins are kept
// as floats so the loop runs in OpenCV's universal intrinsics.
void nearestDirections(const float* gdx, const float* gdy, float* gm2, float* gbin, int w);

}  // namespace fhog_detail
}  // namespace core
}  // namespace obstacle_tracker
