// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Rostest (load.test): 1280x720 frames at 200 Hz for ~duration s (default 60) into the
// nodelet in a real manager (issue 6). Checks, printed with their figures:
//   - latency (image stamp -> receipt of the ObstacleArray) does not grow: the median of the
//     last 10 s is at most 2 x the median of the first 10 s after warm-up + 50 ms (a queue that
//     kept old frames would grow by ~0.75 s per second);
//   - the manager's resident set (VmRSS) grows by less than 5 MiB between the end of warm-up and
//     the end (medians of 5 s of samples at 10 Hz);
//   - the manager is alive at the end, frames were processed throughout, and the diagnostics
//     report a dropped-frame count > 0 (the queue of size 1 drops what the tracker cannot take).
// Parameters (private): duration (s), rate (Hz), width, height, encoding (mono8 | bgr8),
// warmup (s, default min(10, duration / 4)).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "reliability_common.h"

namespace rel = obstacle_tracker::reliability;

namespace {

struct Sample {
  double t;      // wall seconds since the start of the load
  double value;
};

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

std::vector<double> window(const std::vector<Sample>& samples, double from, double to) {
  std::vector<double> out;
  for (const Sample& s : samples) {
    if (s.t >= from && s.t < to) out.push_back(s.value);
  }
  return out;
}

struct State {
  std::mutex mutex;
  ros::WallTime start;
  std::atomic<bool> started{false};
  std::vector<Sample> latency;  // s
  double dropped_total = -1.0;
  double processed_total = -1.0;
};
State* state = nullptr;

void onOutput(const obstacle_tracker::ObstacleArray::ConstPtr& msg) {
  if (!state->started) return;
  const double latency = (ros::Time::now() - msg->header.stamp).toSec();
  std::lock_guard<std::mutex> lock(state->mutex);
  state->latency.push_back({(ros::WallTime::now() - state->start).toSec(), latency});
}

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(state->mutex);
  for (const auto& status : msg->status) {
    if (status.name.rfind("tracker:", 0) != 0) continue;
    for (const auto& kv : status.values) {
      if (kv.key == "dropped frames (total)") state->dropped_total = std::atof(kv.value.c_str());
      if (kv.key == "frames processed (total)") state->processed_total = std::atof(kv.value.c_str());
    }
  }
}

}  // namespace

TEST(Load, NewestFrameBoundedMemoryDropsCounted) {
  ros::NodeHandle nh, pnh("~");
  double duration = 60.0, rate = 200.0;
  int width = 1280, height = 720;
  std::string encoding = "mono8";
  pnh.param("duration", duration, duration);
  pnh.param("rate", rate, rate);
  pnh.param("width", width, width);
  pnh.param("height", height, height);
  pnh.param("encoding", encoding, encoding);
  double warmup = std::min(10.0, duration / 4.0);
  pnh.param("warmup", warmup, warmup);
  const double win = std::min(10.0, (duration - warmup) / 2.0);  // latency comparison windows
  ASSERT_GT(win, 1.0) << "duration too short";

  ros::Publisher pub = nh.advertise<sensor_msgs::Image>("/load/image", 1);
  ros::Subscriber out_sub = nh.subscribe("/tracker/obstacles", 10, onOutput);
  ros::Subscriber diag_sub = nh.subscribe("/diagnostics", 10, onDiagnostics);
  const ros::WallTime wait_end = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::WallTime::now() < wait_end && (pub.getNumSubscribers() == 0 || out_sub.getNumPublishers() == 0)) {
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_GT(pub.getNumSubscribers(), 0u);
  const int pid = rel::nodePid("/manager");
  ASSERT_GT(pid, 0) << "cannot get the manager's pid";

  // A textured background (drawn once) and a square that moves and grows slowly.
  sensor_msgs::Image img = rel::squareImage(width, height, 0, 0, 0, encoding);
  img.header.frame_id = "camera";
  for (std::size_t i = 0; i < img.data.size(); ++i) {
    img.data[i] = static_cast<std::uint8_t>(img.data[i] + ((i * 2654435761u) >> 28));
  }
  const std::vector<std::uint8_t> background = img.data;
  const int channels = encoding == "bgr8" ? 3 : 1;

  std::vector<Sample> rss;  // MiB
  state->start = ros::WallTime::now();
  state->started = true;
  ros::WallRate loop(rate);
  long published = 0;
  double next_rss = 0.0;
  double t = 0.0;
  while ((t = (ros::WallTime::now() - state->start).toSec()) < duration && ros::ok()) {
    const int side = 40 + static_cast<int>(20 * t / duration);
    const int x = static_cast<int>(width / 2 + width / 4 * std::sin(t * 0.7)) - side / 2;
    const int y = static_cast<int>(height / 2 + height / 6 * std::cos(t * 0.5)) - side / 2;
    std::copy(background.begin(), background.end(), img.data.begin());
    for (int r = std::max(0, y); r < std::min(height, y + side); ++r) {
      std::fill(img.data.begin() + static_cast<long>(r) * img.step + std::max(0, x) * channels,
                img.data.begin() + static_cast<long>(r) * img.step + std::min(width, x + side) * channels, 230);
    }
    img.header.stamp = ros::Time::now();
    pub.publish(img);
    ++published;
    if (t >= next_rss) {
      rss.push_back({t, rel::residentKiB(pid) / 1024.0});
      next_rss += 0.1;
    }
    loop.sleep();
  }
  const double elapsed = (ros::WallTime::now() - state->start).toSec();
  const bool alive = rel::processAlive(pid);
  ros::WallDuration(2.5).sleep();  // the last diagnostics
  state->started = false;

  std::lock_guard<std::mutex> lock(state->mutex);
  const double first = median(window(state->latency, warmup, warmup + win));
  const double last = median(window(state->latency, elapsed - win, elapsed + 1.0));
  const double rss_warm = median(window(rss, warmup, warmup + 5.0));
  const double rss_end = median(window(rss, elapsed - 5.0, elapsed + 1.0));
  double rss_max = 0.0;
  for (const Sample& s : rss) rss_max = std::max(rss_max, s.value);
  std::printf("load: %dx%d %s, %.0f Hz asked, %ld frames in %.1f s (%.1f Hz published)\n", width, height,
              encoding.c_str(), rate, published, elapsed, published / elapsed);
  std::printf("load: %zu outputs (%.1f Hz); diagnostics: %.0f processed, %.0f dropped\n", state->latency.size(),
              state->latency.size() / elapsed, state->processed_total, state->dropped_total);
  std::printf("load: latency median %.1f ms in [%.0f, %.0f) s, %.1f ms in the last %.0f s\n", 1e3 * first, warmup,
              warmup + win, 1e3 * last, win);
  std::printf("load: manager VmRSS %.1f MiB after warm-up, %.1f MiB at the end (max %.1f MiB)\n", rss_warm,
              rss_end, rss_max);
  std::fflush(stdout);

  EXPECT_TRUE(alive) << "the nodelet manager died under load";
  EXPECT_GT(published / elapsed, 0.5 * rate) << "the publisher could not keep the rate (machine overloaded?)";
  ASSERT_FALSE(std::isnan(first)) << "no output in the first window";
  ASSERT_FALSE(std::isnan(last)) << "no output in the last window: the tracker stopped";
  EXPECT_LE(last, 2.0 * first + 0.05) << "latency grew: frames are queued instead of dropped";
  EXPECT_LT(last, 1.0) << "latency above a second";
  EXPECT_LT(rss_end - rss_warm, 5.0) << "resident set grew by " << rss_end - rss_warm << " MiB";
  EXPECT_GT(state->dropped_total, 0.0) << "diagnostics report no dropped frame at " << rate << " Hz";
  EXPECT_GE(state->latency.size(), static_cast<std::size_t>(2 * elapsed)) << "fewer than 2 outputs per second";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "reliability_load");
  State s;
  state = &s;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  state = nullptr;
  return result;
}
