// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Hands camera frames from the subscription callbacks to the nodelet's processing thread with the
// drop rule a planner needs: a frame is dropped only while an earlier frame is being processed,
// and then only for a newer one (the tracker always works on the newest image). A subscription
// queue of size 1 does not keep that rule: two frames that arrive together (a transport burst, a
// callback thread woken late on a loaded machine) drop the first one although the tracker is
// idle. Here frames that arrive while nothing is processed are kept (up to kIdleBacklog) and
// processed in order; frames that arrive during processing replace whatever waits.
// ROS-free and header-only so that its GoogleTest needs no ROS master.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <utility>

namespace obstacle_tracker {
namespace bridge {

template <typename Frame>
class FrameSlot {
 public:
  // Frames kept while the processing thread is idle but not yet awake: a burst, or 20 ms of a
  // 200 Hz camera while a loaded machine has not yet scheduled the thread; few enough that a
  // stalled thread cannot pile up old frames (each a full image in memory).
  static constexpr std::size_t kIdleBacklog = 4;

  // Called by the subscription callbacks (any thread). Never blocks on processing.
  void offer(Frame frame) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stopped_) return;
      if (busy_) {
        dropped_ += waiting_.size();
        waiting_.clear();
      } else if (waiting_.size() >= kIdleBacklog) {
        waiting_.pop_front();
        ++dropped_;
      }
      waiting_.push_back(std::move(frame));
    }
    ready_.notify_one();
  }

  // Called by the processing thread: waits for a frame and marks the slot busy until done().
  // Returns false once stop() was called.
  bool take(Frame* frame) {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [this] { return stopped_ || !waiting_.empty(); });
    if (stopped_) return false;
    *frame = std::move(waiting_.front());
    waiting_.pop_front();
    busy_ = true;
    return true;
  }

  // The frame from take() is processed; frames that arrive from now on are kept again. Calling
  // it again before the next take() changes nothing.
  void done() {
    std::lock_guard<std::mutex> lock(mutex_);
    busy_ = false;
  }

  // Wakes take() for good; later offers are ignored.
  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopped_ = true;
      waiting_.clear();
    }
    ready_.notify_all();
  }

  // Frames replaced before they were processed, since construction.
  std::uint64_t dropped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Frame> waiting_;
  bool busy_ = false;
  bool stopped_ = false;
  std::uint64_t dropped_ = 0;
};

}  // namespace bridge
}  // namespace obstacle_tracker
