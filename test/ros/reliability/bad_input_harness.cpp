// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "bad_input_harness.h"

#include <cstdio>
#include <cstdlib>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <sensor_msgs/CameraInfo.h>

namespace obstacle_tracker {
namespace reliability {

Context* ctx = nullptr;

namespace {
void onLog(const rosgraph_msgs::Log::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(ctx->mutex);
  ctx->logs.push_back(*msg);
}

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(ctx->mutex);
  for (const auto& status : msg->status) {
    auto& values = ctx->diagnostics[status.name];
    for (const auto& kv : status.values) values[kv.key] = kv.value;
    values["__message"] = status.message;
  }
}

}  // namespace

void connect(Context& context) {
  ctx = &context;
  context.nh.reset(new ros::NodeHandle);
  ros::NodeHandle& nh = *context.nh;
  context.image_pub = nh.advertise<sensor_msgs::Image>("/camera/image", 1);
  context.geo_image_pub = nh.advertise<sensor_msgs::Image>("/geo/image", 1);
  context.geo_info_pub = nh.advertise<sensor_msgs::CameraInfo>("/geo/camera_info", 1);
  context.out_sub = nh.subscribe<obstacle_tracker::ObstacleArray>(
      "/tracker/obstacles", 10, &OutputCollector::callback, &context.out);
  context.geo_out_sub = nh.subscribe<obstacle_tracker::ObstacleArray>(
      "/tracker_geo/obstacles", 10, &OutputCollector::callback, &context.geo_out);
  context.log_sub = nh.subscribe("/rosout", 1000, onLog);
  context.diag_sub = nh.subscribe("/diagnostics", 100, onDiagnostics);
}

bool waitForTrackers() {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::WallTime::now() < end &&
         (ctx->image_pub.getNumSubscribers() == 0 || ctx->out_sub.getNumPublishers() == 0 ||
          ctx->geo_image_pub.getNumSubscribers() == 0 || ctx->geo_info_pub.getNumSubscribers() == 0 ||
          ctx->geo_out_sub.getNumPublishers() == 0 || ctx->log_sub.getNumPublishers() < 2)) {
    ros::WallDuration(0.1).sleep();
  }
  if (ctx->manager_pid <= 0) ctx->manager_pid = nodePid("/manager");
  return ctx->image_pub.getNumSubscribers() > 0 && ctx->out_sub.getNumPublishers() > 0 &&
         ctx->geo_image_pub.getNumSubscribers() > 0 && ctx->geo_out_sub.getNumPublishers() > 0 &&
         ctx->manager_pid > 0;
}

// A /rosout message at WARN or above containing every one of `parts`.
bool logged(const std::vector<std::string>& parts) {
  std::lock_guard<std::mutex> lock(ctx->mutex);
  for (const auto& log : ctx->logs) {
    if (log.level < rosgraph_msgs::Log::WARN) continue;
    bool all = true;
    for (const auto& p : parts) all = all && log.msg.find(p) != std::string::npos;
    if (all) return true;
  }
  return false;
}

bool waitLogged(const std::vector<std::string>& parts, double timeout) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::WallTime::now() < end) {
    if (logged(parts)) return true;
    ros::WallDuration(0.05).sleep();
  }
  return logged(parts);
}

// The diagnostics value `key` of the status whose name starts with `prefix` (-1 if absent).
double diagnosticValue(const std::string& prefix, const std::string& key) {
  std::lock_guard<std::mutex> lock(ctx->mutex);
  for (const auto& status : ctx->diagnostics) {
    if (status.first.rfind(prefix, 0) != 0 || status.first.find("obstacle tracker") == std::string::npos) continue;
    auto it = status.second.find(key);
    if (it != status.second.end()) return std::atof(it->second.c_str());
  }
  return -1.0;
}

::testing::AssertionResult managerAlive() {
  if (processAlive(ctx->manager_pid)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "nodelet manager (pid " << ctx->manager_pid << ") is gone";
}

// Publishes a good frame (moving square, fresh stamp) and waits for its output; a few attempts
// (a frame can be replaced in the queue of size 1 while the tracker is busy).
::testing::AssertionResult goodFrameProcessed(const std::string& after) {
  for (int attempt = 0; attempt < 4; ++attempt) {
    ctx->good_x = 40 + (ctx->good_x - 40 + 2) % 60;
    sensor_msgs::Image img = squareImage(160, 120, ctx->good_x, 50, 20);
    img.header.stamp = ros::Time::now();
    img.header.frame_id = "camera";
    ctx->image_pub.publish(img);
    auto out = ctx->out.waitFor(img.header.stamp, 5.0);
    if (out) {
      const std::string bad = checkOutput(*out);
      if (!bad.empty()) return ::testing::AssertionFailure() << "good frame after " << after << ": " << bad;
      if (out->image_width != 160 || out->image_height != 120) {
        return ::testing::AssertionFailure() << "good frame after " << after << ": wrong size in the output";
      }
      if (!managerAlive()) return managerAlive() << " after " << after;
      return ::testing::AssertionSuccess();
    }
  }
  if (!managerAlive()) return managerAlive() << " after " << after;
  return ::testing::AssertionFailure() << "no ObstacleArray for a good frame after " << after;
}

sensor_msgs::Image rawImage(std::uint32_t width, std::uint32_t height, const std::string& encoding,
                            std::uint32_t step, std::size_t bytes, std::uint8_t fill) {
  sensor_msgs::Image img;
  img.width = width;
  img.height = height;
  img.encoding = encoding;
  img.step = step;
  img.data.assign(bytes, fill);
  img.header.frame_id = "camera";
  return img;
}

std::size_t logCount() {
  std::lock_guard<std::mutex> lock(ctx->mutex);
  return ctx->logs.size();
}

// /rosout messages since `from` (an index from logCount()) that contain `part`.
int logsSince(std::size_t from, const std::string& part) {
  std::lock_guard<std::mutex> lock(ctx->mutex);
  int n = 0;
  for (std::size_t i = from; i < ctx->logs.size(); ++i) n += ctx->logs[i].msg.find(part) != std::string::npos;
  return n;
}


// Sends one bad image, then a good frame must get through and the manager must be alive.
void sendBad(const std::string& what, sensor_msgs::Image img, Expect expect, bool keep_stamp,
             double timeout) {
  SCOPED_TRACE(what);
  if (!keep_stamp) img.header.stamp = ros::Time::now();
  const std::size_t before = ctx->out.count();
  const std::size_t logs_before = logCount();
  ctx->image_pub.publish(img);
  if (expect == Expect::kProcessed) {
    auto out = ctx->out.waitFor(img.header.stamp, timeout);
    ASSERT_TRUE(out != nullptr) << what << ": no output";
    EXPECT_EQ(checkOutput(*out), "") << what;
    EXPECT_EQ(out->image_width, img.width) << what;
  } else {
    ros::WallDuration(0.4).sleep();
    if (expect == Expect::kRefused) {
      EXPECT_EQ(ctx->out.count(), before) << what << ": refused frame produced an output";
      ++ctx->refused_expected;
    }
  }
  EXPECT_TRUE(goodFrameProcessed(what));
  std::printf("bad input '%s': %s, %zu outputs before, %zu after\n", what.c_str(),
              expect == Expect::kProcessed ? "processed" : expect == Expect::kRefused ? "refused" : "either",
              before, ctx->out.count());
  if (expect == Expect::kProcessed) {
    EXPECT_EQ(logsSince(logs_before, "error on a"), 0) << what << ": a processed frame was also reported as an error";
  }
}

}  // namespace reliability
}  // namespace obstacle_tracker
