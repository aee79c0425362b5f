// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// ObstacleTrackerNodelet (obstacle_tracker_nodelet.h): what the camera model and tf add to a
// frame's obstacles: bearings in ~target_frame, angular sizes, bearing rates and the
// collision-course flag.
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <tf2/exceptions.h>

#include "obstacle_tracker/ros/obstacle_tracker_nodelet.h"

namespace obstacle_tracker {

namespace {

// Element-wise equality where NaN equals NaN: an unchanged camera_info full of NaN must compare
// equal to itself, or it is re-validated and re-logged on every frame.
template <typename Array>
bool sameValues(const Array& a, const Array& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  }
  return true;
}

bool sameCalibration(const sensor_msgs::CameraInfo& a, const sensor_msgs::CameraInfo& b) {
  return a.width == b.width && a.height == b.height && sameValues(a.K, b.K) && sameValues(a.D, b.D) &&
         sameValues(a.R, b.R) && sameValues(a.P, b.P) &&
         a.distortion_model == b.distortion_model && a.binning_x == b.binning_x &&
         a.binning_y == b.binning_y && a.roi.x_offset == b.roi.x_offset &&
         a.roi.y_offset == b.roi.y_offset && a.roi.width == b.roi.width && a.roi.height == b.roi.height;
}

// Size of the image a camera_info describes (after ROI and binning); 0 when unknown.
void describedSize(const sensor_msgs::CameraInfo& info, std::uint32_t* width, std::uint32_t* height) {
  const std::uint32_t bx = std::max<std::uint32_t>(1, info.binning_x);
  const std::uint32_t by = std::max<std::uint32_t>(1, info.binning_y);
  *width = (info.roi.width ? info.roi.width : info.width) / bx;
  *height = (info.roi.height ? info.roi.height : info.height) / by;
}

}  // namespace

void ObstacleTrackerNodelet::fillGeometry(const sensor_msgs::Image& image, const sensor_msgs::CameraInfo& info,
                                          ObstacleArray& out) {
  if (!have_info_ || !sameCalibration(info, last_info_)) {
    std::string error;
    if (!camera_.setCameraInfo(info, &error)) {
      NODELET_WARN("camera_info unusable (%s): no bearings until it changes", error.c_str());
    }
    last_info_ = info;
    have_info_ = true;
  }
  if (!camera_.valid()) return;
  std::uint32_t width, height;
  describedSize(info, &width, &height);
  if (width != 0 && height != 0 && (width != image.width || height != image.height)) {
    NODELET_WARN_THROTTLE(10.0, "camera_info describes %ux%u images but the image is %ux%u: no bearings",
                          width, height, image.width, image.height);
    return;
  }
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  if (!target_frame_.empty() && target_frame_ != image.header.frame_id) {
    try {
      const geometry_msgs::TransformStamped tf = tf_buffer_->lookupTransform(
          target_frame_, image.header.frame_id, image.header.stamp, ros::Duration(tf_timeout_));
      const auto& q = tf.transform.rotation;
      rotation = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized();
    } catch (const tf2::TransformException& e) {
      NODELET_WARN_THROTTLE(5.0, "no transform from '%s' to ~target_frame '%s' at %.3f (%s): bearings left out",
                            image.header.frame_id.c_str(), target_frame_.c_str(), image.header.stamp.toSec(), e.what());
      return;
    }
  }
  for (std::size_t i = 0; i < obstacles_.size() && i < out.obstacles.size(); ++i) {
    const bridge::BoxGeometry g = camera_.box(obstacles_[i].box);
    // A direction: only the rotation of the transform applies.
    const Eigen::Vector3d b = rotation * Eigen::Vector3d(g.bearing[0], g.bearing[1], g.bearing[2]);
    Obstacle& o = out.obstacles[i];
    o.has_bearing = true;
    o.bearing.x = b.x();
    o.bearing.y = b.y();
    o.bearing.z = b.z();
    o.angular_width = static_cast<float>(g.angular_width);
    o.angular_height = static_cast<float>(g.angular_height);
  }
}

void ObstacleTrackerNodelet::markCollisionCourse(double stamp, ObstacleArray& out) {
  course_.resize(out.obstacles.size());
  for (std::size_t i = 0; i < out.obstacles.size(); ++i) {
    const Obstacle& o = out.obstacles[i];
    core::CollisionCourse::Track& t = course_[i];
    t.id = static_cast<int>(o.id);
    t.has_bearing = o.has_bearing;
    t.bearing = cv::Vec3d(o.bearing.x, o.bearing.y, o.bearing.z);
    t.expansion_rate = o.expansion_rate;
    t.expansion_rate_sigma = o.expansion_rate_sigma;
  }
  collision_.update(stamp, course_);
  for (std::size_t i = 0; i < out.obstacles.size(); ++i) {
    out.obstacles[i].bearing_rate = static_cast<float>(course_[i].bearing_rate);
    out.obstacles[i].collision_course = course_[i].collision_course;
  }
}

}  // namespace obstacle_tracker
