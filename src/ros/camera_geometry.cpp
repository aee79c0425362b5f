// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/ros/camera_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include <sensor_msgs/distortion_models.h>

#include "obstacle_tracker/core/box_geometry.h"

namespace obstacle_tracker {
namespace bridge {

namespace {

namespace models = sensor_msgs::distortion_models;

template <typename Array>
bool allZero(const Array& a) {
  return std::all_of(a.begin(), a.end(), [](double x) { return x == 0.0; });
}

template <typename Array>
bool allFinite(const Array& a) {
  return std::all_of(a.begin(), a.end(), [](double x) { return std::isfinite(x); });
}

// The distortion model image_geometry is to use for info, "" after a problem (written to
// problem). image_geometry 1.16 (Debian 12) rectifies plumb_bob and rational_polynomial with
// cv::undistortPoints and equidistant with cv::fisheye::undistortPoints, and throws for any
// other name, even with an all-zero D: a D of zeros is handed over as plumb_bob without
// coefficients, so that any model name means "no distortion" then.
std::string distortionModel(const sensor_msgs::CameraInfo& info, std::ostringstream& problem) {
  if (!allFinite(info.D)) problem << "non-finite distortion coefficient; ";
  if (allZero(info.D)) return models::PLUMB_BOB;
  const std::string& m = info.distortion_model;
  const std::size_t n = info.D.size();
  if (m == models::PLUMB_BOB || m == models::RATIONAL_POLYNOMIAL) {
    // The lengths cv::undistortPoints accepts (it throws on others).
    if (n == 4 || n == 5 || n == 8 || n == 12 || n == 14) return m;
    problem << "distortion model '" << m << "' with " << n << " coefficients; ";
    return "";
  }
  // "fisheye" is the name of OpenCV's module for the same model; image_geometry knows only
  // "equidistant".
  if (m == models::EQUIDISTANT || m == "fisheye") {
    if (n == 4) return models::EQUIDISTANT;
    problem << "equidistant model needs 4 coefficients, got " << n << "; ";
    return "";
  }
  problem << "unknown distortion model '" << m << "' with non-zero D; ";
  return "";
}

// R and P as image_geometry is to use them. Many drivers publish an all-zero R and P (only K and
// D calibrated): an all-zero R is taken as the identity (no stereo rectification) and an
// all-zero P as [K | 0] (the rectified image keeps K), which is what these fields mean for a
// monocular camera; cv::undistortPoints and the ray would divide by their zeros otherwise.
void rectification(const sensor_msgs::CameraInfo& info, sensor_msgs::CameraInfo& out,
                   std::ostringstream& problem) {
  if (allZero(info.R)) {
    out.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  } else {
    const cv::Matx33d r(info.R.data());
    const double off = cv::norm(r * r.t() - cv::Matx33d::eye(), cv::NORM_INF);
    if (!allFinite(info.R) || !(off < 1e-3)) problem << "R is not a rotation matrix; ";
  }
  if (allZero(info.P)) {
    out.P = {info.K[0], info.K[1], info.K[2], 0.0, info.K[3], info.K[4], info.K[5], 0.0,
             info.K[6], info.K[7], info.K[8], 0.0};
  } else if (!allFinite(info.P) || !(info.P[0] > 0.0) || !(info.P[5] > 0.0)) {
    problem << "P has no positive finite focal lengths (fx=" << info.P[0] << ", fy=" << info.P[5]
            << "); ";
  }
}

}  // namespace

bool CameraGeometry::setCameraInfo(const sensor_msgs::CameraInfo& info, std::string* error) {
  std::ostringstream problem;
  const double fx = info.K[0], fy = info.K[4], cx = info.K[2], cy = info.K[5];
  if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy)) ||
      fx <= 0.0 || fy <= 0.0) {
    problem << "K has no positive finite focal lengths (fx=" << fx << ", fy=" << fy << "); ";
  }
  sensor_msgs::CameraInfo usable = info;
  usable.distortion_model = distortionModel(info, problem);
  if (allZero(info.D)) usable.D.clear();
  rectification(info, usable, problem);
  if (!problem.str().empty()) {
    valid_ = false;
    if (error) *error = problem.str().substr(0, problem.str().size() - 2);
    return false;
  }
  model_.fromCameraInfo(usable);
  // The ray is that of this camera's centre: P's last column is a stereo camera's baseline
  // (Tx = -fx' * B), which projectPixelTo3dRay would subtract as if it were pixels.
  projection_ = model_.projectionMatrix();
  projection_(0, 3) = projection_(1, 3) = 0.0;
  // image_geometry's reduced image maps its pixel centre x to x * binning + roi offset in the
  // full image (binning 0 means 1); the corner coordinate u of the reduced image is the full
  // image's corner u * binning + offset, whose pixel centre is half a full pixel less.
  half_pixel_x_ = 0.5 / std::max(1u, info.binning_x);
  half_pixel_y_ = 0.5 / std::max(1u, info.binning_y);
  valid_ = true;
  if (error) error->clear();
  return true;
}

cv::Vec3d CameraGeometry::ray(double u, double v) const {
  // rectifyPoint returns a pixel of the rectified image (P), or the pixel as it is when D is
  // zero. It computes in float: about 1e-4 px in a 2000-pixel-wide image, 2e-7 rad at f = 500 px.
  const cv::Point2d rectified = model_.rectifyPoint(cv::Point2d(u - half_pixel_x_, v - half_pixel_y_));
  const cv::Point3d r = model_.projectPixelTo3dRay(rectified, projection_);
  const cv::Vec3d d(r.x, r.y, r.z);
  return d / cv::norm(d);
}

BoxGeometry CameraGeometry::box(const cv::Rect2f& b) const {
  BoxGeometry g;
  const cv::Point2d c = core::boxCentre(cv::Rect2d(b));
  const double cx = c.x, cy = c.y;
  g.bearing = ray(cx, cy);
  auto angle = [](const cv::Vec3d& a, const cv::Vec3d& c) {
    // atan2 of |a x c| and a.c: accurate for small angles, unlike acos.
    return std::atan2(cv::norm(a.cross(c)), a.dot(c));
  };
  g.angular_width = angle(ray(b.x, cy), ray(b.x + b.width, cy));
  g.angular_height = angle(ray(cx, b.y), ray(cx, b.y + b.height));
  return g;
}

sensor_msgs::CameraInfo pinholeCameraInfo(int width, int height, double focal_px, double cx, double cy) {
  sensor_msgs::CameraInfo info;
  info.width = static_cast<std::uint32_t>(width);
  info.height = static_cast<std::uint32_t>(height);
  info.distortion_model = models::PLUMB_BOB;
  info.D = {0.0, 0.0, 0.0, 0.0, 0.0};
  info.K = {focal_px, 0.0, cx, 0.0, focal_px, cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {focal_px, 0.0, cx, 0.0, 0.0, focal_px, cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

sensor_msgs::CameraInfo pinholeCameraInfo(int width, int height, double focal_px) {
  return pinholeCameraInfo(width, height, focal_px, 0.5 * width - 0.5, 0.5 * height - 0.5);
}

}  // namespace bridge
}  // namespace obstacle_tracker
