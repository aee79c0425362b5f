// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Resamples a window of a frame (any centre and size, also partly outside the frame) onto a
// patch of a given pixel size: bilinear, border replication. When the window is at least twice
// the patch, the covered part of the frame is first shrunk by an integer box filter (qx x qy
// pixels per sample) so that a large window is not aliased.
//
// Written out (not cv::warpAffine / cv::resize) because those allocate on every call, and the
// tracker allocates nothing per frame once its buffers exist (test_pipeline_memory): reserve()
// sizes the buffers, sample() then only writes into them.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace obstacle_tracker {
namespace core {

class PatchSampler {
 public:
  // Buffers for patches up to max_width x max_height taken from frames of this type and width.
  void reserve(int max_width, int max_height, int frame_type, int frame_width);

  // The frame window centred at `centre` with size `window` (frame pixels) -> dst (height x
  // width, the frame's type). dst is created only when its size or type differs.
  void sample(const cv::Mat& frame, cv::Point2f centre, cv::Size2f window, int width, int height,
              cv::Mat& dst);

 private:
  void shrinkBox(const cv::Mat& frame, int rx0, int ry0, int nw, int nh, int qx, int qy);
  template <int NC>
  void horizontalRow(const uchar* r, int width, float* out) const;
  const float* interpolatedRow(const uchar* src, size_t src_step, int row, int keep, int width, int nc);

  cv::Mat shrunk_;  // box-shrunk frame region for large windows
  std::vector<float> col_a_;
  std::vector<int> col_i0_, col_i1_, row_acc_;
  // The horizontal pass of the two source rows last used, and their row indices (-1: none).
  std::vector<float> cached_rows_[2];
  int cached_row_index_[2] = {-1, -1};
};

}  // namespace core
}  // namespace obstacle_tracker
