// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Accuracy rostest (test/ros/accuracy/*.test): `rosbag play` sends a bag made by
// scripts/sequence_to_bag.py (images, camera_info, /ground_truth) through the real nodelet in a
// nodelet manager; this node reads the ground truth from the same bag file, listens to the
// images and the tracker's ~obstacles, and asserts:
//   - one ObstacleArray per image, with the image's stamp (none missing, none doubled, none with
//     a stamp that was not sent);
//   - OTB precision at 20 px and success AUC (src/eval/metrics.cpp, the evaluate tool's code)
//     of the best obstacle against the ground truth at least ~min_precision20 / ~min_auc;
//   - the output rate within ~rate_tolerance of the bag's frame rate times the play rate;
//   - latency: in a replay the stamps are the recording's, so latency is measured from the
//     moment an image reaches a subscriber (this node) to the moment its ObstacleArray arrives,
//     both on this host's wall clock: median <= ~max_latency_median_ms, 95th percentile <=
//     ~max_latency_p95_ms.
// With ~bag empty the test is skipped and prints ~skip_reason (e.g. no ../shared/sequences).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>

#include "obstacle_tracker/ObstacleArray.h"
#include "obstacle_tracker/eval/metrics.h"

namespace ev = obstacle_tracker::eval;

namespace {

struct Output {
  int count = 0;
  cv::Rect2f box;
  float confidence = 0.0f;
  double arrival = 0.0;  // wall clock, s
  float processing = 0.0f;  // the tracker's own processing_time, s
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double k = (v.size() - 1) * q / 100.0;
  const size_t lo = static_cast<size_t>(std::floor(k)), hi = static_cast<size_t>(std::ceil(k));
  return v[lo] + (v[hi] - v[lo]) * (k - lo);
}

double wallNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class AccuracyTest : public ::testing::Test {
 public:
  AccuracyTest() : pnh_("~") {
    pnh_.param("bag", bag_, std::string());
    pnh_.param("skip_reason", skip_reason_, std::string("no bag given"));
    pnh_.param("name", name_, std::string("accuracy"));
    pnh_.param("gt_topic", gt_topic_, std::string("/ground_truth"));
    pnh_.param("image_topic", image_topic_, std::string("/camera/image_raw"));
    pnh_.param("obstacles_topic", obstacles_topic_, std::string("/obstacle_tracker/obstacles"));
    pnh_.param("play_rate", play_rate_, 1.0);
    pnh_.param("min_precision20", min_precision20_, 0.8);
    pnh_.param("min_auc", min_auc_, 0.5);
    pnh_.param("rate_tolerance", rate_tolerance_, 0.2);
    pnh_.param("max_latency_median_ms", max_latency_median_ms_, 50.0);
    pnh_.param("max_latency_p95_ms", max_latency_p95_ms_, 150.0);
    pnh_.param("timeout", timeout_, 240.0);
  }

  void onImage(const sensor_msgs::ImageConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    const uint64_t s = msg->header.stamp.toNSec();
    if (!image_arrival_.count(s)) image_arrival_[s] = wallNow();
    last_image_ = wallNow();
    cv_.notify_all();
  }

  void onObstacles(const obstacle_tracker::ObstacleArrayConstPtr& msg) {
    const double now = wallNow();
    std::lock_guard<std::mutex> lock(mutex_);
    Output& o = outputs_[msg->header.stamp.toNSec()];
    if (++o.count == 1) {
      o.arrival = now;
      o.processing = msg->processing_time;
      if (!msg->obstacles.empty()) {
        const auto& b = msg->obstacles.front();
        o.box = cv::Rect2f(b.x, b.y, b.width, b.height);
        o.confidence = b.confidence;
      }
    }
    ++output_messages_;
    cv_.notify_all();
  }

  ros::NodeHandle nh_, pnh_;
  std::string bag_, skip_reason_, name_, gt_topic_, image_topic_, obstacles_topic_;
  double play_rate_, min_precision20_, min_auc_, rate_tolerance_, max_latency_median_ms_,
      max_latency_p95_ms_, timeout_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::map<uint64_t, double> image_arrival_;
  std::map<uint64_t, Output> outputs_;
  int output_messages_ = 0;
  double last_image_ = 0.0;
};

TEST_F(AccuracyTest, ReplayThroughTheNodelet) {
  if (bag_.empty()) {
    std::printf("[ SKIPPED ] %s: %s\n", name_.c_str(), skip_reason_.c_str());
    ROS_WARN("accuracy test %s skipped: %s", name_.c_str(), skip_reason_.c_str());
    GTEST_SKIP() << skip_reason_;
  }
  // Ground truth straight from the bag file: every stamp that will be played.
  std::vector<uint64_t> stamps;
  std::vector<cv::Rect2f> gt;
  {
    rosbag::Bag bag(bag_, rosbag::bagmode::Read);
    rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{gt_topic_}));
    for (const rosbag::MessageInstance& m : view) {
      auto msg = m.instantiate<obstacle_tracker::ObstacleArray>();
      ASSERT_TRUE(msg != nullptr) << gt_topic_ << " is not an ObstacleArray";
      stamps.push_back(msg->header.stamp.toNSec());
      if (msg->obstacles.empty()) {
        gt.emplace_back();
      } else {
        const auto& b = msg->obstacles.front();
        gt.emplace_back(b.x, b.y, b.width, b.height);
      }
    }
  }
  ASSERT_GE(stamps.size(), 10u) << "too few ground-truth frames in " << bag_;
  const double bag_fps = (stamps.size() - 1) / ((stamps.back() - stamps.front()) * 1e-9);

  ros::Subscriber image_sub = nh_.subscribe(image_topic_, 200, &AccuracyTest::onImage, static_cast<AccuracyTest*>(this));
  ros::Subscriber obstacles_sub = nh_.subscribe(obstacles_topic_, 200, &AccuracyTest::onObstacles, static_cast<AccuracyTest*>(this));
  ros::AsyncSpinner spinner(1);
  spinner.start();

  // rosbag play waits for the subscribers; then give it the clip's duration plus slack.
  const double start = wallNow();
  {
    std::unique_lock<std::mutex> lock(mutex_);
    const bool started = cv_.wait_for(lock, std::chrono::duration<double>(timeout_ / 2),
                                      [&] { return !image_arrival_.empty(); });
    ASSERT_TRUE(started) << "no image on " << image_topic_ << " within " << timeout_ / 2 << " s";
    // Done when every stamp has an output, or 5 s after the last image with nothing new.
    while (wallNow() - start < timeout_) {
      if (outputs_.size() >= stamps.size() && wallNow() - last_image_ > 1.0) break;
      if (image_arrival_.size() >= stamps.size() && wallNow() - last_image_ > 5.0) break;
      cv_.wait_for(lock, std::chrono::milliseconds(200));
    }
  }
  spinner.stop();
  std::lock_guard<std::mutex> lock(mutex_);

  // One output per frame, with the frame's stamp.
  std::vector<cv::Rect2f> predicted(stamps.size());
  std::vector<float> confidence(stamps.size(), 0.0f);
  std::vector<double> latency_ms, arrivals;
  int missing = 0, doubled = 0;
  std::string missing_frames;
  double worst_ms = -1.0;
  int worst_frame = -1;
  std::vector<double> processing_ms;
  double worst_proc_ms = -1.0;
  int worst_proc_frame = -1;
  for (size_t i = 0; i < stamps.size(); ++i) {
    auto it = outputs_.find(stamps[i]);
    if (it == outputs_.end()) {
      if (++missing <= 20) missing_frames += " " + std::to_string(i);
      continue;
    }
    if (it->second.count > 1) ++doubled;
    processing_ms.push_back(1e3 * it->second.processing);
    if (processing_ms.back() > worst_proc_ms) {
      worst_proc_ms = processing_ms.back();
      worst_proc_frame = static_cast<int>(i);
    }
    predicted[i] = it->second.box;
    confidence[i] = it->second.confidence;
    arrivals.push_back(it->second.arrival);
    auto im = image_arrival_.find(stamps[i]);
    if (im != image_arrival_.end()) {
      latency_ms.push_back(1e3 * (it->second.arrival - im->second));
      if (latency_ms.back() > worst_ms) {
        worst_ms = latency_ms.back();
        worst_frame = static_cast<int>(i);
      }
    }
  }
  int unknown = 0;
  for (const auto& kv : outputs_)
    if (!std::binary_search(stamps.begin(), stamps.end(), kv.first)) ++unknown;

  const ev::OtbScores otb = ev::otbScores(predicted, gt);
  std::sort(arrivals.begin(), arrivals.end());
  const double out_rate = arrivals.size() > 1 ? (arrivals.size() - 1) / (arrivals.back() - arrivals.front()) : 0.0;
  const double want_rate = bag_fps * play_rate_;
  const double lat_med = percentile(latency_ms, 50), lat_p95 = percentile(latency_ms, 95),
               lat_p99 = percentile(latency_ms, 99), lat_max = percentile(latency_ms, 100);
  std::printf(
      "[ RESULT  ] %s: %zu frames (%zu images seen), %d outputs, %d missing, %d doubled, %d unknown stamps\n"
      "[ RESULT  ] %s: P@20 %.3f (bar %.3f), AUC %.3f (bar %.3f), mean centre error %.1f px, no box %.3f\n"
      "[ RESULT  ] %s: output rate %.2f Hz (bag %.2f fps x play rate %.2f = %.2f Hz, tolerance %.0f%%)\n"
      "[ RESULT  ] %s: latency image arrival -> obstacles arrival: median %.2f ms (bar %.0f), p95 %.2f ms "
      "(bar %.0f), p99 %.2f ms, max %.2f ms (frame %d)\n"
      "[ RESULT  ] %s: the tracker's processing_time: median %.2f ms, p99 %.2f ms, max %.2f ms (frame %d)\n",
      name_.c_str(), stamps.size(), image_arrival_.size(), output_messages_, missing, doubled, unknown,
      name_.c_str(), otb.precision20, min_precision20_, otb.auc, min_auc_, otb.mean_centre_error, otb.lost_fraction,
      name_.c_str(), out_rate, bag_fps, play_rate_, want_rate, 100 * rate_tolerance_, name_.c_str(), lat_med,
      max_latency_median_ms_, lat_p95, max_latency_p95_ms_, lat_p99, lat_max, worst_frame, name_.c_str(),
      percentile(processing_ms, 50), percentile(processing_ms, 99), worst_proc_ms, worst_proc_frame);
  std::fflush(stdout);

  EXPECT_EQ(missing, 0) << "frames without an ObstacleArray (0-based, first 20):" << missing_frames;
  EXPECT_EQ(doubled, 0) << "frames with more than one ObstacleArray";
  EXPECT_EQ(unknown, 0) << "ObstacleArrays whose stamp was never sent";
  EXPECT_GE(otb.precision20, min_precision20_);
  EXPECT_GE(otb.auc, min_auc_);
  EXPECT_NEAR(out_rate / want_rate, 1.0, rate_tolerance_) << "output rate " << out_rate << " Hz";
  ASSERT_FALSE(latency_ms.empty());
  EXPECT_LE(lat_med, max_latency_median_ms_);
  EXPECT_LE(lat_p95, max_latency_p95_ms_);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "accuracy_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
