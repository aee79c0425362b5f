// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// scene_publisher: a camera stand-in for the demo and for trying the tracker without hardware.
// Publishes `image` (sensor_msgs/Image) and `camera_info` with the same header, at ~rate Hz:
//   - a generated flight scene (src/scene, rendered in-process): ~scenario (default "demo"),
//     ~seed, ~frames (0: the scenario's length), ~width x ~height, ~mono16 (thermal-like mono16
//     frames instead of bgr8); camera_info from the scene's focal length;
//   - or, when ~folder is set, that sequence read as evaluate reads it (eval::Sequence: an OTB
//     folder FOLDER/img/*.jpg, a folder of images, a folder holding one video, or a video file;
//     16-bit PNGs go out as mono16), camera_info from ~hfov (deg).
// ~rate (Hz, 0: the scene's fps, or the sequence's: its video's or scene file's, else 30), ~loop
// (start again at the end; stamps keep increasing), ~frame_id (camera_optical). Exits after the
// last frame unless ~loop.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <cv_bridge/cv_bridge.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/image_encodings.h>

#include "obstacle_tracker/eval/sequence.h"
#include "obstacle_tracker/ros/camera_geometry.h"
#include "obstacle_tracker/scene/scene_generator.h"

namespace {

// The node's private parameters (the file comment above says what each does).
struct PublisherParams {
  std::string folder, scenario, frame_id;
  int seed = 1, frames = 0, width = 640, height = 480;
  bool mono16 = false, loop = false;
  double rate = 0.0, hfov = 60.0;
};

PublisherParams readParams(const ros::NodeHandle& pnh) {
  PublisherParams p;
  pnh.param("folder", p.folder, std::string());
  pnh.param("scenario", p.scenario, std::string("demo"));
  pnh.param("seed", p.seed, p.seed);
  pnh.param("frames", p.frames, p.frames);
  pnh.param("width", p.width, p.width);
  pnh.param("height", p.height, p.height);
  pnh.param("mono16", p.mono16, p.mono16);
  pnh.param("rate", p.rate, p.rate);
  pnh.param("loop", p.loop, p.loop);
  pnh.param("hfov", p.hfov, p.hfov);
  pnh.param("frame_id", p.frame_id, std::string("camera_optical"));
  return p;
}

// Where the frames come from: a generated scene, or else a sequence on disk.
struct FrameSource {
  std::unique_ptr<obstacle_tracker::scene::SceneGenerator> scene;
  std::unique_ptr<obstacle_tracker::eval::Sequence> sequence;
  int count = 0;
  double focal = 0.0;  // the scene's; 0 for a sequence (camera_info then from ~hfov)
};

// Opens the folder or the scene of *p and settles p->rate when it is 0. False (after ROS_FATAL)
// when there is nothing to publish.
bool openSource(PublisherParams* p, FrameSource* source) {
  try {
    if (!p->folder.empty()) {
      source->sequence.reset(new obstacle_tracker::eval::Sequence(p->folder));
      source->count = source->sequence->frameCount();
      if (source->count <= 0) {
        ROS_FATAL("%s does not tell its frame count", p->folder.c_str());
        return false;
      }
      if (p->rate <= 0.0) p->rate = source->sequence->fps();
      ROS_INFO("publishing %d frames of %s at %.1f Hz", source->count, p->folder.c_str(), p->rate);
    } else {
      obstacle_tracker::scene::ScenarioConfig config;
      config.name = p->scenario;
      config.seed = static_cast<std::uint64_t>(std::max(0, p->seed));
      config.frames = p->frames;
      config.size = cv::Size(p->width, p->height);
      config.mono16 = p->mono16;
      source->scene.reset(new obstacle_tracker::scene::SceneGenerator(config));
      source->count = source->scene->frameCount();
      source->focal = source->scene->info().focal_length_px;
      if (p->rate <= 0.0) p->rate = source->scene->fps();
      ROS_INFO("publishing scenario '%s' (seed %d, %d frames, %dx%d%s) at %.1f Hz", p->scenario.c_str(), p->seed,
               source->count, p->width, p->height, p->mono16 ? ", mono16" : "", p->rate);
    }
  } catch (const std::exception& e) {
    ROS_FATAL("scene_publisher: %s", e.what());
    return false;
  }
  return true;
}

// Frame i of the source into *frame; false (warned, throttled) when it is to be skipped.
bool readFrame(FrameSource& source, int i, cv::Mat* frame) {
  try {
    if (source.scene) {
      source.scene->renderFrame(i, *frame);
    } else {
      // Seek only off the sequential path: after a frame that could not be decoded (read() throws
      // without moving on) and when looping back to the start.
      if (source.sequence->position() != i) source.sequence->seek(i);
      if (!source.sequence->read(*frame)) {
        ROS_WARN_THROTTLE(5.0, "%s ends before frame %d: skipped", source.sequence->path().c_str(), i);
        return false;
      }
    }
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(5.0, "frame %d: %s", i, e.what());
    return false;
  }
  return true;
}

// The sensor_msgs encoding of the frame; empty (warned, throttled) for a type not published.
std::string encodingOf(const cv::Mat& frame, int i) {
  switch (frame.type()) {
    case CV_8UC1: return sensor_msgs::image_encodings::MONO8;
    case CV_16UC1: return sensor_msgs::image_encodings::MONO16;
    case CV_8UC3: return sensor_msgs::image_encodings::BGR8;
    case CV_8UC4: return sensor_msgs::image_encodings::BGRA8;
    default:
      ROS_WARN_THROTTLE(5.0, "frame %d has an image type the demo does not publish: skipped", i);
      return std::string();
  }
}

// `image` and `camera_info` with the same header.
class FramePublisher {
 public:
  FramePublisher(ros::NodeHandle& nh, const std::string& frame_id)
      : image_pub_(nh.advertise<sensor_msgs::Image>("image", 2)),
        info_pub_(nh.advertise<sensor_msgs::CameraInfo>("camera_info", 2)),
        frame_id_(frame_id) {}

  // focal in pixels: the scene's, or when 0 the one of hfov (degrees) across the frame's width.
  void publish(const cv::Mat& frame, const std::string& encoding, double focal, double hfov) {
    std_msgs::Header header;
    header.stamp = ros::Time::now();
    header.frame_id = frame_id_;
    header.seq = seq_++;
    sensor_msgs::ImagePtr image = cv_bridge::CvImage(header, encoding, frame).toImageMsg();
    const double f = focal > 0.0 ? focal : 0.5 * frame.cols / std::tan(0.5 * hfov * M_PI / 180.0);
    sensor_msgs::CameraInfo info = obstacle_tracker::bridge::pinholeCameraInfo(frame.cols, frame.rows, f);
    info.header = header;
    info_pub_.publish(info);
    image_pub_.publish(image);
  }

 private:
  ros::Publisher image_pub_, info_pub_;
  std::string frame_id_;
  std::uint32_t seq_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "scene_publisher");
  ros::NodeHandle nh, pnh("~");
  PublisherParams params = readParams(pnh);
  FrameSource source;
  if (!openSource(&params, &source)) return 1;

  FramePublisher publisher(nh, params.frame_id);
  ros::Rate loop_rate(params.rate);
  cv::Mat frame;
  for (int i = 0; ros::ok(); ++i) {
    if (i == source.count) {
      if (!params.loop) break;
      i = 0;
    }
    if (!readFrame(source, i, &frame)) continue;
    const std::string encoding = encodingOf(frame, i);
    if (encoding.empty()) continue;
    publisher.publish(frame, encoding, source.focal, params.hfov);
    ros::spinOnce();
    loop_rate.sleep();
  }
  return 0;
}
