// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Frames with known motion for the KCF tests (test_kcf.cpp, test_kcf_robustness.cpp): textures
// rendered with exact sub-pixel affine maps, so the true position and scale are known.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace obstacle_tracker {
namespace test {


// A smooth random texture (band-limited noise), tileable by construction is not needed: frames are
// rendered from it with an exact sub-pixel affine map, so the "true" motion is known.
inline cv::Mat makeTexture(int size, int seed) {
  cv::Mat noise(size, size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat out;
  noise.convertTo(out, CV_8U);
  return out;
}

// Renders a frame: a background texture, and a target texture of side `side` * scale centred at
// (cx, cy). Sub-pixel positions and scales come from warpAffine with bilinear sampling.
inline cv::Mat renderFrame(const cv::Mat& bg, const cv::Mat& obj, cv::Size frame_size, double cx,
                    double cy, double side, int type) {
  cv::Mat frame;
  cv::resize(bg, frame, frame_size, 0, 0, cv::INTER_LINEAR);
  const double s = side / obj.cols;
  const cv::Matx23d m(s, 0.0, cx - 0.5 * side + 0.5 * s - 0.5, 0.0, s,
                      cy - 0.5 * side + 0.5 * s - 0.5);
  cv::Mat warped, mask;
  cv::warpAffine(obj, warped, m, frame_size, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  cv::Mat ones(obj.size(), CV_8U, cv::Scalar(255));
  cv::warpAffine(ones, mask, m, frame_size, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  // Alpha blend with the (anti-aliased) mask so the object's sub-pixel position is exact.
  cv::Mat f32, w32, b32;
  warped.convertTo(w32, CV_32F);
  frame.convertTo(b32, CV_32F);
  mask.convertTo(f32, CV_32F, 1.0 / 255.0);
  cv::Mat blended = w32.mul(f32) + b32.mul(1.0 - f32);
  blended.convertTo(frame, CV_8U);
  if (type == CV_8UC3) {
    cv::Mat colour;
    cv::cvtColor(frame, colour, cv::COLOR_GRAY2BGR);
    // Give the colour channels something different so the max-channel gradient matters.
    cv::Mat ch[3];
    cv::split(colour, ch);
    ch[0] = 255 - ch[0];
    cv::merge(ch, 3, colour);
    return colour;
  }
  return frame;
}

// The whole frame is one textured pattern translated by a known sub-pixel amount (bilinear
// warp of a smooth texture, so the shifted frame is the exact translate up to rounding to 8 bit).
inline cv::Mat shiftedPattern(const cv::Mat& tex, cv::Size fs, double dx, double dy, int type) {
  const cv::Matx23d m(1.0, 0.0, dx, 0.0, 1.0, dy);
  cv::Mat out;
  cv::warpAffine(tex, out, m, fs, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  if (type == CV_8UC3) {
    cv::Mat ch[3] = {255 - out, out, out / 2 + 60};
    cv::merge(ch, 3, out);
  }
  return out;
}

}  // namespace test
}  // namespace obstacle_tracker
