// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Bearings and angular sizes of boxes from a sensor_msgs/CameraInfo, through image_geometry's
// PinholeCameraModel: the pixel is rectified with K, D, R and P (rectifyPoint; plumb_bob,
// rational_polynomial and equidistant), then turned into a ray with P. binning and roi are
// honoured (image_geometry adjusts K and P to the reduced image). The image is taken to be the one
// the camera_info describes; for an image that is already rectified publish D = 0 (or empty):
// image_geometry then leaves the pixel as it is and projects with P. A skew in K or P (K[1]) is
// ignored, as image_geometry and OpenCV's undistortion ignore it (camera_calibration writes none).
//
// Conventions: the camera's optical frame (REP 103: z forward, x right, y down); with a stereo
// rectification R, the rectified frame. The box from the core is in "corner" pixel coordinates
// (pixel i covers [i, i+1)); K and P use pixel centres.
#pragma once

#include <string>

#include <image_geometry/pinhole_camera_model.h>
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
  // focal lengths in K or P, an unknown distortion model with non-zero D, a D of the wrong
  // length, an R that is not a rotation.
  bool setCameraInfo(const sensor_msgs::CameraInfo& info, std::string* error);
  bool valid() const { return valid_; }

  // Unit ray in the optical frame through the image point (u, v) in corner pixel coordinates of
  // the (possibly binned / ROI) image.
  cv::Vec3d ray(double u, double v) const;

  BoxGeometry box(const cv::Rect2f& box) const;

 private:
  bool valid_ = false;
  image_geometry::PinholeCameraModel model_;
  // P of the reduced image without its stereo baseline column (see ray()).
  cv::Matx34d projection_;
  double half_pixel_x_ = 0.5;  // corner -> pixel-centre offset in reduced pixels
  double half_pixel_y_ = 0.5;
};

// The camera_info of an ideal pinhole camera of width x height pixels: focal length focal_px on
// both axes, principal point (cx, cy) in K's pixel-centre coordinates, R the identity,
// P = [K | 0], plumb_bob with five zero coefficients. The header is left empty.
sensor_msgs::CameraInfo pinholeCameraInfo(int width, int height, double focal_px, double cx, double cy);

// The same with the principal point at the image centre: (width / 2 - 0.5, height / 2 - 0.5).
sensor_msgs::CameraInfo pinholeCameraInfo(int width, int height, double focal_px);

}  // namespace bridge
}  // namespace obstacle_tracker
