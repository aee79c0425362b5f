// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// What the bad-input rostest's test cases share (bad_input.cpp, bad_geometry.cpp): the test
// node's publishers and subscribers, the /rosout and /diagnostics it has seen, and checks that
// the nodelet manager lives and that a good frame still gets its ObstacleArray.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/Image.h>

#include "reliability_common.h"

namespace obstacle_tracker {
namespace reliability {

inline const double kNan = std::numeric_limits<double>::quiet_NaN();
inline const double kInf = std::numeric_limits<double>::infinity();

// The test node's connections and what it has received; one instance, made by main().
struct Context {
  std::unique_ptr<ros::NodeHandle> nh;
  ros::Publisher image_pub, geo_image_pub, geo_info_pub;
  ros::Subscriber out_sub, geo_out_sub, log_sub, diag_sub;
  OutputCollector out, geo_out;
  std::mutex mutex;
  std::vector<rosgraph_msgs::Log> logs;
  std::map<std::string, std::map<std::string, std::string>> diagnostics;  // status name -> key -> value
  int manager_pid = -1;
  int good_x = 40;
  int refused_expected = 0;
};
extern Context* ctx;

// Connects ctx's publishers and subscribers (tracker on /camera/image, tracker_geo on /geo/*).
void connect(Context& context);

// Waits (up to 30 s) until both trackers are connected and the manager's pid is known; true when
// they are.
bool waitForTrackers();

// A /rosout message at WARN or above containing every one of `parts` (waitLogged: within timeout s).
bool logged(const std::vector<std::string>& parts);
bool waitLogged(const std::vector<std::string>& parts, double timeout);

// The diagnostics value `key` of the status whose name starts with `prefix` (-1 if absent).
double diagnosticValue(const std::string& prefix, const std::string& key);

::testing::AssertionResult managerAlive();

// Publishes a good frame (moving square, fresh stamp) and waits for its output; a few attempts
// (a frame can be replaced in the queue of size 1 while the tracker is busy).
::testing::AssertionResult goodFrameProcessed(const std::string& after);

sensor_msgs::Image rawImage(std::uint32_t width, std::uint32_t height, const std::string& encoding,
                            std::uint32_t step, std::size_t bytes, std::uint8_t fill = 100);

// /rosout messages so far; those since `from` (an index from logCount()) that contain `part`.
std::size_t logCount();
int logsSince(std::size_t from, const std::string& part);

enum class Expect {
  kProcessed,  // a valid but odd image: an output for it, and no error logged
  kRefused,    // no output; counted as refused in the diagnostics
  kEither,     // converted or refused (documented either way); never a crash
};

// Sends one bad image, then a good frame must get through and the manager must be alive.
void sendBad(const std::string& what, sensor_msgs::Image img, Expect expect, bool keep_stamp = false,
             double timeout = 15.0);

}  // namespace reliability
}  // namespace obstacle_tracker
