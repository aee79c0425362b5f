// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// GoogleTest node run by the rostests in test/ros/*.test (real master, real nodelet manager or
// the standalone node). Each .test picks its cases with --gtest_filter. Private parameters:
//   ~tracker      namespace of the tracker (its ~obstacles, dynamic_reconfigure, diagnostics)
//   ~manager      nodelet manager to ask for its list (empty: not a nodelet)
//   ~image_topic, ~info_topic, ~use_camera_info   what to publish
//   ~frames       images for the one-output-per-image case
//   ~target_frame when set, bearings are checked in it (the .test publishes base_link <- optical)
//   ~rosout_publishers  /rosout publishers to wait for (this node, the manager, the loader, ...)
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/client.h>
#include <gtest/gtest.h>
#include <nodelet/NodeletList.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>

#include "obstacle_tracker/ObstacleArray.h"
#include "obstacle_tracker/ObstacleTrackerConfig.h"
#include "synthetic_frames.h"

namespace ot = obstacle_tracker;

namespace {

class Harness {
 public:
  Harness() : pnh_("~") {
    pnh_.param("tracker", tracker_, std::string("/obstacle_tracker"));
    pnh_.param("manager", manager_, std::string());
    pnh_.param("image_topic", image_topic_, std::string("/camera/image_raw"));
    pnh_.param("info_topic", info_topic_, std::string("/camera/camera_info"));
    pnh_.param("use_camera_info", use_info_, false);
    pnh_.param("frames", frames_, 30);
    pnh_.param("target_frame", target_frame_, std::string());
    pnh_.param("rosout_publishers", rosout_publishers_, 2);
    image_pub_ = nh_.advertise<sensor_msgs::Image>(image_topic_, 5);
    if (use_info_) info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>(info_topic_, 5);
    echo_sub_ = nh_.subscribe(image_topic_, 50, &Harness::onEcho, this);
    obstacles_sub_ = nh_.subscribe(tracker_ + "/obstacles", 50, &Harness::onObstacles, this);
    rosout_sub_ = nh_.subscribe("/rosout", 200, &Harness::onLog, this);
    diag_sub_ = nh_.subscribe("/diagnostics", 50, &Harness::onDiagnostics, this);
  }

  // Waits until pred() (checked under the lock) or the timeout.
  bool waitFor(const std::function<bool()>& pred, double seconds) {
    std::unique_lock<std::mutex> lock(mutex_);
    return cv_.wait_for(lock, std::chrono::duration<double>(seconds), pred);
  }

  bool waitConnected(double seconds) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::ok() && ros::WallTime::now() < end) {
      // The tracker and our own echo subscribe the image; the tracker publishes obstacles.
      const bool images = image_pub_.getNumSubscribers() >= 2;
      const bool info = !use_info_ || info_pub_.getNumSubscribers() >= 1;
      if (images && info && obstacles_sub_.getNumPublishers() >= 1 &&
          rosout_sub_.getNumPublishers() >= static_cast<std::uint32_t>(rosout_publishers_)) {
        ros::WallDuration(0.3).sleep();  // let the last handshakes settle
        return true;
      }
      ros::WallDuration(0.05).sleep();
    }
    return false;
  }

  // Publishes one frame (camera_info first, so the synchroniser can match at once; none when
  // with_info is false).
  sensor_msgs::Image publish(int i, const std::string& encoding_override = std::string(),
                             bool truncate = false, bool with_info = true) {
    ++published_;
    sensor_msgs::Image image = ot::testing::toImageMsg(ot::testing::skyFrame(i), "camera_optical",
                                                       base_stamp_ + 0.1 * published_, published_);
    if (!encoding_override.empty()) {
      image.encoding = encoding_override;
      if (encoding_override == "32FC3") {  // a well-formed float image: 12 bytes per pixel
        image.step = image.width * 12;
        image.data.assign(static_cast<std::size_t>(image.step) * image.height, 0);
      }
    }
    if (truncate) image.data.resize(image.data.size() / 2);
    if (use_info_ && with_info) info_pub_.publish(ot::testing::cameraInfo(image));
    image_pub_.publish(image);
    return image;
  }

  std::size_t outputCountFor(const ros::Time& stamp) {
    return std::count_if(outputs_.begin(), outputs_.end(),
                         [&](const ot::ObstacleArray& o) { return o.header.stamp == stamp; });
  }

  bool waitOutputFor(const ros::Time& stamp, double seconds) {
    return waitFor([&] { return outputCountFor(stamp) > 0; }, seconds);
  }

  // Latest value of "param NAME" in the tracker's diagnostics, NaN when none yet.
  double diagnosedParam(const std::string& name) {
    for (const auto& kv : last_diagnostics_.values) {
      if (kv.key == "param " + name) return std::stod(kv.value);
    }
    return std::nan("");
  }

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  std::string tracker_, manager_, image_topic_, info_topic_, target_frame_;
  bool use_info_ = false;
  int frames_ = 30;
  int rosout_publishers_ = 2;  // nodes whose /rosout we must hear before logging matters
  ros::Publisher image_pub_, info_pub_;
  ros::Subscriber echo_sub_, obstacles_sub_, rosout_sub_, diag_sub_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<std_msgs::Header> echoed_;
  std::vector<ot::ObstacleArray> outputs_;
  std::vector<rosgraph_msgs::Log> logs_;
  diagnostic_msgs::DiagnosticStatus last_diagnostics_;
  diagnostic_msgs::DiagnosticStatus last_topic_diagnostics_;
  double base_stamp_ = ros::Time::now().toSec();
  std::uint32_t published_ = 0;

 private:
  void onEcho(const sensor_msgs::ImageConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    echoed_.push_back(m->header);
    cv_.notify_all();
  }
  void onObstacles(const ot::ObstacleArrayConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    outputs_.push_back(*m);
    cv_.notify_all();
  }
  void onLog(const rosgraph_msgs::LogConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    logs_.push_back(*m);
    cv_.notify_all();
  }
  void onDiagnostics(const diagnostic_msgs::DiagnosticArrayConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& s : m->status) {
      // "NODE: obstacle tracker" (the tracker's own status) and "NODE: obstacle tracker
      // ~obstacles" (diagnostic_updater's topic diagnostic of the output).
      const std::string suffix = ": obstacle tracker";
      if (s.name.size() >= suffix.size() &&
          s.name.compare(s.name.size() - suffix.size(), suffix.size(), suffix) == 0) {
        last_diagnostics_ = s;
      } else if (s.name.find("obstacle tracker ~obstacles") != std::string::npos) {
        last_topic_diagnostics_ = s;
      }
    }
    cv_.notify_all();
  }
};

Harness* harness = nullptr;

bool sameHeader(const std_msgs::Header& a, const std_msgs::Header& b) {
  return a.seq == b.seq && a.stamp == b.stamp && a.frame_id == b.frame_id;
}

}  // namespace

TEST(Tracker, NodeletIsLoaded) {
  Harness& h = *harness;
  if (!h.manager_.empty()) {
    const std::string service = h.manager_ + "/list";
    ASSERT_TRUE(ros::service::waitForService(service, ros::Duration(30.0))) << service;
    // The manager answers before the loader's request has been served: ask until it is listed.
    bool listed = false;
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(30.0);
    while (!listed && ros::ok() && ros::WallTime::now() < end) {
      nodelet::NodeletList list;
      ASSERT_TRUE(ros::service::call(service, list));
      listed = std::find(list.response.nodelets.begin(), list.response.nodelets.end(), h.tracker_) !=
               list.response.nodelets.end();
      if (!listed) ros::WallDuration(0.1).sleep();
    }
    EXPECT_TRUE(listed) << h.tracker_ << " is not in " << service << " after 30 s";
  }
  // Loaded and initialised: its outputs and its dynamic_reconfigure server are up.
  ASSERT_TRUE(ros::service::waitForService(h.tracker_ + "/set_parameters", ros::Duration(30.0)));
  ASSERT_TRUE(h.waitConnected(30.0)) << "no connection between the test and " << h.tracker_;
}

TEST(Tracker, OneArrayPerImageWithItsHeader) {
  Harness& h = *harness;
  ASSERT_TRUE(h.waitConnected(30.0));
  std::vector<sensor_msgs::Image> sent;
  for (int i = 0; i < h.frames_; ++i) {
    sent.push_back(h.publish(i));
    // Lock-step at up to 20 Hz: the next image only after this one's output, so the test is about
    // the nodelet's contract, not about the machine's speed.
    ASSERT_TRUE(h.waitOutputFor(sent.back().header.stamp, 20.0)) << "no output for image " << i;
    ros::WallDuration(0.05).sleep();
  }
  ros::WallDuration(1.5).sleep();  // anything extra would arrive now
  // ~obstacles has its topic diagnostic (rate and stamp delay) once the diagnostics ran with
  // outputs in their window.
  const bool topic_diagnosed = h.waitFor([&] {
    for (const auto& kv : h.last_topic_diagnostics_.values) {
      if (kv.key == "Events since startup" && std::stod(kv.value) > 0) return true;
    }
    return false;
  }, 10.0);
  EXPECT_TRUE(topic_diagnosed) << "no 'obstacle tracker ~obstacles' status counting outputs";
  std::lock_guard<std::mutex> lock(h.mutex_);
  ASSERT_EQ(h.outputs_.size(), sent.size()) << "exactly one ObstacleArray per image";
  ASSERT_EQ(h.echoed_.size(), sent.size());
  std::size_t with_obstacles = 0;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const ot::ObstacleArray& out = h.outputs_[i];
    EXPECT_TRUE(sameHeader(out.header, h.echoed_[i])) << "output " << i << " does not carry its image's header";
    EXPECT_EQ(out.header.stamp, sent[i].header.stamp);
    EXPECT_EQ(out.header.frame_id, sent[i].header.frame_id);
    EXPECT_EQ(out.image_width, sent[i].width);
    EXPECT_EQ(out.image_height, sent[i].height);
    EXPECT_GE(out.processing_time, 0.0f);
    if (!out.obstacles.empty()) ++with_obstacles;
    for (const ot::Obstacle& o : out.obstacles) {
      EXPECT_GE(o.confidence, 0.0f);
      EXPECT_LE(o.confidence, 1.0f);
      EXPECT_NE(o.state, ot::Obstacle::STATE_SEARCHING);
      EXPECT_EQ(o.has_bearing, h.use_info_);
      if (!o.has_bearing) continue;
      // Expected bearing from the test's own camera model: optical frame, then base_link.
      const sensor_msgs::CameraInfo info = ot::testing::cameraInfo(sent[i]);
      const double f = info.K[0], cx = info.K[2], cy = info.K[5];
      double x = (o.x + 0.5 * o.width - 0.5 - cx) / f, y = (o.y + 0.5 * o.height - 0.5 - cy) / f, z = 1.0;
      const double n = std::sqrt(x * x + y * y + 1.0);
      x /= n, y /= n, z /= n;
      double bx = x, by = y, bz = z;
      if (!h.target_frame_.empty()) {  // base_link: x forward = optical z, y left = -x, z up = -y
        bx = z, by = -x, bz = -y;
      }
      EXPECT_EQ(out.target_frame, h.target_frame_.empty() ? sent[i].header.frame_id : h.target_frame_);
      EXPECT_NEAR(o.bearing.x, bx, 1e-4);
      EXPECT_NEAR(o.bearing.y, by, 1e-4);
      EXPECT_NEAR(o.bearing.z, bz, 1e-4);
      // Angle between the rays through the left and right edge midpoints.
      const double yc = o.y + 0.5 * o.height - 0.5 - cy;
      const double xl = o.x - 0.5 - cx, xr = o.x + o.width - 0.5 - cx;
      const double cos_w = (xl * xr + yc * yc + f * f) /
                           (std::sqrt(xl * xl + yc * yc + f * f) * std::sqrt(xr * xr + yc * yc + f * f));
      EXPECT_NEAR(o.angular_width, std::acos(std::min(1.0, cos_w)), 1e-4);
      EXPECT_GT(o.angular_height, 0.0f);
    }
  }
  // The disc is plain to see: the tracker must report it in most frames after the first few.
  EXPECT_GE(with_obstacles, sent.size() / 2) << "the disc was reported in " << with_obstacles << " of "
                                             << sent.size() << " frames";
}

TEST(Tracker, ImagesWithoutCameraInfoAreNotAnsweredAndDiagnosed) {
  Harness& h = *harness;
  if (!h.use_info_) GTEST_SKIP() << "needs ~use_camera_info";
  ASSERT_TRUE(h.waitConnected(30.0));
  // Images alone for a few diagnostics periods: only pairs reach the tracker.
  std::vector<ros::Time> alone;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(3.0);
  while (ros::ok() && ros::WallTime::now() < end) {
    alone.push_back(h.publish(static_cast<int>(alone.size()), std::string(), false, false).header.stamp);
    ros::WallDuration(0.05).sleep();
  }
  const std::string expected = "no image + camera_info pairs received";
  std::string message;
  EXPECT_TRUE(h.waitFor([&] {
    message = h.last_diagnostics_.message;
    return message.find(expected) != std::string::npos;
  }, 10.0)) << "diagnostics say '" << message << "'";
  // Pairs again: answered, and none of the lone images was.
  const sensor_msgs::Image paired = h.publish(0);
  EXPECT_TRUE(h.waitOutputFor(paired.header.stamp, 20.0)) << "no output once camera_info is back";
  std::lock_guard<std::mutex> lock(h.mutex_);
  for (const ros::Time& t : alone) EXPECT_EQ(h.outputCountFor(t), 0u) << "an image without camera_info was answered";
}

TEST(Tracker, DynamicReconfigureIsApplied) {
  Harness& h = *harness;
  ASSERT_TRUE(h.waitConnected(30.0));
  dynamic_reconfigure::Client<ot::ObstacleTrackerConfig> client(h.tracker_);
  ot::ObstacleTrackerConfig config;
  ASSERT_TRUE(client.getCurrentConfiguration(config, ros::Duration(20.0)));
  // Start-up values: the .test sets max_obstacles to 99 (clamped to 16 with a warning) and
  // detection_interval to 3 as ROS parameters, on top of ~params_file.
  EXPECT_EQ(config.max_obstacles, 16);
  EXPECT_EQ(config.detection_interval, 3);
  ASSERT_TRUE(h.waitFor([&] { return h.diagnosedParam("max_obstacles") == 16.0; }, 20.0))
      << "the pipeline does not run with the start-up parameters";

  config.max_obstacles = 4;
  config.peak_threshold = 0.33;
  ASSERT_TRUE(client.setConfiguration(config));
  // The diagnostics report the pipeline's own Params: the change reached Pipeline::setParams.
  EXPECT_TRUE(h.waitFor([&] { return h.diagnosedParam("max_obstacles") == 4.0 &&
                                     std::abs(h.diagnosedParam("peak_threshold") - 0.33) < 1e-9; }, 20.0))
      << "max_obstacles " << h.diagnosedParam("max_obstacles") << ", peak_threshold "
      << h.diagnosedParam("peak_threshold");

  // Out of range from a client: clamped into [0, 1] before it reaches the pipeline.
  config.peak_threshold = 7.0;
  ASSERT_TRUE(client.setConfiguration(config));
  ot::ObstacleTrackerConfig now;
  ASSERT_TRUE(client.getCurrentConfiguration(now, ros::Duration(10.0)));
  EXPECT_DOUBLE_EQ(now.peak_threshold, 1.0);
  EXPECT_TRUE(h.waitFor([&] { return h.diagnosedParam("peak_threshold") == 1.0; }, 20.0));

  // Frames are still processed with the new parameters.
  for (int i = 0; i < 3; ++i) {
    const sensor_msgs::Image image = h.publish(i);
    EXPECT_TRUE(h.waitOutputFor(image.header.stamp, 20.0));
    std::lock_guard<std::mutex> lock(h.mutex_);
    EXPECT_LE(h.outputs_.back().obstacles.size(), 4u);
  }
}

TEST(Tracker, UnsupportedEncodingIsSkipped) {
  Harness& h = *harness;
  ASSERT_TRUE(h.waitConnected(30.0));
  const sensor_msgs::Image first = h.publish(0);
  ASSERT_TRUE(h.waitOutputFor(first.header.stamp, 20.0));

  std::vector<ros::Time> bad;
  for (int i = 0; i < 5; ++i) {
    bad.push_back(h.publish(1 + i, "32FC3").header.stamp);
    ros::WallDuration(0.1).sleep();
  }
  bad.push_back(h.publish(6, "bgr8", /*truncate=*/true).header.stamp);  // data shorter than step x height
  ros::WallDuration(0.1).sleep();
  bad.push_back(h.publish(7, "yuv444_garbage").header.stamp);
  ros::WallDuration(0.1).sleep();
  const sensor_msgs::Image good = h.publish(8);
  EXPECT_TRUE(h.waitOutputFor(good.header.stamp, 20.0)) << "the good frame after the bad ones was not processed";
  const sensor_msgs::Image good2 = h.publish(9);
  EXPECT_TRUE(h.waitOutputFor(good2.header.stamp, 20.0));
  ros::WallDuration(1.0).sleep();

  std::lock_guard<std::mutex> lock(h.mutex_);
  for (const ros::Time& stamp : bad) EXPECT_EQ(h.outputCountFor(stamp), 0u) << "output for a refused frame";
  EXPECT_EQ(h.outputCountFor(good.header.stamp), 1u);
  auto errorsMentioning = [&](const std::string& text) {
    return std::count_if(h.logs_.begin(), h.logs_.end(), [&](const rosgraph_msgs::Log& l) {
      return l.level == rosgraph_msgs::Log::ERROR && l.msg.find(text) != std::string::npos;
    });
  };
  // Five 32FC3 frames and one unknown encoding within a second: one throttled error naming the
  // first encoding; the malformed frame has its own (throttled) error.
  EXPECT_EQ(errorsMentioning("'32FC3'"), 1);
  EXPECT_EQ(errorsMentioning("'yuv444_garbage'"), 0);
  EXPECT_EQ(errorsMentioning("malformed 'bgr8'"), 1);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "obstacle_tracker_rostest");
  ros::AsyncSpinner spinner(3);
  spinner.start();
  Harness h;
  harness = &h;
  const int result = RUN_ALL_TESTS();
  harness = nullptr;
  spinner.stop();
  ros::shutdown();
  return result;
}
