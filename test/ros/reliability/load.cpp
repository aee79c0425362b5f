// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Rostest (load.test): 1280x720 frames at 200 Hz for ~duration s (default 60) into the
// nodelet in a real manager. Checks, printed with their figures, none of them a bar on the
// machine's speed:
//   - the frames answered follow the delivery rule of frame_delivery.h (each once, in order,
//     dropped only while an earlier frame is in processing, the last one answered);
//   - frames are dropped, not queued: once the last frame is sent, at most kMaxProcessedAfterEnd
//     frames are still processed (those the fixed-size queues hold and the few in the socket),
//     counted on the nodelet's own clock (its diagnostics, stamped when published); a queue that
//     kept old frames would process the whole backlog. Answers that reach this node after the
//     end are only a figure: answers published earlier wait in the nodelet's publisher queue
//     while this node is not scheduled;
//   - the manager's resident set (VmRSS) grows by less than 5 MiB between the end of warm-up and
//     the end (medians of 5 s of samples at 10 Hz);
//   - the manager is alive at the end, frames were answered in the last window, the diagnostics'
//     dropped-frame count is the number of frames sent and never processed, and every frame
//     processed had exactly one answer published: the answers received and those lost on the way
//     (gaps in roscpp's header.seq, see frame_delivery.h), whatever this node's scheduling.
//     Latency and the answers lost on the way are printed as figures.
// Parameters (private): duration (s), rate (Hz), width, height, encoding (mono8 | bgr8),
// warmup (s, default min(10, duration / 4)).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <condition_variable>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "../frame_delivery.h"
#include "obstacle_tracker/ros/frame_slot.h"
#include "reliability_common.h"

namespace rel = obstacle_tracker::reliability;
namespace rt = obstacle_tracker::ros_test;

namespace {

// Our publisher's queue: deep enough that the sending side hardly ever drops (a frame it dropped
// would look like one the tracker dropped while idle); the nodelet's own queueing is under test.
constexpr int kPublisherQueue = 16;
// Frames that can still be processed after the last one was sent without any backlog in the
// nodelet: everything that the path's fixed-size queues hold (our publisher's, the nodelet's
// subscription queue and the FrameSlot's idle backlog, kIdleBacklog each, the frame in
// processing) and a few 2.7 MB frames in the loopback socket. A nodelet that queued instead of
// dropping would process the whole backlog: hundreds of frames after a minute at 200 Hz.
constexpr int kQueueDepth = static_cast<int>(obstacle_tracker::bridge::FrameSlot<int>::kIdleBacklog);
constexpr int kNodeletHeldFrames = kQueueDepth + kQueueDepth + 1;  // subscription, FrameSlot, processing
constexpr int kMaxProcessedAfterEnd = kPublisherQueue + kNodeletHeldFrames + 3;

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
  std::condition_variable answered;
  ros::WallTime start;
  std::atomic<bool> started{false};
  std::vector<Sample> latency;  // s
  std::map<ros::Time, std::size_t> index;  // stamp -> frame
  std::vector<rt::FrameRecord> frames;
  int unknown = 0;
  double dropped_total = -1.0;
  double processed_total = -1.0;
  bool handshake_answered = false;
  long handshake_seq = -1;  // header.seq of the handshake's answer
  long last_seq = -1;       // header.seq of the latest answer
  long received = 0;        // answers received after the handshake's (any stamp, doubled too)
  ros::Time last_stamp;     // of the last frame sent
  std::vector<std::pair<ros::Time, double>> processed_at;  // diagnostics: stamp, frames processed
};
State* state = nullptr;

void onOutput(const obstacle_tracker::ObstacleArray::ConstPtr& msg) {
  if (!state->started) {  // the answer to the handshake frame
    std::lock_guard<std::mutex> lock(state->mutex);
    state->handshake_answered = true;
    state->handshake_seq = msg->header.seq;
    state->answered.notify_all();
    return;
  }
  const double latency = (ros::Time::now() - msg->header.stamp).toSec();
  const double now = (ros::WallTime::now() - state->start).toSec();
  std::lock_guard<std::mutex> lock(state->mutex);
  state->latency.push_back({now, latency});
  state->last_seq = msg->header.seq;
  ++state->received;
  auto it = state->index.find(msg->header.stamp);
  if (it == state->index.end()) {
    ++state->unknown;
  } else if (state->frames[it->second].answers++ == 0) {
    state->frames[it->second].answered = now;
    state->frames[it->second].seq = msg->header.seq;
  }
  state->answered.notify_all();
}

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(state->mutex);
  for (const auto& status : msg->status) {
    if (status.name.rfind("tracker:", 0) != 0) continue;
    for (const auto& kv : status.values) {
      if (kv.key == "dropped frames (total)") state->dropped_total = std::atof(kv.value.c_str());
      if (kv.key == "frames processed (total)") {
        state->processed_total = std::atof(kv.value.c_str());
        state->processed_at.emplace_back(msg->header.stamp, state->processed_total);
      }
    }
  }
  state->answered.notify_all();
}

struct LoadSettings {
  double duration = 60.0;  // s
  double rate = 200.0;     // Hz
  int width = 1280, height = 720;
  std::string encoding = "mono8";
  double warmup = 0.0;  // s
  double window = 0.0;  // s: the latency comparison windows
};

LoadSettings readSettings(const ros::NodeHandle& pnh) {
  LoadSettings s;
  pnh.param("duration", s.duration, s.duration);
  pnh.param("rate", s.rate, s.rate);
  pnh.param("width", s.width, s.width);
  pnh.param("height", s.height, s.height);
  pnh.param("encoding", s.encoding, s.encoding);
  s.warmup = std::min(10.0, s.duration / 4.0);
  pnh.param("warmup", s.warmup, s.warmup);
  s.window = std::min(10.0, (s.duration - s.warmup) / 2.0);
  return s;
}

// A textured background, drawn once.
sensor_msgs::Image texturedFrame(const LoadSettings& s) {
  sensor_msgs::Image img = rel::squareImage(s.width, s.height, 0, 0, 0, s.encoding);
  img.header.frame_id = "camera";
  for (std::size_t i = 0; i < img.data.size(); ++i) {
    img.data[i] = static_cast<std::uint8_t>(img.data[i] + ((i * 2654435761u) >> 28));
  }
  return img;
}

// The background with a bright square that moves and grows slowly, at t s of `duration`.
void drawFrame(const LoadSettings& s, const std::vector<std::uint8_t>& background, double t, sensor_msgs::Image& img) {
  const int channels = s.encoding == "bgr8" ? 3 : 1;
  const int side = 40 + static_cast<int>(20 * t / s.duration);
  const int x = static_cast<int>(s.width / 2 + s.width / 4 * std::sin(t * 0.7)) - side / 2;
  const int y = static_cast<int>(s.height / 2 + s.height / 6 * std::cos(t * 0.5)) - side / 2;
  std::copy(background.begin(), background.end(), img.data.begin());
  for (int r = std::max(0, y); r < std::min(s.height, y + side); ++r) {
    std::fill(img.data.begin() + static_cast<long>(r) * img.step + std::max(0, x) * channels,
              img.data.begin() + static_cast<long>(r) * img.step + std::min(s.width, x + side) * channels, 230);
  }
}

// One frame, answered, before the load. The nodelet counts frames lost before its callback from
// gaps in the sequence numbers, which needs a frame it received before them: a loaded machine that
// did not run its callback thread while the first frames arrived would otherwise lose them
// uncounted. This frame is not one of the recorded ones.
bool handshake(const ros::Publisher& pub, sensor_msgs::Image& img) {
  img.header.stamp = ros::Time::now();
  pub.publish(img);
  std::unique_lock<std::mutex> lock(state->mutex);
  state->answered.wait_for(lock, std::chrono::seconds(60), [] { return state->handshake_answered; });
  return state->handshake_answered;
}

struct LoadRun {
  long published = 0;
  double elapsed = 0.0;      // s
  std::vector<Sample> rss;   // MiB of the manager, every 0.1 s
  bool alive = false;        // the manager at the end
};

// Publishes frames at s.rate for s.duration, recording each frame sent and the manager's RSS;
// then waits for the last frame's answer (a hang guard, not a speed bar) and the last diagnostics.
LoadRun publishLoad(const LoadSettings& s, const ros::Publisher& pub, int pid, sensor_msgs::Image& img) {
  const std::vector<std::uint8_t> background = img.data;
  LoadRun run;
  state->start = ros::WallTime::now();
  state->started = true;
  ros::WallRate loop(s.rate);
  double next_rss = 0.0;
  double t = 0.0;
  while ((t = (ros::WallTime::now() - state->start).toSec()) < s.duration && ros::ok()) {
    drawFrame(s, background, t, img);
    img.header.stamp = ros::Time::now();
    {
      std::lock_guard<std::mutex> lock(state->mutex);
      state->index[img.header.stamp] = state->frames.size();
      rt::FrameRecord record;
      record.sent = (ros::WallTime::now() - state->start).toSec();
      state->frames.push_back(record);
      state->last_stamp = img.header.stamp;
    }
    pub.publish(img);
    ++run.published;
    if (t >= next_rss) {
      run.rss.push_back({t, rel::residentKiB(pid) / 1024.0});
      next_rss += 0.1;
    }
    loop.sleep();
  }
  run.elapsed = (ros::WallTime::now() - state->start).toSec();
  run.alive = rel::processAlive(pid);
  {
    std::unique_lock<std::mutex> lock(state->mutex);
    state->answered.wait_for(lock, std::chrono::seconds(60), [] { return state->frames.back().answers > 0; });
  }
  ros::WallDuration(2.5).sleep();  // any doubled answer
  {
    // Diagnostics that count every answer published so far (the handshake's and those after it): a
    // loaded machine may delay them past the sleep. A hang guard, not a speed bar.
    std::unique_lock<std::mutex> lock(state->mutex);
    state->answered.wait_for(lock, std::chrono::seconds(60), [] {
      return state->processed_total >= static_cast<double>(state->last_seq - state->handshake_seq + 1);
    });
  }
  state->started = false;
  return run;
}

// Figures of a run, from the recorded frames and answers (state's mutex held).
struct LoadFigures {
  rt::DeliveryReport delivery;
  int answered_after_end = 0;  // earlier frames whose answer arrived after the last one was sent
  double processed_after_end = NAN;  // frames the nodelet processed after the last one was sent
  long lost_in_transport = 0;  // answers published after the handshake's and never received
  double latency_first = 0.0, latency_last = 0.0;  // s, medians of the first and last windows
  double rss_warm = 0.0, rss_end = 0.0, rss_max = 0.0;  // MiB
};

LoadFigures figuresOf(const LoadSettings& s, const LoadRun& run) {
  LoadFigures f;
  // A frame dropped without an earlier one in processing was pushed out of the subscription queue
  // or the FrameSlot's idle backlog, each kQueueDepth deep.
  f.delivery = rt::checkDelivery(state->frames, kQueueDepth, state->handshake_seq);
  const double last_sent = state->frames.back().sent;
  for (std::size_t i = 0; i + 1 < state->frames.size(); ++i) {
    if (state->frames[i].answers > 0 && state->frames[i].answered > last_sent) ++f.answered_after_end;
  }
  // The first count the nodelet published after the last frame was sent (same clock: both are
  // ros::Time::now() on this machine): frames processed since are at most those after the end
  // (a late diagnostics timer only makes this count smaller, never blames a correct nodelet).
  for (const auto& p : state->processed_at) {
    if (p.first >= state->last_stamp) {
      f.processed_after_end = state->processed_total - p.second;
      break;
    }
  }
  f.lost_in_transport = state->last_seq - state->handshake_seq - state->received;
  f.latency_first = median(window(state->latency, s.warmup, s.warmup + s.window));
  f.latency_last = median(window(state->latency, run.elapsed - s.window, run.elapsed + 1.0));
  f.rss_warm = median(window(run.rss, s.warmup, s.warmup + 5.0));
  f.rss_end = median(window(run.rss, run.elapsed - 5.0, run.elapsed + 1.0));
  for (const Sample& r : run.rss) f.rss_max = std::max(f.rss_max, r.value);
  return f;
}

void printFigures(const LoadSettings& s, const LoadRun& run, const LoadFigures& f) {
  const rt::DeliveryReport& d = f.delivery;
  std::printf("load: %dx%d %s, %.0f Hz asked, %ld frames in %.1f s (%.1f Hz published)\n", s.width, s.height,
              s.encoding.c_str(), s.rate, run.published, run.elapsed, run.published / run.elapsed);
  std::printf("load: %zu outputs (%.1f Hz); diagnostics: %.0f processed, %.0f dropped\n", state->latency.size(),
              state->latency.size() / run.elapsed, state->processed_total, state->dropped_total);
  std::printf("load: %d sent, %d answered, %d dropped (%d while idle, %d pushed out of a full backlog), "
              "%d doubled, %d out of order, %d unknown stamps\n",
              d.sent, d.answered, d.dropped, d.dropped_while_idle, d.dropped_by_backlog, d.doubled, d.out_of_order,
              state->unknown);
  std::printf("load: after the last frame was sent, %.0f frames processed (nodelet's clock), %d earlier answers "
              "received here\n",
              f.processed_after_end, f.answered_after_end);
  std::printf("load: %ld answers published and lost on the way to this node (header.seq); %d unanswered frames "
              "not judged, lost answers between their neighbours\n",
              f.lost_in_transport, d.dropped_answer_lost);
  std::printf("load: latency median %.1f ms in [%.0f, %.0f) s, %.1f ms in the last %.0f s\n", 1e3 * f.latency_first,
              s.warmup, s.warmup + s.window, 1e3 * f.latency_last, s.window);
  std::printf("load: manager VmRSS %.1f MiB after warm-up, %.1f MiB at the end (max %.1f MiB)\n", f.rss_warm,
              f.rss_end, f.rss_max);
  std::fflush(stdout);
}

}  // namespace

TEST(Load, NewestFrameBoundedMemoryDropsCounted) {
  ros::NodeHandle nh, pnh("~");
  const LoadSettings settings = readSettings(pnh);
  ASSERT_GT(settings.window, 1.0) << "duration too short";

  ros::Publisher pub = nh.advertise<sensor_msgs::Image>("/load/image", kPublisherQueue);
  // Deep: on a loaded machine this node's own callback thread falls behind, and an answer lost
  // here would count as a frame the tracker dropped.
  ros::Subscriber out_sub = nh.subscribe("/tracker/obstacles", 10000, onOutput);
  ros::Subscriber diag_sub = nh.subscribe("/diagnostics", 10, onDiagnostics);
  const ros::WallTime wait_end = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::WallTime::now() < wait_end && (pub.getNumSubscribers() == 0 || out_sub.getNumPublishers() == 0)) {
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_GT(pub.getNumSubscribers(), 0u);
  const int pid = rel::nodePid("/manager");
  ASSERT_GT(pid, 0) << "cannot get the manager's pid";

  sensor_msgs::Image img = texturedFrame(settings);
  ASSERT_TRUE(handshake(pub, img)) << "the handshake frame was not answered within 60 s";
  const LoadRun run = publishLoad(settings, pub, pid, img);

  std::lock_guard<std::mutex> lock(state->mutex);
  const LoadFigures f = figuresOf(settings, run);
  printFigures(settings, run, f);
  const rt::DeliveryReport& delivery = f.delivery;
  EXPECT_TRUE(run.alive) << "the nodelet manager died under load";
  ASSERT_FALSE(std::isnan(f.latency_first)) << "no output in the first window";
  ASSERT_FALSE(std::isnan(f.latency_last)) << "no output in the last window: the tracker stopped";
  EXPECT_EQ(state->unknown, 0) << "ObstacleArrays whose stamp was never sent";
  EXPECT_EQ(delivery.doubled, 0) << "frames answered more than once";
  EXPECT_EQ(delivery.out_of_order, 0) << "answers out of the order of the frames";
  EXPECT_EQ(delivery.dropped_while_idle, 0)
      << "frames dropped with no earlier frame in processing (first 20):" << delivery.idle_drops;
  EXPECT_TRUE(delivery.last_answered) << "the last frame sent was not answered";
  ASSERT_FALSE(std::isnan(f.processed_after_end)) << "no diagnostics published after the last frame was sent";
  EXPECT_LE(f.processed_after_end, kMaxProcessedAfterEnd) << "frames are queued instead of dropped";
  // The nodelet's fixed queues may fill up for the first time after warm-up (a stalled thread on a
  // loaded machine) and the allocator keeps that memory: growth beyond 5 MiB plus what they hold
  // is unbounded growth.
  const double held_mib = kNodeletHeldFrames * static_cast<double>(img.data.size()) / (1024.0 * 1024.0);
  EXPECT_LT(f.rss_end - f.rss_warm, 5.0 + held_mib)
      << "resident set grew by " << f.rss_end - f.rss_warm << " MiB (the queues hold " << held_mib << " MiB)";
  // Whatever this machine's speed, the diagnostics count exactly the frames that were never
  // processed: the frames sent (and the handshake frame) less those the diagnostics processed.
  const double never_processed = static_cast<double>(delivery.sent) + 1.0 - state->processed_total;
  EXPECT_EQ(state->dropped_total, never_processed)
      << "diagnostics' dropped frames against the frames sent and never processed";
  // Every frame processed after the handshake had exactly one answer published: roscpp numbers
  // each one (header.seq), received here or lost on the way when this node or the manager's
  // network thread was not scheduled for longer than the nodelet's publisher queue lasts. The
  // losses are the machine's scheduling, not the nodelet's doing: a figure, not a bar.
  EXPECT_EQ(state->processed_total - 1.0, static_cast<double>(state->last_seq - state->handshake_seq))
      << "frames processed against answers published (received " << state->received << ", lost on the way "
      << f.lost_in_transport << ")";
  EXPECT_GE(f.lost_in_transport, 0) << "more answers received than published";
  if (delivery.dropped == 0) {
    std::printf("load: the tracker kept up with %.0f Hz: nothing was dropped, the drop rule was not exercised\n",
                settings.rate);
  }
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
