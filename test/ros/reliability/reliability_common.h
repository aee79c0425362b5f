// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Helpers shared by the reliability rostests (test/ros/reliability): the pid and resident set
// of another node (through its XML-RPC getPid), image messages, and waiting for the tracker's
// output for a given stamp.
#pragma once

#include <signal.h>
#include <sys/types.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include "obstacle_tracker/ObstacleArray.h"

namespace obstacle_tracker {
namespace reliability {

// Process id of a node, asked through its own XML-RPC server (ROS master API: lookupNode, then
// the slave API's getPid). -1 when the node is not registered or does not answer.
inline int nodePid(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, false)) return -1;
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port)) return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue call_args, call_result;
  call_args[0] = ros::this_node::getName();
  if (!client.execute("getPid", call_args, call_result) || client.isFault()) return -1;
  if (call_result.getType() != XmlRpc::XmlRpcValue::TypeArray || call_result.size() < 3) return -1;
  return static_cast<int>(call_result[2]);
}

// True when the process exists and is not a zombie.
inline bool processAlive(int pid) {
  if (pid <= 0 || ::kill(pid, 0) != 0) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  const std::size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}

// VmRSS of a process in KiB (-1 when unreadable).
inline long residentKiB(int pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kib = -1;
      status >> kib;
      return kib;
    }
    std::string rest;
    std::getline(status, rest);
  }
  return -1;
}

// A mono8 or bgr8 image with a bright square on a dark graded background.
inline sensor_msgs::Image squareImage(std::uint32_t width, std::uint32_t height, int x, int y, int side,
                                      const std::string& encoding = "mono8") {
  sensor_msgs::Image img;
  img.width = width;
  img.height = height;
  img.encoding = encoding;
  const std::uint32_t channels = encoding == "bgr8" ? 3 : 1;
  img.step = width * channels;
  img.data.resize(static_cast<std::size_t>(img.step) * height);
  for (std::uint32_t r = 0; r < height; ++r) {
    const std::uint8_t bg = static_cast<std::uint8_t>(30 + 10 * r / std::max<std::uint32_t>(1, height));
    std::fill(img.data.begin() + static_cast<long>(r) * img.step,
              img.data.begin() + static_cast<long>(r + 1) * img.step, bg);
  }
  for (int r = std::max(0, y); r < std::min<int>(static_cast<int>(height), y + side); ++r) {
    for (int c = std::max(0, x); c < std::min<int>(static_cast<int>(width), x + side); ++c) {
      for (std::uint32_t k = 0; k < channels; ++k) {
        img.data[static_cast<std::size_t>(r) * img.step + static_cast<std::size_t>(c) * channels + k] = 220;
      }
    }
  }
  return img;
}

// Collects the tracker's ObstacleArray messages by stamp; waits for one.
class OutputCollector {
 public:
  void callback(const obstacle_tracker::ObstacleArray::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    received_[msg->header.stamp] = msg;
    last_ = msg;
    ++count_;
    cv_.notify_all();
  }
  // The output for this stamp, or null after `timeout` seconds (wall time).
  obstacle_tracker::ObstacleArray::ConstPtr waitFor(const ros::Time& stamp, double timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
    while (true) {
      auto it = received_.find(stamp);
      if (it != received_.end()) return it->second;
      if (cv_.wait_until(lock, deadline) == std::cv_status::timeout) {
        it = received_.find(stamp);
        return it != received_.end() ? it->second : nullptr;
      }
    }
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::map<ros::Time, obstacle_tracker::ObstacleArray::ConstPtr> received_;
  obstacle_tracker::ObstacleArray::ConstPtr last_;
  std::size_t count_ = 0;
};

// Every obstacle finite, confidence in [0, 1]; the header's size matches the image.
inline std::string checkOutput(const obstacle_tracker::ObstacleArray& out) {
  std::ostringstream bad;
  for (const auto& o : out.obstacles) {
    if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.width) || !std::isfinite(o.height)) {
      bad << "non-finite box; ";
    }
    if (!(o.confidence >= 0.0f && o.confidence <= 1.0f)) bad << "confidence " << o.confidence << "; ";
    if (std::isnan(o.expansion_rate) || std::isnan(o.time_to_contact)) bad << "NaN looming; ";
    if (o.has_bearing) {
      const double n = std::sqrt(o.bearing.x * o.bearing.x + o.bearing.y * o.bearing.y + o.bearing.z * o.bearing.z);
      if (!(std::fabs(n - 1.0) < 1e-3)) bad << "bearing not a unit vector (" << n << "); ";
      if (!std::isfinite(o.angular_width) || !std::isfinite(o.angular_height)) bad << "non-finite angular size; ";
    }
  }
  return bad.str();
}

}  // namespace reliability
}  // namespace obstacle_tracker
