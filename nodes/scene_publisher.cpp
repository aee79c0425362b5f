// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// scene_publisher: a camera stand-in for the demo and for trying the tracker without hardware.
// Publishes `image` (sensor_msgs/Image) and `camera_info` with the same header, at ~rate Hz:
//   - a generated flight scene (src/scene, rendered in-process): ~scenario (default "demo"),
//     ~seed, ~frames (0: the scenario's length), ~width x ~height, ~mono16 (thermal-like mono16
//     frames instead of bgr8); camera_info from the scene's focal length;
//   - or, when ~folder is set, the images of a folder (OTB layout FOLDER/img/*.jpg, or
//     FOLDER/*.{jpg,png,...}; 16-bit PNGs go out as mono16), camera_info from ~hfov (deg).
// ~rate (Hz, 0: the scene's fps / 30 for a folder), ~loop (start again at the end; stamps keep
// increasing), ~frame_id (camera_optical). Exits after the last frame unless ~loop.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/core/utils/filesystem.hpp>
#include <opencv2/imgcodecs.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/image_encodings.h>

#include "obstacle_tracker/scene/scene_generator.h"

namespace {

std::vector<std::string> listImages(const std::string& folder) {
  std::vector<std::string> files;
  const std::string dir = cv::utils::fs::isDirectory(folder + "/img") ? folder + "/img" : folder;
  for (const char* pattern : {"*.jpg", "*.jpeg", "*.png", "*.bmp", "*.pgm", "*.ppm", "*.tif", "*.tiff"}) {
    std::vector<cv::String> found;
    cv::glob(dir + "/" + pattern, found, false);
    files.insert(files.end(), found.begin(), found.end());
  }
  std::sort(files.begin(), files.end());
  return files;
}

sensor_msgs::CameraInfo pinhole(int width, int height, double focal) {
  sensor_msgs::CameraInfo info;
  info.width = width;
  info.height = height;
  const double cx = 0.5 * width - 0.5, cy = 0.5 * height - 0.5;
  info.distortion_model = "plumb_bob";
  info.D = {0.0, 0.0, 0.0, 0.0, 0.0};
  info.K = {focal, 0.0, cx, 0.0, focal, cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {focal, 0.0, cx, 0.0, 0.0, focal, cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "scene_publisher");
  ros::NodeHandle nh, pnh("~");
  std::string folder, scenario, frame_id;
  int seed = 1, frames = 0, width = 640, height = 480;
  bool mono16 = false, loop = false;
  double rate = 0.0, hfov = 60.0;
  pnh.param("folder", folder, std::string());
  pnh.param("scenario", scenario, std::string("demo"));
  pnh.param("seed", seed, seed);
  pnh.param("frames", frames, frames);
  pnh.param("width", width, width);
  pnh.param("height", height, height);
  pnh.param("mono16", mono16, mono16);
  pnh.param("rate", rate, rate);
  pnh.param("loop", loop, loop);
  pnh.param("hfov", hfov, hfov);
  pnh.param("frame_id", frame_id, std::string("camera_optical"));

  std::unique_ptr<obstacle_tracker::scene::SceneGenerator> scene;
  std::vector<std::string> files;
  int count = 0;
  double focal = 0.0;
  try {
    if (!folder.empty()) {
      files = listImages(folder);
      if (files.empty()) {
        ROS_FATAL("no images in %s (nor in %s/img)", folder.c_str(), folder.c_str());
        return 1;
      }
      count = static_cast<int>(files.size());
      if (rate <= 0.0) rate = 30.0;
      ROS_INFO("publishing %d images of %s at %.1f Hz", count, folder.c_str(), rate);
    } else {
      obstacle_tracker::scene::ScenarioConfig config;
      config.name = scenario;
      config.seed = static_cast<std::uint64_t>(std::max(0, seed));
      config.frames = frames;
      config.size = cv::Size(width, height);
      config.mono16 = mono16;
      scene.reset(new obstacle_tracker::scene::SceneGenerator(config));
      count = scene->frameCount();
      focal = scene->info().focal_length_px;
      if (rate <= 0.0) rate = scene->fps();
      ROS_INFO("publishing scenario '%s' (seed %d, %d frames, %dx%d%s) at %.1f Hz", scenario.c_str(), seed,
               count, width, height, mono16 ? ", mono16" : "", rate);
    }
  } catch (const std::exception& e) {
    ROS_FATAL("scene_publisher: %s", e.what());
    return 1;
  }

  ros::Publisher image_pub = nh.advertise<sensor_msgs::Image>("image", 2);
  ros::Publisher info_pub = nh.advertise<sensor_msgs::CameraInfo>("camera_info", 2);
  ros::Rate loop_rate(rate);
  cv::Mat frame;
  std::uint32_t seq = 0;
  for (int i = 0; ros::ok(); ++i) {
    if (i == count) {
      if (!loop) break;
      i = 0;
    }
    try {
      if (scene) {
        scene->renderFrame(i, frame);
      } else {
        frame = cv::imread(files[i], cv::IMREAD_UNCHANGED);
        if (frame.empty()) {
          ROS_WARN_THROTTLE(5.0, "cannot read %s: skipped", files[i].c_str());
          continue;
        }
      }
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "frame %d: %s", i, e.what());
      continue;
    }
    std::string encoding;
    switch (frame.type()) {
      case CV_8UC1: encoding = sensor_msgs::image_encodings::MONO8; break;
      case CV_16UC1: encoding = sensor_msgs::image_encodings::MONO16; break;
      case CV_8UC3: encoding = sensor_msgs::image_encodings::BGR8; break;
      case CV_8UC4: encoding = sensor_msgs::image_encodings::BGRA8; break;
      default:
        ROS_WARN_THROTTLE(5.0, "frame %d has an image type the demo does not publish: skipped", i);
        continue;
    }
    std_msgs::Header header;
    header.stamp = ros::Time::now();
    header.frame_id = frame_id;
    header.seq = seq++;
    sensor_msgs::ImagePtr image = cv_bridge::CvImage(header, encoding, frame).toImageMsg();
    const double f = focal > 0.0 ? focal : 0.5 * frame.cols / std::tan(0.5 * hfov * M_PI / 180.0);
    sensor_msgs::CameraInfo info = pinhole(frame.cols, frame.rows, f);
    info.header = header;
    info_pub.publish(info);
    image_pub.publish(image);
    ros::spinOnce();
    loop_rate.sleep();
  }
  return 0;
}
