// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// tool_count_colour IMAGE B G R [TOLERANCE]: prints how many pixels of IMAGE are within TOLERANCE
// (default 40, per channel) of the BGR colour. Exit 2 when the image cannot be read.
#include <cstdio>
#include <cstdlib>

#include <opencv2/imgcodecs.hpp>

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s IMAGE B G R [TOLERANCE]\n", argv[0]);
    return 2;
  }
  const cv::Mat image = cv::imread(argv[1], cv::IMREAD_COLOR);
  if (image.empty()) {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 2;
  }
  const int b = std::atoi(argv[2]), g = std::atoi(argv[3]), r = std::atoi(argv[4]);
  const int tol = argc > 5 ? std::atoi(argv[5]) : 40;
  long count = 0;
  for (int y = 0; y < image.rows; ++y) {
    const cv::Vec3b* row = image.ptr<cv::Vec3b>(y);
    for (int x = 0; x < image.cols; ++x) {
      if (std::abs(row[x][0] - b) <= tol && std::abs(row[x][1] - g) <= tol && std::abs(row[x][2] - r) <= tol) ++count;
    }
  }
  std::printf("%ld\n", count);
  return 0;
}
