// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// ObstacleTrackerNodelet (obstacle_tracker_nodelet.h): the input side. The image alone, or with
// ~use_camera_info the image and its camera_info paired by image_transport's CameraSubscriber;
// the callbacks count what arrives and hand it to the FrameSlot, doing no work on the image.
#include <cstdint>
#include <mutex>
#include <string>

#include "obstacle_tracker/ros/obstacle_tracker_nodelet.h"

namespace obstacle_tracker {

void ObstacleTrackerNodelet::subscribe() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_.reset(new image_transport::ImageTransport(nh));
  const image_transport::TransportHints hints("raw", ros::TransportHints(), pnh);
  // The callbacks only hand frames to the slot, so these queues hardly ever hold more than one;
  // room for a burst, so that the slot (not roscpp) decides what is dropped. When the callback
  // thread is not scheduled for a while, roscpp drops the oldest frame (or camera_info, whose
  // image then never pairs) once `queue` newer ones wait: the same depth as the slot's idle
  // backlog, so that any frame dropped without an earlier one in processing had that many newer
  // frames behind it (the delivery rule the rostests check, test/ros/frame_delivery.h).
  // CameraSubscriber uses the depth for the image and camera_info subscriptions and for its
  // exact-time pairing alike.
  const std::uint32_t queue = bridge::FrameSlot<PendingFrame>::kIdleBacklog;
  if (use_camera_info_) {
    subscribeCamera(queue, hints);
  } else {
    image_sub_ = it_->subscribe("image", queue, &ObstacleTrackerNodelet::imageCallback, this, hints);
    image_topic_ = image_sub_.getTopic();
    NODELET_INFO("tracking %s (transport '%s'), no camera_info (no bearings); publishing %s",
                 image_topic_.c_str(), hints.getTransport().c_str(), obstacles_pub_.getTopic().c_str());
  }
}

void ObstacleTrackerNodelet::subscribeCamera(std::uint32_t queue, const image_transport::TransportHints& hints) {
  ros::NodeHandle& nh = getNodeHandle();
  // image_transport pairs the image with the camera_info of the same stamp on the image topic's
  // sibling, and itself warns (every 10 s, logger ros.image_transport.sync) when the two topics
  // do not appear to be synchronised.
  camera_sub_ = it_->subscribeCamera("image", queue, &ObstacleTrackerNodelet::imageInfoCallback, this, hints);
  image_topic_ = camera_sub_.getTopic();
  info_topic_ = camera_sub_.getInfoTopic();
  // A remapping of camera_info alone does not reach the subscription: say so rather than wait
  // for pairs that never come.
  const std::string remapped = nh.resolveName("camera_info");
  if (remapped != nh.resolveName("camera_info", false) && remapped != info_topic_) {
    NODELET_WARN("camera_info is remapped to %s, but image_transport reads it from %s, next to the "
                 "image topic: remap %s instead",
                 remapped.c_str(), info_topic_.c_str(), info_topic_.c_str());
  }
  NODELET_INFO("tracking %s (transport '%s') with camera_info %s; publishing %s", image_topic_.c_str(),
               hints.getTransport().c_str(), info_topic_.c_str(), obstacles_pub_.getTopic().c_str());
}

void ObstacleTrackerNodelet::countInput(const sensor_msgs::ImageConstPtr& image) {
  try {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++window_.received;
    ++total_.received;
    const std::uint32_t seq = image->header.seq;
    // A gap in the sequence numbers: frames lost before the callback (transport, a full
    // subscription queue; with ~use_camera_info also an image that found no camera_info of its
    // stamp). Sequences that restart (bag loop) are not gaps.
    if (have_input_seq_ && seq > last_input_seq_ + 1 && seq - last_input_seq_ < 1000000) {
      window_.dropped += seq - last_input_seq_ - 1;
      total_.dropped += seq - last_input_seq_ - 1;
    }
    have_input_seq_ = true;
    last_input_seq_ = seq;
  } catch (...) {
  }
}

void ObstacleTrackerNodelet::imageCallback(const sensor_msgs::ImageConstPtr& image) {
  try {
    countInput(image);
    slot_.offer({image, sensor_msgs::CameraInfoConstPtr()});
  } catch (const std::exception& e) {  // process() catches its own; this guards the locking
    NODELET_ERROR_THROTTLE(5.0, "image callback: %s", e.what());
  } catch (...) {
    NODELET_ERROR_THROTTLE(5.0, "image callback: unknown error");
  }
}

void ObstacleTrackerNodelet::imageInfoCallback(const sensor_msgs::ImageConstPtr& image,
                                               const sensor_msgs::CameraInfoConstPtr& info) {
  try {
    countInput(image);
    slot_.offer({image, info});
  } catch (const std::exception& e) {
    NODELET_ERROR_THROTTLE(5.0, "image + camera_info callback: %s", e.what());
  } catch (...) {
    NODELET_ERROR_THROTTLE(5.0, "image + camera_info callback: unknown error");
  }
}

}  // namespace obstacle_tracker
