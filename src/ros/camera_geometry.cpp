// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/ros/camera_geometry.h"

#include <cmath>
#include <sstream>
#include <vector>

#include <opencv2/calib3d.hpp>

namespace obstacle_tracker {
namespace bridge {

bool CameraGeometry::setCameraInfo(const sensor_msgs::CameraInfo& info, std::string* error) {
  std::ostringstream problem;
  const double fx = info.K[0], fy = info.K[4], cx = info.K[2], cy = info.K[5];
  bool any_distortion = false;
  for (double d : info.D) {
    if (!std::isfinite(d)) problem << "non-finite distortion coefficient; ";
    if (d != 0.0) any_distortion = true;
  }
  if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy)) ||
      fx <= 0.0 || fy <= 0.0) {
    problem << "K has no positive finite focal lengths (fx=" << fx << ", fy=" << fy << "); ";
  }
  Model model = Model::kPinhole;
  if (any_distortion) {
    const std::string& m = info.distortion_model;
    if (m == "plumb_bob" || m == "rational_polynomial") {
      model = Model::kPlumbBob;
      if (info.D.size() != 4 && info.D.size() != 5 && info.D.size() != 8 &&
          info.D.size() != 12 && info.D.size() != 14) {
        problem << "distortion model '" << m << "' with " << info.D.size() << " coefficients; ";
      }
    } else if (m == "equidistant" || m == "fisheye") {
      model = Model::kEquidistant;
      if (info.D.size() != 4) problem << "equidistant model needs 4 coefficients, got " << info.D.size() << "; ";
    } else {
      problem << "unknown distortion model '" << m << "' with non-zero D; ";
    }
  }
  if (!problem.str().empty()) {
    valid_ = false;
    if (error) *error = problem.str().substr(0, problem.str().size() - 2);
    return false;
  }
  model_ = model;
  K_ = cv::Matx33d(fx, info.K[1], cx, info.K[3], fy, cy, 0.0, 0.0, 1.0);
  D_ = info.D.empty() ? cv::Mat() : cv::Mat(info.D, true).reshape(1, 1);
  binning_x_ = info.binning_x > 1 ? info.binning_x : 1.0;
  binning_y_ = info.binning_y > 1 ? info.binning_y : 1.0;
  roi_x_ = info.roi.x_offset;
  roi_y_ = info.roi.y_offset;
  valid_ = true;
  if (error) error->clear();
  return true;
}

cv::Vec3d CameraGeometry::ray(double u, double v) const {
  // Corner coordinates of the binned / ROI image -> pixel-centre coordinates of the full sensor.
  const double uf = u * binning_x_ + roi_x_ - 0.5;
  const double vf = v * binning_y_ + roi_y_ - 0.5;
  double x, y;
  if (model_ == Model::kPinhole) {
    // Inverse of K (with skew): y from the second row, then x.
    y = (vf - K_(1, 2)) / K_(1, 1);
    x = (uf - K_(0, 2) - K_(0, 1) * y) / K_(0, 0);
  } else {
    std::vector<cv::Point2d> in{{uf, vf}}, out;
    if (model_ == Model::kPlumbBob) {
      cv::undistortPoints(in, out, K_, D_);
    } else {
      cv::fisheye::undistortPoints(in, out, K_, D_);
    }
    x = out[0].x;
    y = out[0].y;
  }
  const cv::Vec3d r(x, y, 1.0);
  return r / cv::norm(r);
}

BoxGeometry CameraGeometry::box(const cv::Rect2f& b) const {
  BoxGeometry g;
  const double cx = b.x + 0.5 * b.width, cy = b.y + 0.5 * b.height;
  g.bearing = ray(cx, cy);
  auto angle = [](const cv::Vec3d& a, const cv::Vec3d& c) {
    // atan2 of |a x c| and a.c: accurate for small angles, unlike acos.
    return std::atan2(cv::norm(a.cross(c)), a.dot(c));
  };
  g.angular_width = angle(ray(b.x, cy), ray(b.x + b.width, cy));
  g.angular_height = angle(ray(cx, b.y), ray(cx, b.y + b.height));
  return g;
}

}  // namespace bridge
}  // namespace obstacle_tracker
