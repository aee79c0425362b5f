// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// ObstacleTrackerNodelet (obstacle_tracker_nodelet.h): the /diagnostics status, from the
// statistics the callbacks and the processing thread keep, one window per period.
#include <algorithm>

#include "obstacle_tracker/ros/obstacle_tracker_nodelet.h"

namespace obstacle_tracker {

void ObstacleTrackerNodelet::diagnosticsTimer(const ros::WallTimerEvent&) {
  try {
    updater_->update();
  } catch (const std::exception& e) {
    NODELET_ERROR_THROTTLE(10.0, "diagnostics: %s", e.what());
  } catch (...) {
  }
}

void ObstacleTrackerNodelet::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  core::Params params;
  {
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    params = pipeline_->params();
  }
  // With ~use_camera_info only paired images reach the nodelet (image_transport's
  // CameraSubscriber): the counts are of image + camera_info pairs, and an image without a
  // camera_info of its stamp shows as a sequence gap (dropped) once a later pair arrives.
  const char* input = use_camera_info_ ? "image + camera_info pairs" : "images";
  const std::uint32_t image_publishers =
      use_camera_info_ ? camera_sub_.getNumPublishers() : image_sub_.getNumPublishers();
  std::lock_guard<std::mutex> lock(stats_mutex_);
  const ros::WallTime now = ros::WallTime::now();
  const double seconds = std::max(1e-6, (now - window_start_).toSec());
  const Window& w = window_;
  const double n = std::max<double>(1.0, static_cast<double>(w.processed));
  status.add("input rate (Hz)", w.received / seconds);
  status.add("processed rate (Hz)", w.processed / seconds);
  status.add("processing time mean (ms)", 1e3 * w.processing_sum / n);
  status.add("processing time max (ms)", 1e3 * w.processing_max);
  status.add("dropped frames (this period)", w.dropped);
  status.add("refused frames (this period)", w.rejected);
  status.add(std::string(input) + " received (total)", total_.received);
  status.add("image publishers", image_publishers);
  status.add("frames processed (total)", total_.processed);
  status.add("dropped frames (total)", total_.dropped);
  status.add("refused frames (total)", total_.rejected);
  status.add("duplicate frames skipped (total)", duplicates_);
  status.add("tracker state", core::toString(last_state_));
  status.add("obstacles", last_obstacle_count_);
  for (const core::ParamInfo& info : core::paramTable()) {
    status.add(std::string("param ") + info.name, core::getParam(params, info.name));
  }
  if (w.received == 0 && use_camera_info_) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "no image + camera_info pairs received (%u publishers of %s; camera_info of "
                    "the same stamps expected on %s)",
                    image_publishers, image_topic_.c_str(), info_topic_.c_str());
  } else if (w.received == 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no images received");
  } else if (w.rejected > 0) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "%llu frames refused: %s",
                    static_cast<unsigned long long>(w.rejected), last_error_.c_str());
  } else {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::OK, "%s, %zu obstacles, %.1f Hz",
                    core::toString(last_state_), last_obstacle_count_, w.processed / seconds);
  }
  window_ = Window();
  window_start_ = now;
}

}  // namespace obstacle_tracker
