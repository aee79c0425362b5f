// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/ros/obstacle_tracker_nodelet.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <boost/bind/bind.hpp>
#include <boost/make_shared.hpp>
#include <cv_bridge/cv_bridge.h>
#include <pluginlib/class_list_macros.hpp>

#include "obstacle_tracker/core/overlay_drawing.h"
#include "obstacle_tracker/ros/conversions.h"
#include "obstacle_tracker/ros/markers.h"

namespace obstacle_tracker {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

ObstacleTrackerNodelet::ObstacleTrackerNodelet() = default;

ObstacleTrackerNodelet::~ObstacleTrackerNodelet() {
  // Stop the inputs, then the processing thread, before the members they use go away.
  diagnostics_timer_.stop();
  image_sub_.shutdown();
  camera_sub_.shutdown();
  slot_.stop();
  if (worker_.joinable()) worker_.join();
}

void ObstacleTrackerNodelet::loadParams() {
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  core::Params params;
  std::string file;
  if (pnh.getParam("params_file", file) && !file.empty()) {
    try {
      std::vector<std::string> messages;
      params = core::loadParamsFile(file, &messages, params);
      for (const std::string& m : messages) NODELET_WARN("%s: %s", file.c_str(), m.c_str());
      NODELET_INFO("parameters loaded from %s", file.c_str());
    } catch (const std::exception& e) {
      NODELET_ERROR("cannot use ~params_file: %s; starting from the defaults", e.what());
    }
  }
  std::vector<std::string> messages;
  params = bridge::paramsFromRos(pnh, params, &messages);
  for (const std::string& m : messages) NODELET_WARN("%s", m.c_str());
  params_ = params;

  // The 16-bit stretch: the tools' defaults unless set (core/intensity_stretch.h).
  core::IntensityStretch& stretch = converter_.stretch();
  double low = core::kStretchLowPercentile, high = core::kStretchHighPercentile;
  double smoothing = core::kStretchSmoothing;
  pnh.param("mono16_low_percentile", low, low);
  pnh.param("mono16_high_percentile", high, high);
  pnh.param("mono16_smoothing", smoothing, smoothing);
  try {
    stretch.setPercentiles(low, high);
  } catch (const std::invalid_argument& e) {
    NODELET_ERROR("~mono16_low/high_percentile: %s; using %g and %g", e.what(),
                  stretch.lowPercentile(), stretch.highPercentile());
  }
  try {
    stretch.setSmoothing(smoothing);
  } catch (const std::invalid_argument& e) {
    NODELET_ERROR("~mono16_smoothing: %s; using %g", e.what(), stretch.smoothing());
  }
}

void ObstacleTrackerNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();

  loadParams();
  pipeline_.reset(new core::Pipeline(params_));

  pnh.param("target_frame", target_frame_, std::string());
  pnh.param("tf_timeout", tf_timeout_, 0.05);
  if (!(tf_timeout_ >= 0.0 && tf_timeout_ <= 10.0)) {
    NODELET_WARN("~tf_timeout %g outside [0, 10] s; using 0.05", tf_timeout_);
    tf_timeout_ = 0.05;
  }
  pnh.param("use_camera_info", use_camera_info_, false);
  if (!target_frame_.empty()) {
    tf_buffer_.reset(new tf2_ros::Buffer());
    tf_listener_.reset(new tf2_ros::TransformListener(*tf_buffer_, nh));
  }

  // Every answer reaches the planner: a subscriber whose socket is a moment late (a loaded
  // machine) loses ObstacleArrays from a short queue (with 30, 3 to 43 of about 7000 answers at
  // 200 Hz beside stress-ng). They are a few hundred bytes: keep a second's worth at 200 Hz. A
  // planner that wants only the newest keeps that with its own subscriber queue.
  obstacles_pub_ = pnh.advertise<ObstacleArray>("obstacles", 200);
  image_transport::ImageTransport private_it(pnh);
  debug_pub_ = private_it.advertise("debug_image", 1);
  markers_pub_ = pnh.advertise<visualization_msgs::MarkerArray>("markers", 1);

  // dynamic_reconfigure: start from the parameters just read (file + ROS), not from the .cfg
  // defaults, then apply every later change through the callback.
  reconfigure_server_.reset(new dynamic_reconfigure::Server<ObstacleTrackerConfig>(reconfigure_mutex_, pnh));
  reconfigure_server_->updateConfig(bridge::configFromParams(params_, ObstacleTrackerConfig::__getDefault__()));
  reconfigure_server_->setCallback(boost::bind(&ObstacleTrackerNodelet::reconfigure, this,
                                               boost::placeholders::_1, boost::placeholders::_2));
  const std::vector<std::string> missing = bridge::paramsMissingFromConfig();
  if (!missing.empty()) {
    NODELET_WARN("not in dynamic_reconfigure (settable as ROS parameters only): %s", joined(missing).c_str());
  }

  updater_.reset(new diagnostic_updater::Updater(nh, pnh, getName()));
  updater_->setHardwareID("none");
  updater_->add("obstacle tracker", this, &ObstacleTrackerNodelet::diagnose);
  obstacles_diagnostic_.reset(new diagnostic_updater::TopicDiagnostic(
      "obstacle tracker ~obstacles", *updater_,
      diagnostic_updater::FrequencyStatusParam(&min_obstacles_rate_, &max_obstacles_rate_, 0.0, 10),
      diagnostic_updater::TimeStampStatusParam(0.0, kMaxStampDelay)));
  window_start_ = ros::WallTime::now();

  worker_ = std::thread(&ObstacleTrackerNodelet::processFrames, this);
  subscribe();
  // Last: diagnose() reads the subscriptions.
  diagnostics_timer_ = pnh.createWallTimer(ros::WallDuration(0.25), &ObstacleTrackerNodelet::diagnosticsTimer, this);
}

void ObstacleTrackerNodelet::processFrames() {
  PendingFrame frame;
  while (slot_.take(&frame)) {
    try {
      process(frame.image, frame.info);
    } catch (...) {  // process() reports its own errors; nothing may end this thread
      NODELET_ERROR_THROTTLE(5.0, "frame processing: unknown error");
    }
    frame = PendingFrame();  // the image's memory goes back while we wait
    slot_.done();  // also for frames refused or skipped (done() twice is harmless)
    const std::uint64_t dropped = slot_.dropped();
    std::lock_guard<std::mutex> lock(stats_mutex_);
    window_.dropped += dropped - slot_drops_counted_;
    total_.dropped += dropped - slot_drops_counted_;
    slot_drops_counted_ = dropped;
  }
}

void ObstacleTrackerNodelet::prepareFor(const cv::Mat& frame) {
  // The first frame of a size would otherwise make the pipeline's buffers and OpenCV's lazy
  // tables (several times a steady frame's time). A new size starts new tracks anyway; a new
  // type (grey <-> colour) does so here too.
  const auto t0 = std::chrono::steady_clock::now();
  prepared_size_ = frame.size();  // once per size and type, even when it fails
  prepared_type_ = frame.type();
  try {
    pipeline_->prepare(frame.size(), frame.type());
  } catch (const std::exception& e) {  // the frame is still processed, only without warm-up
    NODELET_WARN("pipeline warm-up for %dx%d frames failed: %s", frame.cols, frame.rows, e.what());
    return;
  }
  NODELET_INFO("pipeline prepared for %dx%d %s frames in %.1f ms", frame.cols, frame.rows,
               frame.channels() == 1 ? "grey" : "colour",
               1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

void ObstacleTrackerNodelet::countRefused(const std::string& error) {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  ++window_.rejected;
  ++total_.rejected;
  last_error_ = error;
}

bool ObstacleTrackerNodelet::alreadyProcessed(const std_msgs::Header& header) {
  if (!(have_last_ && header.stamp == last_stamp_ && header.seq == last_seq_)) return false;
  std::lock_guard<std::mutex> lock(stats_mutex_);
  ++duplicates_;
  NODELET_WARN_THROTTLE(5.0, "frame (stamp %.6f, seq %u) already processed: skipped",
                        header.stamp.toSec(), header.seq);
  return true;
}

const cv::Mat* ObstacleTrackerNodelet::convert(const sensor_msgs::Image& image) {
  try {
    return &converter_.convert(image);
  } catch (const bridge::UnsupportedEncoding& e) {
    NODELET_ERROR_THROTTLE(5.0, "%s: frame skipped (supported: %s)", e.what(),
                           joined(bridge::supportedEncodings()).c_str());
    countRefused(e.what());
  } catch (const bridge::MalformedImage& e) {
    NODELET_ERROR_THROTTLE(5.0, "%s: frame skipped", e.what());
    countRefused(e.what());
  }
  return nullptr;
}

double ObstacleTrackerNodelet::trackingStamp(const std_msgs::Header& header) {
  if (header.stamp.isZero()) {
    NODELET_WARN_ONCE("images carry no stamp: using the arrival time (latency figures are meaningless)");
    return ros::Time::now().toSec();
  }
  if (have_last_ && header.stamp < last_stamp_) {
    NODELET_INFO("image time went backwards (%.3f -> %.3f, e.g. a looping bag): tracks restart",
                 last_stamp_.toSec(), header.stamp.toSec());
  }
  return header.stamp.toSec();
}

double ObstacleTrackerNodelet::track(const cv::Mat& frame, double stamp, core::TrackState* state) {
  std::lock_guard<std::mutex> lock(pipeline_mutex_);
  if (frame.size() != prepared_size_ || frame.type() != prepared_type_) prepareFor(frame);
  const auto t0 = std::chrono::steady_clock::now();
  obstacles_ = pipeline_->process(frame, stamp);
  const double processing = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  *state = pipeline_->state();
  collision_.setMaxBearingRate(pipeline_->params().collision_bearing_rate);
  return processing;
}

void ObstacleTrackerNodelet::publishObstacles(const sensor_msgs::Image& image,
                                              const sensor_msgs::CameraInfoConstPtr& info,
                                              double stamp, double processing) {
  boost::shared_ptr<ObstacleArray> out = boost::make_shared<ObstacleArray>();
  out->header = image.header;
  out->target_frame = target_frame_.empty() ? image.header.frame_id : target_frame_;
  out->image_width = image.width;
  out->image_height = image.height;
  out->processing_time = static_cast<float>(processing);
  out->obstacles.resize(obstacles_.size());
  for (std::size_t i = 0; i < obstacles_.size(); ++i) bridge::toMessage(obstacles_[i], out->obstacles[i]);
  if (info) fillGeometry(image, *info, *out);
  markCollisionCourse(stamp, *out);
  // The frame is processed once its answer exists: a frame that arrives after the answer (the
  // overlay and statistics below are still being done) is kept, not dropped (frame_slot.h).
  slot_.done();
  obstacles_pub_.publish(out);
  obstacles_diagnostic_->tick(image.header.stamp);
  if (markers_pub_.getNumSubscribers() > 0) {
    // Arrows outlive a frame a little, so that they vanish when the frames stop, not between.
    bridge::bearingMarkers(*out, kMarkerLifetime, markers_);
    markers_pub_.publish(markers_);
  }
}

void ObstacleTrackerNodelet::publishOverlay(const sensor_msgs::Image& image, const cv::Mat& frame,
                                            core::TrackState state, double processing) {
  if (debug_pub_.getNumSubscribers() == 0) return;
  char status[160];
  std::snprintf(status, sizeof(status), "%s  obstacles: %zu  %.1f ms", core::toString(state),
                obstacles_.size(), processing * 1e3);
  core::OverlayExtras extras;
  extras.status = status;
  core::drawOverlay(frame, obstacles_, extras, overlay_);
  debug_pub_.publish(cv_bridge::CvImage(image.header, "bgr8", overlay_).toImageMsg());
}

void ObstacleTrackerNodelet::countProcessed(double processing, core::TrackState state) {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  for (Window* w : {&window_, &total_}) {
    ++w->processed;
    w->processing_sum += processing;
    w->processing_max = std::max(w->processing_max, processing);
  }
  last_state_ = state;
  last_obstacle_count_ = obstacles_.size();
}

void ObstacleTrackerNodelet::process(const sensor_msgs::ImageConstPtr& image,
                                     const sensor_msgs::CameraInfoConstPtr& info) {
  const std::string& encoding = image->encoding;
  std::string error;
  try {
    if (alreadyProcessed(image->header)) return;
    const cv::Mat* frame = convert(*image);
    if (!frame) return;
    const double stamp = trackingStamp(image->header);
    core::TrackState state;
    const double processing = track(*frame, stamp, &state);
    have_last_ = true;
    last_stamp_ = image->header.stamp;
    last_seq_ = image->header.seq;
    publishObstacles(*image, info, stamp, processing);
    publishOverlay(*image, *frame, state, processing);
    countProcessed(processing, state);
    return;
  } catch (const cv::Exception& e) {
    NODELET_ERROR_THROTTLE(5.0, "OpenCV error on a '%s' frame (skipped, tracks reset): %s", encoding.c_str(), e.what());
    error = e.what();
  } catch (const std::exception& e) {
    NODELET_ERROR_THROTTLE(5.0, "error on a '%s' frame (skipped, tracks reset): %s", encoding.c_str(), e.what());
    error = e.what();
  } catch (...) {
    NODELET_ERROR_THROTTLE(5.0, "unknown error on a '%s' frame (skipped, tracks reset)", encoding.c_str());
    error = "unknown exception";
  }
  // After an unexpected failure the pipeline's state is not trusted: start again.
  try {
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    pipeline_->reset();
  } catch (...) {
  }
  countRefused(error);
}

void ObstacleTrackerNodelet::reconfigure(ObstacleTrackerConfig& config, std::uint32_t /*level*/) {
  try {
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    std::vector<std::string> messages;
    const core::Params params = bridge::paramsFromConfig(config, params_, &messages);
    for (const std::string& m : messages) NODELET_WARN("%s", m.c_str());
    pipeline_->setParams(params);  // applies from the next frame
    params_ = pipeline_->params();
    config = bridge::configFromParams(params_, config);  // report the values actually used
  } catch (const std::exception& e) {
    NODELET_ERROR("dynamic_reconfigure change refused: %s", e.what());
  } catch (...) {
    NODELET_ERROR("dynamic_reconfigure change refused: unknown error");
  }
}

}  // namespace obstacle_tracker

PLUGINLIB_EXPORT_CLASS(obstacle_tracker::ObstacleTrackerNodelet, nodelet::Nodelet)
