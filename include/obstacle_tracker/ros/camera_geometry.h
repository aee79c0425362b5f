// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Bearings and angular sizes of boxes from a sensor_msgs/CameraInfo (pinhole K, optional
// distortion D). The image is taken to be the one the camera_info describes: with a non-zero D
// (plumb_bob, rational_polynomial, equidistant) the pixel is undistorted first; for a rectified
// image publish a camera_info with D = 0 (or all-zero D). binning and roi are honoured.
//
// Conventions: the camera's optical frame (REP 103: z forward, x right, y down). The box from the
// core is in "corner" pixel coordinates (pixel i covers [i, i+1)); K uses pixel centres, so the
// point (u, v) of the box is looked up at (u - 0.5, v - 0.5).
#pragma once

#include <string>

#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>

namespace obstacle_tracker {
namespace bridge {

struct BoxGeometry {
  cv::Vec3d bearing;          // unit vector from the camera centre through the box centre
  double angular_width = 0;   // rad: angle between the rays through the left and right edge midpoints
  double angular_height = 0;  // rad: same for the top and bottom edge midpoints
};

class CameraGeometry {
 public:
  CameraGeometry() = default;

  // False (with a reason in *error) for a camera_info that cannot be used: zero or non-finite
  // focal lengths, an unknown distortion model with non-zero D, a D of the wrong length.
  bool setCameraInfo(const sensor_msgs::CameraInfo& info, std::string* error);
  bool valid() const { return valid_; }

  // Unit ray in the optical frame through the image point (u, v) in corner pixel coordinates of
  // the (possibly binned / ROI) image.
  cv::Vec3d ray(double u, double v) const;

  BoxGeometry box(const cv::Rect2f& box) const;

 private:
  enum class Model { kPinhole, kPlumbBob, kEquidistant };
  bool valid_ = false;
  Model model_ = Model::kPinhole;
  cv::Matx33d K_ = cv::Matx33d::eye();
  cv::Mat D_;
  double binning_x_ = 1.0;
  double binning_y_ = 1.0;
  double roi_x_ = 0.0;
  double roi_y_ = 0.0;
};

}  // namespace bridge
}  // namespace obstacle_tracker
