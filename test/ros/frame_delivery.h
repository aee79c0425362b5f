// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// What the nodelet promises about which frames it answers, checked from the sending side without
// any bar on the machine's speed (used by the accuracy and load rostests):
//   - every answer carries the stamp of a frame that was sent, and no frame is answered twice;
//   - frames are answered in the order they were sent;
//   - a frame is left unanswered only while the tracker was busy with an earlier frame: the
//     FrameSlot replaces a waiting frame only when a newer one arrives while an earlier frame is
//     being processed, so that earlier frame's answer was published after this frame was sent. Sent-before-received and published-before-received make the test causal: with
//     s_i the time frame i was published and o_j the time the answer to j reached the test (one
//     clock, one process), a dropped frame i needs an answered j < i with o_j > s_i;
//   - or, on a machine that did not schedule the nodelet's threads for a while, the frame was
//     pushed out of a full queue: each of the nodelet's queues (the image and camera_info
//     subscriptions, the FrameSlot's idle backlog) holds `backlog` frames, so at least that many
//     newer frames were sent before the next answer;
//   - the newest frame is never dropped: the last frame sent (nothing came after it to replace
//     it) is answered.
// An answer can also be lost after the nodelet published it: roscpp's publisher queue drops its
// oldest answer when the receiving test is not scheduled for longer than the queue lasts. roscpp
// numbers every message it publishes on a topic (it writes header.seq), so a gap between the
// numbers of two answers received says that answers were published and lost between them. A lost
// answer hides which frame it answered and when that frame was processed, and that time is what
// excuses the frames replaced meanwhile; so no unanswered frame between two such answers is
// counted as an idle drop: a correct nodelet is never blamed for the receiving side's scheduling.
// The number of answers published is still checked exactly against the frames processed
// (load.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace obstacle_tracker {
namespace ros_test {

struct FrameRecord {
  double sent = NAN;     // when the test published the frame (steady clock, s); NaN: not sent
  double answered = NAN; // when its ObstacleArray reached the test (first one); NaN: no answer
  int answers = 0;       // ObstacleArrays received with this frame's stamp
  long seq = -1;         // header.seq of its first answer as roscpp numbered it; -1: not known
};

struct DeliveryReport {
  int sent = 0;
  int answered = 0;
  int doubled = 0;              // frames answered more than once
  int dropped = 0;              // sent frames with no answer
  int dropped_while_idle = 0;   // of those, frames no earlier answer was pending for, no full
                                // backlog pushed out and no lost answer accounts for
  int dropped_by_backlog = 0;   // frames pushed out of a full backlog while the tracker waited
  int out_of_order = 0;         // answers that arrived before the answer of an earlier frame
  int lost_in_transport = 0;    // answers published (gaps in header.seq) that never arrived
  int dropped_answer_lost = 0;  // idle-looking drops between two answers with lost ones between
  bool last_answered = false;   // the last frame sent has an answer
  std::string idle_drops;       // indices of the first dropped-while-idle frames

  // The promise, as one boolean (the fields above say which part failed).
  bool kept() const {
    return doubled == 0 && dropped_while_idle == 0 && out_of_order == 0 && last_answered;
  }
};

// Unanswered frames that no pending answer or full backlog excuses, since the last answer; `gap`
// answers were published in that interval and lost on the way. Where gap > 0, none of them is an
// idle drop: the lost answers' arrival times, which would have excused them, are unknown.
inline void settleIdleDrops(std::vector<std::size_t>& idle, long gap, DeliveryReport& r) {
  if (gap > 0) {
    r.dropped_answer_lost += static_cast<int>(idle.size());
  } else {
    for (const std::size_t i : idle) {
      if (++r.dropped_while_idle <= 20) r.idle_drops += " " + std::to_string(i);
    }
  }
  idle.clear();
}

// backlog: depth of each of the nodelet's queues (0: none, every idle drop is a violation).
// seq_before: header.seq of the answer received just before frames[0] (-1: not known).
inline DeliveryReport checkDelivery(const std::vector<FrameRecord>& frames, int backlog = 0, long seq_before = -1) {
  DeliveryReport r;
  double latest_answer = -INFINITY;  // max o_j over the answered frames before the current one
  long latest_seq = seq_before;      // header.seq of the last answered frame before the current one
  std::vector<std::size_t> idle;     // idle-drop candidates since that frame
  int last_sent = -1;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const FrameRecord& f = frames[i];
    if (std::isnan(f.sent)) continue;
    ++r.sent;
    last_sent = static_cast<int>(i);
    if (f.answers > 1) ++r.doubled;
    if (f.answers > 0) {
      ++r.answered;
      if (f.answered < latest_answer) ++r.out_of_order;
      if (f.answered > latest_answer) latest_answer = f.answered;
      const long gap = f.seq >= 0 && latest_seq >= 0 ? std::max(0L, f.seq - latest_seq - 1) : 0;
      r.lost_in_transport += static_cast<int>(gap);
      settleIdleDrops(idle, gap, r);
      latest_seq = f.seq;
      continue;
    }
    ++r.dropped;
    if (latest_answer > f.sent) continue;  // dropped while an earlier frame was in processing
    // The next answer after this frame, and how many newer frames were sent before it.
    double next_answer = INFINITY;
    for (std::size_t k = i + 1; k < frames.size(); ++k) {
      if (frames[k].answers > 0) {
        next_answer = frames[k].answered;
        break;
      }
    }
    int newer = 0;
    for (std::size_t k = i + 1; k < frames.size() && newer < backlog; ++k) {
      if (frames[k].sent < next_answer) ++newer;
    }
    if (backlog > 0 && newer >= backlog) {
      ++r.dropped_by_backlog;
    } else {
      idle.push_back(i);
    }
  }
  settleIdleDrops(idle, 0, r);
  r.last_answered = last_sent >= 0 && frames[static_cast<std::size_t>(last_sent)].answers > 0;
  return r;
}

}  // namespace ros_test
}  // namespace obstacle_tracker
