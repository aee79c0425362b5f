// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// FrameSlot (include/obstacle_tracker/ros/frame_slot.h): frames are dropped only while an earlier
// one is processed, always for the newest, and a burst that arrives while idle is kept whole.
// Also frame_delivery.h's checker, which the accuracy and load rostests trust.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "frame_delivery.h"
#include "obstacle_tracker/ros/frame_slot.h"

using obstacle_tracker::bridge::FrameSlot;
namespace rt = obstacle_tracker::ros_test;

TEST(FrameSlot, BurstWhileIdleIsKeptInOrder) {
  FrameSlot<int> slot;
  const int n = static_cast<int>(FrameSlot<int>::kIdleBacklog);
  ASSERT_GE(n, 2) << "two frames arriving together must both be kept";
  for (int i = 0; i < n; ++i) slot.offer(i);
  for (int i = 0; i < n; ++i) {
    int f = -1;
    ASSERT_TRUE(slot.take(&f));
    EXPECT_EQ(f, i);
    slot.done();
  }
  EXPECT_EQ(slot.dropped(), 0u);
}

TEST(FrameSlot, WhileBusyOnlyTheNewestWaits) {
  FrameSlot<int> slot;
  slot.offer(1);
  int f = 0;
  ASSERT_TRUE(slot.take(&f));  // busy with 1
  slot.offer(2);
  slot.offer(3);
  slot.offer(4);
  EXPECT_EQ(slot.dropped(), 2u);  // 2 and 3, replaced during processing
  slot.done();
  ASSERT_TRUE(slot.take(&f));
  EXPECT_EQ(f, 4);
  slot.done();
}

TEST(FrameSlot, IdleBacklogIsBounded) {
  FrameSlot<int> slot;
  const int n = static_cast<int>(FrameSlot<int>::kIdleBacklog) + 3;
  for (int i = 0; i < n; ++i) slot.offer(i);
  EXPECT_EQ(slot.dropped(), 3u);
  int f = -1;
  ASSERT_TRUE(slot.take(&f));
  EXPECT_EQ(f, 3);  // the oldest three went first
}

TEST(FrameSlot, StopWakesTheWaitingThread) {
  FrameSlot<int> slot;
  std::atomic<bool> returned{false}, result{true};
  std::thread worker([&] {
    int f = 0;
    result = slot.take(&f);
    returned = true;
  });
  slot.stop();
  worker.join();
  EXPECT_TRUE(returned);
  EXPECT_FALSE(result);
  slot.offer(1);  // ignored after stop
  int f = 0;
  EXPECT_FALSE(slot.take(&f));
}

TEST(FrameSlot, ThreadedProducerNeverLosesTheLastFrame) {
  FrameSlot<int> slot;
  std::vector<int> processed;
  std::thread worker([&] {
    int f = 0;
    while (slot.take(&f)) {
      processed.push_back(f);
      if (f == 9999) {
        slot.done();
        break;
      }
      std::this_thread::yield();
      slot.done();
    }
  });
  for (int i = 0; i < 10000; ++i) slot.offer(i);
  worker.join();
  ASSERT_FALSE(processed.empty());
  EXPECT_EQ(processed.back(), 9999);
  for (std::size_t i = 1; i < processed.size(); ++i) EXPECT_LT(processed[i - 1], processed[i]);
  EXPECT_EQ(slot.dropped() + processed.size(), 10000u);
}

TEST(FrameDelivery, DropWhileBusyIsAllowedDropWhileIdleIsNot) {
  // Frame 1 sent at 1.0 while frame 0 (answered at 1.5) was in processing: a legitimate drop.
  std::vector<rt::FrameRecord> frames = {{0.0, 1.5, 1}, {1.0, NAN, 0}, {2.0, 2.5, 1}};
  rt::DeliveryReport r = rt::checkDelivery(frames);
  EXPECT_TRUE(r.kept());
  EXPECT_EQ(r.dropped, 1);
  EXPECT_EQ(r.dropped_while_idle, 0);
  // Frame 1 sent after frame 0's answer: the tracker was idle, the drop breaks the rule.
  frames[1].sent = 1.6;
  r = rt::checkDelivery(frames);
  EXPECT_FALSE(r.kept());
  EXPECT_EQ(r.dropped_while_idle, 1);
  EXPECT_EQ(r.idle_drops, " 1");
}

TEST(FrameDelivery, AFullBacklogMayPushOutTheOldest) {
  // The tracker answered frame 0 at 0.5, then was not scheduled: frames 1..4 were sent before its
  // next answer (frame 2 at 4.5). With a backlog of 3, frame 1 was pushed out by 3 newer frames.
  std::vector<rt::FrameRecord> frames = {{0.0, 0.5, 1}, {1.0, NAN, 0}, {2.0, 4.5, 1}, {3.0, 5.5, 1}, {4.0, 6.5, 1}};
  rt::DeliveryReport r = rt::checkDelivery(frames, 3);
  EXPECT_TRUE(r.kept());
  EXPECT_EQ(r.dropped_by_backlog, 1);
  // With room for 4 it should not have been dropped; strict (0) never excuses an idle drop.
  EXPECT_EQ(rt::checkDelivery(frames, 4).dropped_while_idle, 1);
  EXPECT_EQ(rt::checkDelivery(frames, 0).dropped_while_idle, 1);
  // The old bug: two frames arriving together while idle, the first dropped; one newer frame only.
  frames = {{0.0, 0.5, 1}, {1.0, NAN, 0}, {1.0, 1.5, 1}};
  EXPECT_EQ(rt::checkDelivery(frames, 6).dropped_while_idle, 1);
}

TEST(FrameDelivery, AnAnswerLostInTransportIsNotAnIdleDrop) {
  // Frame 0 is answered (number 11). Frame 1 is processed and its answer (12) lost on the way;
  // frame 2, sent while frame 1 was in processing, is rightly replaced by frame 3, answered (13).
  // Frame 1's answer would have excused frame 2; lost, it cannot, so neither frame is blamed.
  std::vector<rt::FrameRecord> frames = {
      {0.0, 0.5, 1, 11}, {1.0, NAN, 0}, {1.2, NAN, 0}, {1.4, 1.9, 1, 13}};
  rt::DeliveryReport r = rt::checkDelivery(frames);
  EXPECT_EQ(r.lost_in_transport, 1);
  EXPECT_EQ(r.dropped_answer_lost, 2);
  EXPECT_EQ(r.dropped_while_idle, 0);
  EXPECT_TRUE(r.kept());
  // Without the numbers (or with no gap) the same frames are idle drops.
  frames[3].seq = 12;
  r = rt::checkDelivery(frames);
  EXPECT_EQ(r.lost_in_transport, 0);
  EXPECT_EQ(r.dropped_while_idle, 2);
  EXPECT_EQ(r.idle_drops, " 1 2");
  // A lost answer does not excuse a drop in another interval, nor before the first known number.
  frames = {{0.0, NAN, 0}, {1.0, 1.5, 1, 20}, {2.0, 2.5, 1, 22}, {3.0, 3.5, 1, 23}, {4.0, NAN, 0}, {5.0, 5.5, 1, 24}};
  r = rt::checkDelivery(frames);
  EXPECT_EQ(r.lost_in_transport, 1);
  EXPECT_EQ(r.dropped_answer_lost, 0);
  EXPECT_EQ(r.dropped_while_idle, 2);
  EXPECT_EQ(r.idle_drops, " 0 4");
  // The number of the answer before the first frame is given: the gap before frame 1 counts.
  r = rt::checkDelivery(frames, 0, 18);
  EXPECT_EQ(r.lost_in_transport, 2);
  EXPECT_EQ(r.dropped_while_idle, 1);
  EXPECT_EQ(r.idle_drops, " 4");
  // Unknown numbers (the accuracy test) excuse nothing.
  for (rt::FrameRecord& f : frames) f.seq = -1;
  EXPECT_EQ(rt::checkDelivery(frames, 0, 18).dropped_while_idle, 2);
}

TEST(FrameDelivery, DoubledOutOfOrderAndLastFrameAreCaught) {
  std::vector<rt::FrameRecord> frames = {{0.0, 0.5, 2}, {1.0, 1.5, 1}};
  EXPECT_EQ(rt::checkDelivery(frames).doubled, 1);
  frames = {{0.0, 2.0, 1}, {1.0, 1.5, 1}};
  EXPECT_EQ(rt::checkDelivery(frames).out_of_order, 1);
  frames = {{0.0, 0.5, 1}, {1.0, NAN, 0}};
  const rt::DeliveryReport r = rt::checkDelivery(frames);
  EXPECT_FALSE(r.last_answered);
  EXPECT_FALSE(r.kept());
  // Frames never sent are not counted.
  frames = {{0.0, 0.5, 1}, {NAN, NAN, 0}};
  EXPECT_TRUE(rt::checkDelivery(frames).kept());
}
