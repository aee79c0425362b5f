// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Rostest (bad_input.test): a real nodelet manager with two ObstacleTrackerNodelets, fed every
// kind of bad input: unsupported encodings, empty / tiny / thin / 8000x8000 images,
// data shorter than step x height, step shorter than a row, sizes whose step x height overflows
// 32 bits, odd 16-bit steps, duplicate / backward / jumping / zero stamps, flat frames, 32FC1
// full of NaN; bad parameters at startup (launch file) and through dynamic_reconfigure; bad
// camera_info (zeros, NaN, wrong distortion) and a missing tf. After each bad input the next good
// frame must give an ObstacleArray and the manager must still be alive; refusals must be logged
// and counted in the diagnostics.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <ros/topic.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/scene/scene_generator.h"
#include "reliability_common.h"

namespace rel = obstacle_tracker::reliability;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

struct Context {
  std::unique_ptr<ros::NodeHandle> nh;
  ros::Publisher image_pub, geo_image_pub, geo_info_pub;
  ros::Subscriber out_sub, geo_out_sub, log_sub, diag_sub;
  rel::OutputCollector out, geo_out;
  std::mutex mutex;
  std::vector<rosgraph_msgs::Log> logs;
  std::map<std::string, std::map<std::string, std::string>> diagnostics;  // status name -> key -> value
  int manager_pid = -1;
  int good_x = 40;
  int refused_expected = 0;
};
Context* ctx = nullptr;

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
  if (rel::processAlive(ctx->manager_pid)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "nodelet manager (pid " << ctx->manager_pid << ") is gone";
}

// Publishes a good frame (moving square, fresh stamp) and waits for its output; a few attempts
// (a frame can be replaced in the queue of size 1 while the tracker is busy).
::testing::AssertionResult goodFrameProcessed(const std::string& after) {
  for (int attempt = 0; attempt < 4; ++attempt) {
    ctx->good_x = 40 + (ctx->good_x - 40 + 2) % 60;
    sensor_msgs::Image img = rel::squareImage(160, 120, ctx->good_x, 50, 20);
    img.header.stamp = ros::Time::now();
    img.header.frame_id = "camera";
    ctx->image_pub.publish(img);
    auto out = ctx->out.waitFor(img.header.stamp, 5.0);
    if (out) {
      const std::string bad = rel::checkOutput(*out);
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
                            std::uint32_t step, std::size_t bytes, std::uint8_t fill = 100) {
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

enum class Expect {
  kProcessed,  // a valid but odd image: an output for it, and no error logged
  kRefused,    // no output; counted as refused in the diagnostics
  kEither,     // converted or refused (documented either way); never a crash
};

// Sends one bad image, then a good frame must get through and the manager must be alive.
void sendBad(const std::string& what, sensor_msgs::Image img, Expect expect, bool keep_stamp = false,
             double timeout = 15.0) {
  SCOPED_TRACE(what);
  if (!keep_stamp) img.header.stamp = ros::Time::now();
  const std::size_t before = ctx->out.count();
  const std::size_t logs_before = logCount();
  ctx->image_pub.publish(img);
  if (expect == Expect::kProcessed) {
    auto out = ctx->out.waitFor(img.header.stamp, timeout);
    ASSERT_TRUE(out != nullptr) << what << ": no output";
    EXPECT_EQ(rel::checkOutput(*out), "") << what;
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

}  // namespace

TEST(BadInput, ManagerAndTrackersAreUp) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::WallTime::now() < end &&
         (ctx->image_pub.getNumSubscribers() == 0 || ctx->out_sub.getNumPublishers() == 0 ||
          ctx->geo_image_pub.getNumSubscribers() == 0 || ctx->geo_info_pub.getNumSubscribers() == 0 ||
          ctx->geo_out_sub.getNumPublishers() == 0 || ctx->log_sub.getNumPublishers() < 2)) {
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_GT(ctx->image_pub.getNumSubscribers(), 0u);
  ASSERT_GT(ctx->out_sub.getNumPublishers(), 0u);
  ctx->manager_pid = rel::nodePid("/manager");
  ASSERT_GT(ctx->manager_pid, 0) << "cannot get the manager's pid through XML-RPC getPid";
  ASSERT_TRUE(managerAlive());
  ASSERT_TRUE(goodFrameProcessed("start"));
}

TEST(BadInput, StartupParametersWereValidated) {
  // bad_input.test sets NaN, -5, 1e9, inf, a string and 1e12 on the parameter server. The values
  // in use are published (latched) by dynamic_reconfigure.
  auto config = ros::topic::waitForMessage<dynamic_reconfigure::Config>("/tracker/parameter_updates", *ctx->nh,
                                                                         ros::Duration(10.0));
  ASSERT_TRUE(config != nullptr);
  std::map<std::string, double> v;
  for (const auto& d : config->doubles) v[d.name] = d.value;
  for (const auto& i : config->ints) v[i.name] = i.value;
  const obstacle_tracker::core::Params defaults;
  EXPECT_DOUBLE_EQ(v["peak_threshold"], defaults.peak_threshold) << "NaN must be refused (default kept)";
  EXPECT_DOUBLE_EQ(v["search_window_scale"], 1.0) << "-5 must be clamped to the minimum";
  EXPECT_EQ(v["max_obstacles"], 16) << "1e9 must be clamped to the maximum";
  EXPECT_DOUBLE_EQ(v["kcf_lambda"], 1.0) << "inf must be clamped to the maximum";
  EXPECT_EQ(v["detection_interval"], defaults.detection_interval) << "a string must be refused (default kept)";
  EXPECT_EQ(v["saliency_max_side"], 4096) << "1e12 must be clamped to the maximum";
  EXPECT_DOUBLE_EQ(v["merge_iou"], 0.0) << "-inf must be clamped to the minimum";
  EXPECT_TRUE(goodFrameProcessed("startup parameters"));
}

TEST(BadInput, UnsupportedEncodingsAreRefused) {
  // 32FC1 full of NaN (a depth or radiometric thermal image).
  sensor_msgs::Image f32 = rawImage(64, 48, "32FC1", 64 * 4, 64 * 48 * 4);
  for (std::size_t i = 0; i < f32.data.size(); i += 4) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&f32.data[i], &nan, 4);
  }
  sendBad("32FC1 NaN", f32, Expect::kRefused);
  sendBad("32FC3", rawImage(64, 48, "32FC3", 64 * 12, 64 * 48 * 12), Expect::kRefused);
  sendBad("64FC1", rawImage(64, 48, "64FC1", 64 * 8, 64 * 48 * 8), Expect::kRefused);
  sendBad("16SC1", rawImage(64, 48, "16SC1", 64 * 2, 64 * 48 * 2), Expect::kRefused);
  sendBad("8SC1", rawImage(64, 48, "8SC1", 64, 64 * 48), Expect::kRefused);
  sendBad("8UC2", rawImage(64, 48, "8UC2", 128, 64 * 48 * 2), Expect::kRefused);
  sendBad("misspelt", rawImage(64, 48, "mono_8", 64, 64 * 48), Expect::kRefused);
  sendBad("upper case", rawImage(64, 48, "MONO8", 64, 64 * 48), Expect::kRefused);
  sendBad("empty encoding", rawImage(64, 48, "", 64, 64 * 48), Expect::kRefused);
  sendBad("jpeg", rawImage(64, 48, "jpeg", 64, 64 * 48), Expect::kRefused);
  EXPECT_TRUE(waitLogged({"unsupported image encoding"}, 5.0)) << "no /rosout message for an unsupported encoding";
}

TEST(BadInput, DegenerateSizesAreRefusedOrProcessed) {
  sendBad("mono8 0x0", rawImage(0, 0, "mono8", 0, 0), Expect::kRefused);
  sendBad("mono8 0x48", rawImage(0, 48, "mono8", 0, 0), Expect::kRefused);
  sendBad("mono8 1x1", rawImage(1, 1, "mono8", 1, 1, 200), Expect::kProcessed);
  sendBad("mono8 2x2", rawImage(2, 2, "mono8", 2, 4, 7), Expect::kProcessed);
  sendBad("bgr8 2x2", rawImage(2, 2, "bgr8", 6, 12, 250), Expect::kProcessed);
  sendBad("mono8 4000x1", rawImage(4000, 1, "mono8", 4000, 4000, 90), Expect::kProcessed);
  sendBad("mono8 1x4000", rawImage(1, 4000, "mono8", 1, 4000, 90), Expect::kProcessed);
  sendBad("bgr8 4000x2", rawImage(4000, 2, "bgr8", 12000, 24000, 90), Expect::kProcessed);
  sendBad("bayer_rggb8 1x1", rawImage(1, 1, "bayer_rggb8", 1, 1), Expect::kEither);
  sendBad("bayer_rggb8 3x3", rawImage(3, 3, "bayer_rggb8", 3, 9), Expect::kProcessed);
  sendBad("rgba16 2x2", rawImage(2, 2, "rgba16", 16, 32), Expect::kProcessed);
  sensor_msgs::Image huge = rel::squareImage(8000, 8000, 3900, 3900, 200);
  huge.header.frame_id = "camera";
  sendBad("mono8 8000x8000", huge, Expect::kProcessed, false, 60.0);
  sendBad("mono8 70000x1 (too large)", rawImage(70000, 1, "mono8", 70000, 70000), Expect::kRefused);
}

TEST(BadInput, InconsistentStepAndDataAreRefused) {
  sendBad("data shorter than step x height", rawImage(64, 48, "mono8", 64, 64 * 48 - 1), Expect::kRefused);
  sendBad("no data at all", rawImage(64, 48, "bgr8", 192, 0), Expect::kRefused);
  sendBad("step shorter than a row", rawImage(64, 48, "bgr8", 100, 100 * 48), Expect::kRefused);
  sendBad("step 0", rawImage(64, 48, "mono8", 0, 64 * 48), Expect::kRefused);
  // 65536 x 65536 with step 65536: step x height is 2^32, 0 in 32-bit arithmetic.
  sendBad("step x height overflowing 32 bits", rawImage(65536, 65536, "mono8", 65536, 0), Expect::kRefused);
  sendBad("huge step", rawImage(64, 2, "mono8", 0xFFFFFFFFu, 256), Expect::kRefused);
  sendBad("yuv422 odd width", rawImage(3, 2, "yuv422", 6, 12), Expect::kRefused);
  // A 16-bit image whose step is not a multiple of 2 bytes: refused (or converted), never a crash.
  sendBad("mono16 odd step", rawImage(64, 48, "mono16", 129, 129 * 48), Expect::kEither);
  sendBad("data longer than step x height", rawImage(64, 48, "mono8", 64, 64 * 48 + 1000), Expect::kEither);
  EXPECT_TRUE(waitLogged({"malformed"}, 5.0)) << "no /rosout message for a malformed image";
}

TEST(BadInput, FlatAndBigEndianFramesAreProcessed) {
  sendBad("all black 640x480", rawImage(640, 480, "mono8", 640, 640 * 480, 0), Expect::kProcessed);
  sendBad("saturated 640x480", rawImage(640, 480, "mono8", 640, 640 * 480, 255), Expect::kProcessed);
  sendBad("saturated bgr8", rawImage(320, 240, "bgr8", 960, 960 * 240, 255), Expect::kProcessed);
  sensor_msgs::Image flat16 = rawImage(64, 48, "mono16", 128, 128 * 48, 0xFF);
  flat16.is_bigendian = 1;
  sendBad("flat big-endian mono16", flat16, Expect::kProcessed);
  sendBad("flat 16UC1 zero", rawImage(64, 48, "16UC1", 128, 128 * 48, 0), Expect::kProcessed);
}

TEST(BadInput, DuplicateBackwardJumpingAndZeroStamps) {
  sensor_msgs::Image img = rel::squareImage(160, 120, 60, 50, 20);
  img.header.frame_id = "camera";
  img.header.stamp = ros::Time::now();
  ctx->image_pub.publish(img);
  ASSERT_TRUE(ctx->out.waitFor(img.header.stamp, 5.0) != nullptr);
  // The same image again with the same stamp (a republished frame; roscpp gives it a new seq).
  ctx->image_pub.publish(img);
  ros::WallDuration(0.4).sleep();
  EXPECT_TRUE(goodFrameProcessed("a duplicate stamp"));
  // Time going backwards by an hour (a looping bag): tracks restart, frames go on.
  img.header.stamp = ros::Time::now() - ros::Duration(3600.0);
  sendBad("stamp an hour back", img, Expect::kProcessed, true);
  // A jump of three hours forwards.
  img.header.stamp = ros::Time::now() + ros::Duration(3 * 3600.0);
  sendBad("stamp three hours ahead", img, Expect::kProcessed, true);
  // No stamp at all: the arrival time is used.
  img.header.stamp = ros::Time(0);
  ctx->image_pub.publish(img);
  ros::WallDuration(0.4).sleep();
  EXPECT_TRUE(goodFrameProcessed("a zero stamp"));
  // Stamps near the end of ROS time.
  img.header.stamp = ros::Time(4294967295u, 999999999u);
  sendBad("stamp at the end of ROS time", img, Expect::kProcessed, true);
}

TEST(BadInput, DynamicReconfigureRefusesOrClampsBadValues) {
  ros::ServiceClient client = ctx->nh->serviceClient<dynamic_reconfigure::Reconfigure>("/tracker/set_parameters");
  ASSERT_TRUE(client.waitForExistence(ros::Duration(10.0)));
  struct Case {
    const char* name;
    double value;
    bool is_int;
    double expected;  // value in use afterwards; NaN = unchanged
  };
  const Case cases[] = {
      {"peak_threshold", kNan, false, kNan},          {"peak_threshold", kInf, false, 1.0},
      {"search_window_scale", -kInf, false, 1.0},     {"search_window_scale", -7.0, false, 1.0},
      {"kcf_lambda", 1e300, false, 1.0},              {"learning_rate", -1e-300, false, 0.0},
      {"max_obstacles", -100, true, 1},               {"max_obstacles", 2147483647.0, true, 16},
      {"saliency_max_side", -2147483648.0, true, 32}, {"max_redetect_failures", 2147483647.0, true, 10000},
      {"scale_step", kNan, false, kNan},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.name) + " = " + std::to_string(c.value));
    // The value in use before (from the latched config).
    auto before_cfg = ros::topic::waitForMessage<dynamic_reconfigure::Config>("/tracker/parameter_updates",
                                                                              *ctx->nh, ros::Duration(5.0));
    ASSERT_TRUE(before_cfg != nullptr);
    double before = kNan;
    for (const auto& d : before_cfg->doubles) if (d.name == c.name) before = d.value;
    for (const auto& i : before_cfg->ints) if (i.name == c.name) before = i.value;
    dynamic_reconfigure::Reconfigure srv;
    if (c.is_int) {
      dynamic_reconfigure::IntParameter p;
      p.name = c.name;
      p.value = static_cast<int>(c.value);
      srv.request.config.ints.push_back(p);
    } else {
      dynamic_reconfigure::DoubleParameter p;
      p.name = c.name;
      p.value = c.value;
      srv.request.config.doubles.push_back(p);
    }
    ASSERT_TRUE(client.call(srv)) << "set_parameters failed";
    double after = kNan;
    for (const auto& d : srv.response.config.doubles) if (d.name == c.name) after = d.value;
    for (const auto& i : srv.response.config.ints) if (i.name == c.name) after = i.value;
    if (std::isnan(c.expected)) {
      EXPECT_EQ(after, before) << "NaN must be refused, keeping the old value";
      EXPECT_TRUE(waitLogged({c.name, "NaN"}, 5.0)) << "no /rosout message naming " << c.name;
    } else {
      EXPECT_EQ(after, c.expected);
    }
    EXPECT_TRUE(goodFrameProcessed(std::string("dynamic_reconfigure ") + c.name));
  }
  // Back to the defaults for the tests that follow.
  const obstacle_tracker::core::Params defaults;
  dynamic_reconfigure::Reconfigure srv;
  for (const char* name : {"peak_threshold", "search_window_scale", "kcf_lambda", "learning_rate", "scale_step"}) {
    dynamic_reconfigure::DoubleParameter p;
    p.name = name;
    p.value = obstacle_tracker::core::getParam(defaults, name);
    srv.request.config.doubles.push_back(p);
  }
  for (const char* name : {"max_obstacles", "saliency_max_side", "max_redetect_failures"}) {
    dynamic_reconfigure::IntParameter p;
    p.name = name;
    p.value = static_cast<int>(obstacle_tracker::core::getParam(defaults, name));
    srv.request.config.ints.push_back(p);
  }
  EXPECT_TRUE(client.call(srv));
  EXPECT_TRUE(goodFrameProcessed("dynamic_reconfigure reset"));
}

TEST(BadGeometry, BadCameraInfoAndMissingTfLeaveBearingsOutWithoutBlocking) {
  // tracker_geo: use_camera_info true, target_frame "world" (no tf until the end of this test).
  auto goodInfo = [](const ros::Time& stamp) {
    sensor_msgs::CameraInfo info;
    info.header.stamp = stamp;
    info.header.frame_id = "camera";
    info.width = 320;
    info.height = 240;
    info.distortion_model = "plumb_bob";
    info.D = {0, 0, 0, 0, 0};
    info.K = {300, 0, 160, 0, 300, 120, 0, 0, 1};
    info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    info.P = {300, 0, 160, 0, 0, 300, 120, 0, 0, 0, 1, 0};
    return info;
  };
  // Frames of a generated scene (an aircraft crossing the sky): the tracker finds
  // it, so bearings can be checked. Played in a loop, one frame per pair.
  std::vector<sensor_msgs::Image> scene;
  {
    auto gen = obstacle_tracker::scene::makeScenario("crossing", 3, 120, cv::Size(320, 240));
    cv::Mat frame;
    for (int i = 0; i < gen.frameCount(); ++i) {
      gen.renderFrame(i, frame);
      sensor_msgs::Image img;
      img.width = 320;
      img.height = 240;
      img.encoding = "bgr8";
      img.step = 320 * 3;
      img.data.assign(frame.data, frame.data + frame.total() * frame.elemSize());
      img.header.frame_id = "camera";
      scene.push_back(img);
    }
  }
  std::size_t next_frame = 0;
  // Runs `frames` synchronised pairs; returns (outputs received, outputs with obstacles, with bearings).
  auto run = [&](const std::string& what, int frames,
                 const std::function<void(sensor_msgs::CameraInfo&)>& spoil) {
    int outputs = 0, with_obstacles = 0, with_bearing = 0;
    for (int i = 0; i < frames; ++i) {
      sensor_msgs::Image img = scene[next_frame++ % scene.size()];
      img.header.stamp = ros::Time::now();
      img.header.frame_id = "camera";
      sensor_msgs::CameraInfo info = goodInfo(img.header.stamp);
      spoil(info);
      ctx->geo_info_pub.publish(info);
      ctx->geo_image_pub.publish(img);
      auto out = ctx->geo_out.waitFor(img.header.stamp, 2.0);
      if (!out) continue;
      ++outputs;
      EXPECT_EQ(rel::checkOutput(*out), "") << what;
      if (!out->obstacles.empty()) ++with_obstacles;
      for (const auto& o : out->obstacles) with_bearing += o.has_bearing ? 1 : 0;
    }
    EXPECT_TRUE(managerAlive()) << what;
    std::printf("camera_info phase '%s': %d frames, %d outputs, %d with obstacles, %d bearings\n", what.c_str(),
                frames, outputs, with_obstacles, with_bearing);
    return std::array<int, 3>{outputs, with_obstacles, with_bearing};
  };
  const int n = 40;
  auto zeros = run("camera_info of zeros", n, [](sensor_msgs::CameraInfo& i) {
    i.K = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    i.P = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    i.D.clear();
    i.width = i.height = 0;
  });
  EXPECT_GE(zeros[0], n / 2) << "outputs stopped with a zero camera_info";
  EXPECT_EQ(zeros[2], 0) << "bearings from a zero camera_info";
  const std::size_t nan_logs = logCount();
  auto nans = run("camera_info with NaN", n, [](sensor_msgs::CameraInfo& i) {
    i.K[0] = kNan;
    i.K[4] = kNan;
    i.D[0] = kNan;
  });
  EXPECT_GE(nans[0], n / 2);
  EXPECT_EQ(nans[2], 0) << "bearings from a NaN camera_info";
  // The same bad camera_info on every frame is reported once, not at camera rate.
  EXPECT_LE(logsSince(nan_logs, "camera_info unusable"), 2) << "an unchanged NaN camera_info is re-logged every frame";
  auto bad_d = run("camera_info with 100 distortion coefficients", n / 2,
                   [](sensor_msgs::CameraInfo& i) { i.D.assign(100, 0.1); });
  EXPECT_GE(bad_d[0], n / 4);
  auto odd_model = run("unknown distortion model", n / 2, [](sensor_msgs::CameraInfo& i) {
    i.distortion_model = "no_such_model";
    i.D = {0.1, 0.2, 0.0, 0.0, 0.0};
  });
  EXPECT_GE(odd_model[0], n / 4);
  auto binning0 = run("binning and roi beyond the image", n / 2, [](sensor_msgs::CameraInfo& i) {
    i.binning_x = 0;
    i.roi.x_offset = 100000;
    i.roi.width = 5;
  });
  EXPECT_GE(binning0[0], n / 4);
  // A valid camera_info but no transform to "world": bearings left out, frames still flow.
  auto no_tf = run("missing tf", n, [](sensor_msgs::CameraInfo&) {});
  EXPECT_GE(no_tf[0], n / 2) << "a missing tf blocked the outputs";
  EXPECT_EQ(no_tf[2], 0) << "bearings without a transform to target_frame";
  EXPECT_GT(no_tf[1] + zeros[1] + nans[1], 0) << "no obstacle found at all: the checks above prove nothing";
  EXPECT_TRUE(waitLogged({"world"}, 5.0)) << "no /rosout message about the missing transform";
  // Now the transform arrives: bearings appear (the positive control of the checks above).
  tf2_ros::StaticTransformBroadcaster broadcaster;
  geometry_msgs::TransformStamped tf;
  tf.header.stamp = ros::Time(0);
  tf.header.frame_id = "world";
  tf.child_frame_id = "camera";
  tf.transform.rotation.w = 1.0;
  broadcaster.sendTransform(tf);
  ros::WallDuration(1.0).sleep();
  auto with_tf = run("with tf", n, [](sensor_msgs::CameraInfo&) {});
  EXPECT_GE(with_tf[0], n / 2);
  EXPECT_GT(with_tf[2], 0) << "no bearing even with a valid camera_info and tf";
}

TEST(BadInput, RefusalsAreCountedInDiagnostics) {
  // The diagnostics period is about a second; wait for a status that includes every refusal.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);
  double refused = -1.0;
  while (ros::WallTime::now() < end) {
    refused = diagnosticValue("tracker:", "refused frames (total)");
    if (refused >= ctx->refused_expected) break;
    ros::WallDuration(0.2).sleep();
  }
  EXPECT_GE(refused, ctx->refused_expected) << "diagnostics 'refused frames (total)' of tracker";
  EXPECT_TRUE(managerAlive());
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "reliability_bad_input");
  Context context;
  ctx = &context;
  context.nh.reset(new ros::NodeHandle);
  ros::NodeHandle& nh = *context.nh;
  context.image_pub = nh.advertise<sensor_msgs::Image>("/camera/image", 1);
  context.geo_image_pub = nh.advertise<sensor_msgs::Image>("/geo/image", 1);
  context.geo_info_pub = nh.advertise<sensor_msgs::CameraInfo>("/geo/camera_info", 1);
  context.out_sub = nh.subscribe<obstacle_tracker::ObstacleArray>(
      "/tracker/obstacles", 10, &rel::OutputCollector::callback, &context.out);
  context.geo_out_sub = nh.subscribe<obstacle_tracker::ObstacleArray>(
      "/tracker_geo/obstacles", 10, &rel::OutputCollector::callback, &context.geo_out);
  context.log_sub = nh.subscribe("/rosout", 1000, onLog);
  context.diag_sub = nh.subscribe("/diagnostics", 100, onDiagnostics);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  ctx = nullptr;
  return result;
}
