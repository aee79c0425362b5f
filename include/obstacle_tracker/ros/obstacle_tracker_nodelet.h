// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// obstacle_tracker/ObstacleTrackerNodelet: the thin ROS adapter around core::Pipeline.
//   subscribes  image (image_transport, ~image_transport picks the transport)
//               camera_info (only with ~use_camera_info): image_transport's CameraSubscriber,
//               the image topic's sibling, paired with the image of the same stamp
//               The callbacks hand each frame to one processing thread through a FrameSlot
//               (frame_slot.h): a frame is dropped only for a newer one while an earlier frame
//               is being processed.
//   publishes   ~obstacles (ObstacleArray, header = the input image's header, one per processed
//               frame, empty when nothing is there), ~debug_image (overlay, only when subscribed),
//               ~markers (bearing arrows in target_frame, markers.h; only when subscribed),
//               /diagnostics
//   parameters  every core parameter under its params.h name in the private namespace,
//               ~params_file (YAML, read first), dynamic_reconfigure (ObstacleTracker.cfg),
//               ~target_frame, ~tf_timeout, ~use_camera_info, ~image_transport,
//               ~mono16_low_percentile, ~mono16_high_percentile, ~mono16_smoothing
// Every callback catches everything: bad input is refused with a throttled log, never thrown
// into the nodelet manager.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/publisher.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "obstacle_tracker/ObstacleArray.h"
#include "obstacle_tracker/ObstacleTrackerConfig.h"
#include "obstacle_tracker/core/collision_course.h"
#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/ros/camera_geometry.h"
#include "obstacle_tracker/ros/frame_slot.h"
#include "obstacle_tracker/ros/image_conversion.h"

namespace obstacle_tracker {

class ObstacleTrackerNodelet : public nodelet::Nodelet {
 public:
  ObstacleTrackerNodelet();
  ~ObstacleTrackerNodelet() override;

 private:
  void onInit() override;
  void loadParams();
  // The input side (nodelet_input.cpp): the image alone, or paired with its camera_info.
  void subscribe();
  void subscribeCamera(std::uint32_t queue, const image_transport::TransportHints& hints);
  void imageCallback(const sensor_msgs::ImageConstPtr& image);
  void imageInfoCallback(const sensor_msgs::ImageConstPtr& image, const sensor_msgs::CameraInfoConstPtr& info);
  void countInput(const sensor_msgs::ImageConstPtr& image);  // an image, or an image + camera_info pair
  void processFrames();
  void prepareFor(const cv::Mat& frame);  // under pipeline_mutex_
  // One frame: refused, or tracked, answered and counted (every exception caught here).
  void process(const sensor_msgs::ImageConstPtr& image, const sensor_msgs::CameraInfoConstPtr& info);
  bool alreadyProcessed(const std_msgs::Header& header);  // counted and logged when it is
  const cv::Mat* convert(const sensor_msgs::Image& image);  // null (counted, logged) if refused
  double trackingStamp(const std_msgs::Header& header);    // the arrival time when unstamped
  // Runs the pipeline on the frame; its processing time in seconds.
  double track(const cv::Mat& frame, double stamp, core::TrackState* state);
  void publishObstacles(const sensor_msgs::Image& image, const sensor_msgs::CameraInfoConstPtr& info,
                        double stamp, double processing);
  void publishOverlay(const sensor_msgs::Image& image, const cv::Mat& frame, core::TrackState state,
                      double processing);  // only when ~debug_image has subscribers
  void countProcessed(double processing, core::TrackState state);
  void countRefused(const std::string& error);
  void fillGeometry(const sensor_msgs::Image& image, const sensor_msgs::CameraInfo& info, ObstacleArray& out);
  // bearing_rate and collision_course of out's obstacles (core/collision_course.h).
  void markCollisionCourse(double stamp, ObstacleArray& out);
  void reconfigure(ObstacleTrackerConfig& config, std::uint32_t level);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  void diagnosticsTimer(const ros::WallTimerEvent&);

  // Frames from the callbacks to processFrames(), which runs on worker_.
  struct PendingFrame {
    sensor_msgs::ImageConstPtr image;
    sensor_msgs::CameraInfoConstPtr info;  // null without ~use_camera_info
  };
  bridge::FrameSlot<PendingFrame> slot_;
  std::thread worker_;

  // Pipeline and parameters: the pipeline runs on worker_; dynamic_reconfigure changes its
  // parameters from a callback thread.
  std::mutex pipeline_mutex_;
  std::unique_ptr<core::Pipeline> pipeline_;
  core::Params params_;
  std::vector<core::Obstacle> obstacles_;  // copy of the last result (reused buffer)

  // Configuration read once in onInit.
  std::string target_frame_;
  double tf_timeout_ = 0.05;
  bool use_camera_info_ = false;

  // ROS interface.
  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber image_sub_;         // without ~use_camera_info
  image_transport::CameraSubscriber camera_sub_;  // with it
  std::string image_topic_, info_topic_;          // as subscribed (diagnostics)
  ros::Publisher obstacles_pub_;
  image_transport::Publisher debug_pub_;
  ros::Publisher markers_pub_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ObstacleTrackerConfig>> reconfigure_server_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  // ~obstacles' rate and the delay of its stamps (the input images') behind the clock: any
  // rate from kMinObstaclesRate up, a delay within [0, kMaxStampDelay] s.
  static constexpr double kMinObstaclesRate = 1.0;   // Hz
  static constexpr double kMaxStampDelay = 0.5;      // s
  double min_obstacles_rate_ = kMinObstaclesRate;
  double max_obstacles_rate_ = std::numeric_limits<double>::infinity();
  std::unique_ptr<diagnostic_updater::TopicDiagnostic> obstacles_diagnostic_;
  ros::WallTimer diagnostics_timer_;

  // Per-frame helpers, used on worker_ only.
  cv::Size prepared_size_;  // the pipeline was last prepared for frames of this size and type
  int prepared_type_ = -1;
  bridge::FrameConverter converter_;
  bridge::CameraGeometry camera_;
  core::CollisionCourse collision_;                     // processing thread only
  std::vector<core::CollisionCourse::Track> course_;    // reused buffer
  sensor_msgs::CameraInfo last_info_;
  bool have_info_ = false;
  cv::Mat overlay_;
  visualization_msgs::MarkerArray markers_;  // reused buffer
  static constexpr double kMarkerLifetime = 1.0;  // s
  bool have_last_ = false;
  ros::Time last_stamp_;
  std::uint32_t last_seq_ = 0;

  // Statistics for diagnostics (guarded by stats_mutex_).
  struct Window {
    std::uint64_t received = 0;  // images; with ~use_camera_info, image + camera_info pairs
    std::uint64_t processed = 0;
    std::uint64_t dropped = 0;
    std::uint64_t rejected = 0;
    double processing_sum = 0.0, processing_max = 0.0;
  };
  std::mutex stats_mutex_;
  Window window_;
  Window total_;
  ros::WallTime window_start_;
  bool have_input_seq_ = false;
  std::uint32_t last_input_seq_ = 0;
  std::uint64_t slot_drops_counted_ = 0;  // slot_.dropped() already added to the windows
  std::uint64_t duplicates_ = 0;
  std::size_t last_obstacle_count_ = 0;
  core::TrackState last_state_ = core::TrackState::kSearching;
  std::string last_error_;
};

}  // namespace obstacle_tracker
