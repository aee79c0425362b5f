// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// KcfTracker::update / detect / learn / evaluate make no heap allocation once the tracker is
// initialised. malloc, calloc and realloc are interposed in this test program (glibc exports the
// real ones as __libc_*) and counted while a flag is set; under AddressSanitizer (which
// interposes them itself) or without glibc the test is skipped with a message.
#include <atomic>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/kcf.h"

#include "alloc_counter.h"

namespace oc = obstacle_tracker::core;

namespace {

std::vector<cv::Mat> makeClip(int type, cv::Rect box, int count) {
  cv::Mat bg(480, 640, CV_8UC3);
  cv::RNG rng(5);
  rng.fill(bg, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(bg, bg, cv::Size(0, 0), 3.0);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f = bg.clone();
    const cv::Rect b = box + cv::Point(i, i / 2);
    cv::rectangle(f, b, cv::Scalar(220, 40, 90), -1);
    cv::circle(f, (b.tl() + b.br()) / 2, b.height / 3, cv::Scalar(20, 200, 30), -1);
    if (type == CV_8UC1) cv::cvtColor(f, f, cv::COLOR_BGR2GRAY);
    frames.push_back(f);
  }
  return frames;
}

}  // namespace

TEST(KcfAllocation, NoHeapAllocationPerFrameAfterInit) {
  OT_SKIP_UNLESS_COUNTING_ALLOCATIONS();
  ASSERT_GT(probeOpenCvAllocations(), 0);  // so that a zero below means something

  struct Case {
    int type;
    cv::Rect box;
    bool scale_filter;
  };
  // A small box (plain bilinear sampling), a large one (box-shrink path), grey and colour, scale
  // search and DSST scale filter.
  for (const Case& c : {Case{CV_8UC3, cv::Rect(300, 200, 40, 30), false},
                        Case{CV_8UC1, cv::Rect(300, 200, 12, 9), false},
                        Case{CV_8UC3, cv::Rect(150, 100, 300, 200), false},
                        Case{CV_8UC1, cv::Rect(150, 100, 300, 200), true},
                        Case{CV_8UC3, cv::Rect(300, 200, 40, 30), true}}) {
    const std::vector<cv::Mat> frames = makeClip(c.type, c.box, 24);
    oc::Params p;
    p.kcf_scale_filter = c.scale_filter;
    if (c.scale_filter) p.scale_count = 17;
    oc::KcfTracker kcf(p);
    kcf.init(frames[0], c.box);
    for (int i = 1; i < 4; ++i) kcf.update(frames[i]);  // warm-up
    const cv::Rect2f candidate(static_cast<float>(c.box.x - 5), static_cast<float>(c.box.y + 3),
                               static_cast<float>(c.box.width), static_cast<float>(c.box.height));
    g_allocations = 0;
    g_counting = true;
    for (int i = 4; i < 24; ++i) {
      oc::Params q = p;
      q.learn_threshold = 0.3 + 0.01 * i;  // as the pipeline does when it moves its gate
      kcf.setParams(q);
      if (i % 3 == 0) {
        kcf.detect(frames[i]);
        kcf.learn(frames[i]);
      } else {
        kcf.update(frames[i]);
      }
      kcf.evaluate(frames[i], candidate);
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0)
        << "box " << c.box << " type " << c.type << " scale filter " << c.scale_filter;
  }
}
