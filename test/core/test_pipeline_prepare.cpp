// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Pipeline::prepare warms the pipeline up on synthetic frames and forgets them: a prepared
// pipeline gives exactly the outputs (ids, boxes, scores, states, looming) of one that never was,
// whether prepared for the clip's size or another, colour or grey, auto-started or from a box.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/pipeline.h"
#include "obstacle_tracker/core/warmup.h"
#include "rendered_clip.h"

namespace oc = obstacle_tracker::core;

namespace {

using Clip = obstacle_tracker::test::RenderedClip;

Clip render(const std::string& scenario, cv::Size size, bool grey, int frames) {
  return obstacle_tracker::test::renderClip(scenario, 2, frames, size, grey);
}

// Every output of every frame, as text with full float precision (a readable diff on failure).
std::vector<std::string> run(const Clip& c, bool from_box, const cv::Size* prepare_size) {
  oc::Pipeline pipeline;
  if (prepare_size != nullptr) pipeline.prepare(*prepare_size, c.frames[0].type());
  std::vector<std::string> log;
  for (std::size_t i = 0; i < c.frames.size(); ++i) {
    const double stamp = static_cast<double>(i) / c.fps;
    const auto& out = (i == 0 && from_box) ? pipeline.startTrack(c.frames[i], stamp, c.truth[0])
                                           : pipeline.process(c.frames[i], stamp);
    std::string line = std::to_string(i) + ":";
    char buf[256];
    for (const oc::Obstacle& o : out) {
      std::snprintf(buf, sizeof(buf), " [%d %a %a %a %a %a %a %a %d %a %a %d]", o.id, o.box.x, o.box.y, o.box.width,
                    o.box.height, o.confidence, o.peak, o.psr, static_cast<int>(o.state), o.expansion_rate,
                    o.time_to_contact, o.age);
      line += buf;
    }
    log.push_back(line);
  }
  return log;
}

void expectSame(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "first difference at frame " << i;
}

}  // namespace

TEST(PipelinePrepare, AutoStartedColourClipUnchanged) {
  const Clip c = render("bird", cv::Size(480, 360), false, 60);
  const cv::Size same(480, 360), other(1280, 720);
  const std::vector<std::string> cold = run(c, false, nullptr);
  expectSame(cold, run(c, false, &same));
  expectSame(cold, run(c, false, &other));
  bool tracked = false;
  for (const std::string& line : cold) tracked = tracked || line.find('[') != std::string::npos;
  EXPECT_TRUE(tracked) << "the clip never started a track: the comparison would prove little";
}

TEST(PipelinePrepare, BoxStartedGreyClipUnchanged) {
  const Clip c = render("crossing", cv::Size(640, 512), true, 40);
  const cv::Size same(640, 512);
  expectSame(run(c, true, nullptr), run(c, true, &same));
}

TEST(PipelinePrepare, IdsContinueAfterAPrepareMidRun) {
  const Clip c = render("crossing", cv::Size(320, 240), false, 10);
  oc::Pipeline pipeline;
  const int first_id = pipeline.startTrack(c.frames[0], 0.0, c.truth[0]).at(0).id;
  pipeline.prepare(cv::Size(320, 240), CV_8UC3);  // forgets the track, not the id counter
  const int second_id = pipeline.startTrack(c.frames[1], 1.0, c.truth[0]).at(0).id;
  EXPECT_EQ(second_id, first_id + 1);
}

TEST(PipelinePrepare, RefusesWhatProcessRefusesAndSkipsTinyFrames) {
  oc::Pipeline pipeline;
  EXPECT_NO_THROW(pipeline.prepare(cv::Size(8, 8), CV_8UC1));     // too small to warm: nothing
  EXPECT_NO_THROW(pipeline.prepare(cv::Size(4000, 1), CV_8UC3));
  EXPECT_THROW(pipeline.prepare(cv::Size(64, 64), CV_16UC1), std::invalid_argument);
  EXPECT_THROW(oc::makeWarmupClip(cv::Size(15, 64), CV_8UC1), std::invalid_argument);
  EXPECT_NO_THROW(pipeline.prepare(cv::Size(16, 16), CV_8UC1));
  const oc::WarmupClip clip = oc::makeWarmupClip(cv::Size(100, 60), CV_8UC3);
  ASSERT_FALSE(clip.frames.empty());
  EXPECT_EQ(clip.frames[0].size(), cv::Size(100, 60));
  EXPECT_EQ(clip.frames[0].type(), CV_8UC3);
  EXPECT_GT(clip.box.area(), 0.0f);
}
