// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// CameraGeometry (camera_geometry.h) on the camera_info forms drivers publish beyond the known
// answers of test_ros_conversion.cpp: all-zero P and R, a P that differs from K, a stereo
// baseline, ROI with binning, the equidistant model, and the refusals of R and P; and the
// camera_info pinholeCameraInfo builds.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "obstacle_tracker/ros/camera_geometry.h"

using obstacle_tracker::bridge::CameraGeometry;

namespace {

// 640x480, f = 500, principal point at the centre, plumb_bob with some barrel distortion; R and P
// left all-zero as many drivers publish them.
sensor_msgs::CameraInfo distortedCamera() {
  sensor_msgs::CameraInfo info;
  info.width = 640;
  info.height = 480;
  info.K = {500.0, 0.0, 319.5, 0.0, 500.0, 239.5, 0.0, 0.0, 1.0};
  info.distortion_model = "plumb_bob";
  info.D = {-0.2, 0.05, 0.001, -0.002, 0.0};
  return info;
}

CameraGeometry usable(const sensor_msgs::CameraInfo& info) {
  CameraGeometry cam;
  std::string error;
  EXPECT_TRUE(cam.setCameraInfo(info, &error)) << error;
  return cam;
}

// Corner points spread over a 640x480 image.
std::vector<cv::Point2d> grid() {
  std::vector<cv::Point2d> points;
  for (double v : {1.0, 120.0, 240.0, 355.5, 479.0}) {
    for (double u : {1.0, 160.25, 320.0, 480.0, 639.0}) points.emplace_back(u, v);
  }
  return points;
}

void expectSameRays(const CameraGeometry& a, const CameraGeometry& b, double tolerance) {
  for (const cv::Point2d& p : grid()) {
    const cv::Vec3d ra = a.ray(p.x, p.y), rb = b.ray(p.x, p.y);
    EXPECT_LT(cv::norm(ra - rb), tolerance) << "at (" << p.x << ", " << p.y << ")";
  }
}

}  // namespace

TEST(CameraGeometryImageGeometry, AllZeroPIsKAndAllZeroRIsTheIdentity) {
  const sensor_msgs::CameraInfo zeros = distortedCamera();
  sensor_msgs::CameraInfo explicit_info = zeros;
  explicit_info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  explicit_info.P = {500.0, 0.0, 319.5, 0.0, 0.0, 500.0, 239.5, 0.0, 0.0, 0.0, 1.0, 0.0};
  const CameraGeometry a = usable(zeros), b = usable(explicit_info);
  expectSameRays(a, b, 1e-12);
  // Rays are finite unit vectors, right of the centre is +x.
  const cv::Vec3d r = a.ray(600.0, 240.0);
  EXPECT_NEAR(cv::norm(r), 1.0, 1e-12);
  EXPECT_GT(r[0], 0.1);

  // Without distortion an all-zero P still gives the exact pinhole answer.
  sensor_msgs::CameraInfo pinhole = zeros;
  pinhole.D.clear();
  const cv::Vec3d c = usable(pinhole).ray(320.0 + 500.0, 240.0);
  EXPECT_NEAR(c[0], 1.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(c[1], 0.0, 1e-12);
}

TEST(CameraGeometryImageGeometry, PAndStereoBaselineDoNotChangeTheRay) {
  // A calibration's P often differs from K (alpha: a rectified image scaled to keep the valid
  // pixels); with a distorted image P only names the intermediate rectified pixel.
  sensor_msgs::CameraInfo scaled = distortedCamera();
  scaled.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  scaled.P = {430.0, 0.0, 310.0, 0.0, 0.0, 425.0, 250.0, 0.0, 0.0, 0.0, 1.0, 0.0};
  const CameraGeometry reference = usable(distortedCamera());
  expectSameRays(reference, usable(scaled), 1e-6);
  // The right camera of a stereo pair: Tx = -fx' * B is the baseline, not a pixel offset.
  sensor_msgs::CameraInfo right = scaled;
  right.P[3] = -430.0 * 0.12;
  expectSameRays(reference, usable(right), 1e-6);
}

TEST(CameraGeometryImageGeometry, RoiAndBinningMapToTheFullSensor) {
  const sensor_msgs::CameraInfo full = distortedCamera();
  sensor_msgs::CameraInfo reduced = full;
  reduced.roi.x_offset = 100;
  reduced.roi.y_offset = 60;
  reduced.roi.width = 400;
  reduced.roi.height = 300;
  reduced.binning_x = 2;
  reduced.binning_y = 2;  // a 200x150 image
  const CameraGeometry f = usable(full), r = usable(reduced);
  // The reduced image's corner point (u, v) is the full image's (2u + 100, 2v + 60).
  for (double v : {0.0, 30.5, 75.0, 149.0}) {
    for (double u : {0.0, 50.25, 110.0, 199.0}) {
      EXPECT_LT(cv::norm(r.ray(u, v) - f.ray(2.0 * u + 100.0, 2.0 * v + 60.0)), 1e-6)
          << "at (" << u << ", " << v << ")";
    }
  }
  // Without distortion, exactly: corner (110, 90) is the full corner (320, 240), the principal
  // point's pixel corner.
  reduced.D.clear();
  const cv::Vec3d c = usable(reduced).ray(110.0, 90.0);
  EXPECT_NEAR(c[0], 0.0, 1e-12);
  EXPECT_NEAR(c[1], 0.0, 1e-12);
  // Binning on one axis only.
  reduced.binning_y = 1;
  const cv::Vec3d d = usable(reduced).ray(110.0, 180.0);
  EXPECT_NEAR(d[0], 0.0, 1e-12);
  EXPECT_NEAR(d[1], 0.0, 1e-12);
}

TEST(CameraGeometryImageGeometry, EquidistantDistortionIsUndone) {
  const double k[4] = {0.1, -0.05, 0.01, -0.002};
  sensor_msgs::CameraInfo info;
  info.K = {300.0, 0.0, 320.0, 0.0, 300.0, 240.0, 0.0, 0.0, 1.0};
  info.D = {k[0], k[1], k[2], k[3]};
  const cv::Point2d xn(0.6, -0.4);  // 36 degrees off the axis
  const double r = std::hypot(xn.x, xn.y), t = std::atan(r), t2 = t * t;
  const double td = t * (1.0 + k[0] * t2 + k[1] * t2 * t2 + k[2] * t2 * t2 * t2 + k[3] * t2 * t2 * t2 * t2);
  const double u = 300.0 * xn.x * td / r + 320.0 + 0.5, v = 300.0 * xn.y * td / r + 240.0 + 0.5;
  for (const char* name : {"equidistant", "fisheye"}) {
    info.distortion_model = name;
    const cv::Vec3d ray = usable(info).ray(u, v);
    EXPECT_NEAR(ray[0] / ray[2], xn.x, 1e-6) << name;
    EXPECT_NEAR(ray[1] / ray[2], xn.y, 1e-6) << name;
  }
  info.distortion_model = "equidistant";
  info.D.push_back(0.0);
  CameraGeometry cam;
  std::string error;
  EXPECT_FALSE(cam.setCameraInfo(info, &error));
  EXPECT_NE(error.find("4 coefficients"), std::string::npos) << error;
}

TEST(CameraGeometryImageGeometry, UnusableRAndPAreRefused) {
  CameraGeometry cam;
  std::string error;
  sensor_msgs::CameraInfo info = distortedCamera();
  info.R = {2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  EXPECT_FALSE(cam.setCameraInfo(info, &error));
  EXPECT_NE(error.find("R is not a rotation"), std::string::npos) << error;
  EXPECT_FALSE(cam.valid());

  info = distortedCamera();
  info.P = {0.0, 0.0, 319.5, 0.0, 0.0, 500.0, 239.5, 0.0, 0.0, 0.0, 1.0, 0.0};
  EXPECT_FALSE(cam.setCameraInfo(info, &error));
  EXPECT_NE(error.find("P has no positive finite focal lengths"), std::string::npos) << error;
  info.P[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(cam.setCameraInfo(info, &error));

  // Several problems are all named.
  info.K[0] = 0.0;
  EXPECT_FALSE(cam.setCameraInfo(info, &error));
  EXPECT_NE(error.find("K has"), std::string::npos) << error;
  EXPECT_NE(error.find("P has"), std::string::npos) << error;
}

TEST(CameraGeometryImageGeometry, PinholeCameraInfoIsAnUndistortedPinhole) {
  const sensor_msgs::CameraInfo info = obstacle_tracker::bridge::pinholeCameraInfo(640, 480, 500.0);
  EXPECT_EQ(info.width, 640u);
  EXPECT_EQ(info.height, 480u);
  EXPECT_EQ(info.distortion_model, "plumb_bob");
  EXPECT_EQ(info.D, std::vector<double>(5, 0.0));
  const boost::array<double, 9> k = {500.0, 0.0, 319.5, 0.0, 500.0, 239.5, 0.0, 0.0, 1.0};
  const boost::array<double, 9> r = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  const boost::array<double, 12> p = {500.0, 0.0, 319.5, 0.0, 0.0, 500.0, 239.5, 0.0, 0.0, 0.0, 1.0, 0.0};
  EXPECT_EQ(info.K, k);
  EXPECT_EQ(info.R, r);
  EXPECT_EQ(info.P, p);
  const sensor_msgs::CameraInfo off_centre = obstacle_tracker::bridge::pinholeCameraInfo(320, 240, 300.0, 160.0, 120.0);
  EXPECT_EQ(off_centre.K[2], 160.0);
  EXPECT_EQ(off_centre.K[5], 120.0);
  EXPECT_EQ(off_centre.P[2], 160.0);
  EXPECT_EQ(off_centre.P[6], 120.0);
  // The image centre (corner coordinates) looks straight ahead.
  const cv::Vec3d ahead = usable(info).ray(320.0, 240.0);
  EXPECT_NEAR(ahead[0], 0.0, 1e-12);
  EXPECT_NEAR(ahead[1], 0.0, 1e-12);
}
