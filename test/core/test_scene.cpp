// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Scene generator: ground truth against the drawn pixels, time-to-contact law, determinism,
// every scenario at several sizes, mono16, writers.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/scene/random.h"
#include "obstacle_tracker/scene/raster.h"
#include "obstacle_tracker/scene/scene_generator.h"
#include "obstacle_tracker/scene/scene_io.h"

namespace os = obstacle_tracker::scene;

namespace {

std::uint64_t frameHash(const cv::Mat& m) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (int r = 0; r < m.rows; ++r) h = os::fnv1a64(m.ptr(r), m.cols * m.elemSize(), h);
  return h;
}

// Bounding box [x0, x1) x [y0, y1) of the non-zero pixels; empty rect when none.
cv::Rect nonZeroBounds(const cv::Mat& m8) {
  std::vector<cv::Point> pts;
  cv::findNonZero(m8, pts);
  if (pts.empty()) return cv::Rect();
  return cv::boundingRect(pts);
}

std::vector<std::string> baseNames() {
  std::vector<std::string> b;
  for (const auto& d : os::listScenarios())
    if (!d.modifier) b.push_back(d.name);
  return b;
}
std::vector<std::string> modifierNames() {
  std::vector<std::string> b;
  for (const auto& d : os::listScenarios())
    if (d.modifier) b.push_back(d.name);
  return b;
}

}  // namespace

TEST(SceneGenerator, ListsScenariosAndRejectsBadConfigs) {
  const auto b = baseNames(), m = modifierNames();
  for (const char* n : {"demo", "approach", "recede", "crossing", "rotation", "out_of_view", "multi", "bird", "tiny"})
    EXPECT_NE(std::find(b.begin(), b.end(), n), b.end()) << n;
  for (const char* n : {"jitter", "jerk", "blur", "noise", "illumination", "occlusion", "flock", "overlay", "glare"})
    EXPECT_NE(std::find(m.begin(), m.end(), n), m.end()) << n;
  EXPECT_THROW(os::makeScenario("nope", 1), std::invalid_argument);
  EXPECT_THROW(os::makeScenario("jitter", 1), std::invalid_argument);  // a modifier is not a base
  EXPECT_THROW(os::makeScenario("approach+nope", 1), std::invalid_argument);
  EXPECT_THROW(os::makeScenario("", 1), std::invalid_argument);
  EXPECT_THROW(os::makeScenario("approach", 1, 10, cv::Size(8, 8)), std::invalid_argument);
  EXPECT_THROW(os::makeScenario("approach", 1, -1), std::invalid_argument);
  EXPECT_THROW(os::makeScenario("approach", 1, 10, cv::Size(64, 48), false, 0.0), std::invalid_argument);
  auto g = os::makeScenario("approach", 1, 10, cv::Size(64, 48));
  cv::Mat f;
  EXPECT_THROW(g.renderFrame(10, f), std::out_of_range);
  EXPECT_THROW(g.renderFrame(-1, f), std::out_of_range);
  EXPECT_EQ(g.frameCount(), 10);
  EXPECT_EQ(os::makeScenario("demo", 1).frameCount(), 240);  // the default length
}

TEST(SceneGenerator, EveryScenarioRendersAtSeveralSizesIncludingTiny) {
  std::vector<std::string> names = baseNames();
  for (const auto& m : modifierNames()) names.push_back("crossing+" + m);
  names.push_back("approach+jitter+jerk+blur+noise+illumination+occlusion+flock+overlay+glare+clutter");
  for (const auto& name : names) {
    for (const cv::Size size : {cv::Size(16, 16), cv::Size(48, 32), cv::Size(200, 150)}) {
      for (bool mono16 : {false, true}) {
        if (mono16 && size.width != 48) continue;
        auto g = os::makeScenario(name, 5, 24, size, mono16);
        cv::Mat f;
        for (int i : {0, 11, 23}) {
          os::FrameTruth t;
          ASSERT_NO_THROW(g.renderFrame(i, f, &t)) << name << " " << size;
          ASSERT_EQ(f.size(), size) << name;
          ASSERT_EQ(f.type(), mono16 ? CV_16UC1 : CV_8UC3) << name;
          ASSERT_NE(t.find(1), nullptr) << name;
          EXPECT_EQ(t.frame, i);
          for (const auto& o : t.obstacles) {
            EXPECT_GE(o.visible_fraction, 0.0f) << name;
            EXPECT_LE(o.visible_fraction, 1.0f) << name;
            if (o.box.area() > 0) {
              EXPECT_GE(o.box.x, 0.0f) << name;
              EXPECT_GE(o.box.y, 0.0f) << name;
              EXPECT_LE(o.box.x + o.box.width, size.width + 1e-3f) << name;
              EXPECT_LE(o.box.y + o.box.height, size.height + 1e-3f) << name;
            }
            if (o.visible) {
              EXPECT_GT(o.box.area(), 0.0f) << name;
            }
          }
        }
      }
    }
  }
}

TEST(SceneGenerator, Mono16IsSixteenBitWithARealisticSignalRange) {
  for (const char* name : {"demo", "tiny+noise", "rotation+overlay"}) {
    auto g = os::makeScenario(name, 3, 20, cv::Size(160, 120), true);
    EXPECT_EQ(g.type(), CV_16UC1);
    cv::Mat f;
    g.renderFrame(10, f);
    ASSERT_EQ(f.type(), CV_16UC1);
    double lo, hi;
    cv::minMaxLoc(f, &lo, &hi);
    EXPECT_GT(lo, 1000.0) << name;    // an offset, like a real thermal core
    EXPECT_LT(hi, 16384.0) << name;   // within 14 bits
    EXPECT_GT(hi - lo, 1024.0) << name;  // more than 10 bits of signal
  }
}

// The ground-truth box of the main obstacle matches the drawn pixels (mask support) within 1 px.
TEST(SceneGenerator, GroundTruthBoxMatchesTheDrawnMask) {
  const std::vector<std::string> names = {"demo", "approach", "recede", "crossing", "rotation", "out_of_view", "multi", "bird", "tiny",
                                          "crossing+blur", "approach+jerk", "rotation+large", "crossing+small",
                                          "approach+as_bird", "approach+as_multirotor"};
  int compared = 0;
  for (const auto& name : names) {
    auto g = os::makeScenario(name, 11, 60, cv::Size(320, 240));
    cv::Mat mask;
    for (int i = 0; i < g.frameCount(); i += 3) {
      const os::FrameTruth t = g.truth(i);
      for (const auto& o : t.obstacles) {
        if (o.distractor) continue;
        g.renderObstacleMask(i, o.id, mask);
        const cv::Rect mb = nonZeroBounds(mask);
        if (o.box.area() <= 0.0f) {
          EXPECT_TRUE(mb.empty() || mb.area() <= 2) << name << " frame " << i << " id " << o.id;
          continue;
        }
        ASSERT_FALSE(mb.empty()) << name << " frame " << i << " id " << o.id;
        EXPECT_NEAR(mb.x, o.box.x, 1.0) << name << " frame " << i << " id " << o.id;
        EXPECT_NEAR(mb.y, o.box.y, 1.0) << name << " frame " << i << " id " << o.id;
        EXPECT_NEAR(mb.x + mb.width, o.box.x + o.box.width, 1.0) << name << " frame " << i << " id " << o.id;
        EXPECT_NEAR(mb.y + mb.height, o.box.y + o.box.height, 1.0) << name << " frame " << i << " id " << o.id;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 200);
}

// Rendering with and without the obstacles: every changed pixel lies in a ground-truth box, and
// the changed region of an unoccluded obstacle fills its box.
TEST(SceneGenerator, PixelsChangedByObstaclesLieInTheirBoxes) {
  for (const char* name : {"crossing", "rotation+jitter+noise", "multi", "bird+illumination", "approach+jerk", "tiny+clutter"}) {
    os::ScenarioConfig with;
    with.name = name;
    with.seed = 4;
    with.frames = 45;
    with.size = cv::Size(256, 192);
    os::ScenarioConfig without = with;
    without.render_obstacles = false;
    os::SceneGenerator a(with), b(without);
    cv::Mat fa, fb, diff, changed;
    for (int i = 0; i < with.frames; i += 4) {
      os::FrameTruth t;
      a.renderFrame(i, fa, &t);
      b.renderFrame(i, fb);
      cv::absdiff(fa, fb, diff);
      cv::Mat grey;
      cv::extractChannel(diff, grey, 0);
      for (int k = 1; k < 3; ++k) {
        cv::Mat ch;
        cv::extractChannel(diff, ch, k);
        grey = cv::max(grey, ch);
      }
      changed = grey > 0;
      cv::Mat outside = changed.clone();
      for (const auto& o : t.obstacles) {
        if (o.box.area() <= 0.0f) continue;
        const cv::Rect r = cv::Rect(cv::Point(static_cast<int>(std::floor(o.box.x)) - 1, static_cast<int>(std::floor(o.box.y)) - 1),
                                    cv::Point(static_cast<int>(std::ceil(o.box.x + o.box.width)) + 1,
                                              static_cast<int>(std::ceil(o.box.y + o.box.height)) + 1)) &
                           cv::Rect(0, 0, fa.cols, fa.rows);
        outside(r).setTo(0);
      }
      EXPECT_EQ(cv::countNonZero(outside), 0) << name << " frame " << i;
      const os::ObstacleTruth* m = t.find(1);
      if (t.obstacles.size() == 1 && m && m->visible_fraction > 0.999f && m->box.width > 6 && m->box.height > 6) {
        const cv::Rect cb = nonZeroBounds(changed);
        EXPECT_NEAR(cb.x, m->box.x, 2.0) << name << " frame " << i;
        EXPECT_NEAR(cb.y, m->box.y, 2.0) << name << " frame " << i;
        EXPECT_NEAR(cb.x + cb.width, m->box.x + m->box.width, 2.0) << name << " frame " << i;
        EXPECT_NEAR(cb.y + cb.height, m->box.y + m->box.height, 2.0) << name << " frame " << i;
      }
    }
  }
}

// Approach: size(t) = size(0) * T / (T - t) with T the time to contact at t = 0, and the reported
// time to contact is T - t; the drawn mask follows the same law within a pixel.
TEST(SceneGenerator, ApproachFollowsTheTimeToContactLaw) {
  for (const char* name : {"approach", "demo", "approach+jitter", "approach+as_multirotor"}) {
    auto g = os::makeScenario(name, 21, 90, cv::Size(320, 240));
    ASSERT_EQ(g.info().obstacles.size(), 1u);
    const double T = g.info().obstacles[0].time_to_contact_at_start;
    ASSERT_TRUE(std::isfinite(T)) << name;
    ASSERT_GT(T, 90 / 30.0) << name;  // contact happens after the clip
    EXPECT_GT(g.info().obstacles[0].closing_speed_mps, 0.0);
    const os::FrameTruth t0 = g.truth(0);
    const os::ObstacleTruth o0 = *t0.find(1);
    cv::Mat mask;
    g.renderObstacleMask(0, 1, mask);
    const cv::Rect m0 = nonZeroBounds(mask);
    for (int i = 10; i < g.frameCount(); i += 10) {
      const os::FrameTruth ti = g.truth(i);
      const os::ObstacleTruth& o = *ti.find(1);
      const double t = i / g.fps();
      const double k = T / (T - t);
      EXPECT_NEAR(o.time_to_contact, T - t, 1e-9) << name;
      // The model's outline scales exactly; the drawn box within a pixel at each end.
      EXPECT_NEAR(o.shape_box.width / o0.shape_box.width, k, 1e-4 * k) << name << " frame " << i;
      EXPECT_NEAR(o.shape_box.height / o0.shape_box.height, k, 1e-4 * k) << name << " frame " << i;
      EXPECT_NEAR(o.box.width, o0.box.width * k, 2.0 + 2.0 * k) << name << " frame " << i;
      EXPECT_NEAR(o.box.height, o0.box.height * k, 2.0 + 2.0 * k) << name << " frame " << i;
      EXPECT_NEAR(o.scale_px / o0.scale_px, k, 1e-6 * k) << name;
      EXPECT_NEAR(o.distance_m * k, o0.distance_m, 1e-6 * o0.distance_m) << name;
      g.renderObstacleMask(i, 1, mask);
      const cv::Rect mi = nonZeroBounds(mask);
      EXPECT_NEAR(mi.width, m0.width * k, 2.0 + 1.0 * k) << name << " frame " << i;
    }
    // The whole clip grows the obstacle by a large factor.
    const os::FrameTruth tl = g.truth(g.frameCount() - 1);
    EXPECT_GT(tl.find(1)->box.width / o0.box.width, 2.0) << name;
  }
}

TEST(SceneGenerator, SameSeedSameBytesInAnyRenderOrder) {
  for (bool mono16 : {false, true}) {
    auto a = os::makeScenario("approach+jitter+jerk+blur+noise+illumination+occlusion+flock+overlay", 99, 40, cv::Size(160, 120), mono16);
    auto b = os::makeScenario("approach+jitter+jerk+blur+noise+illumination+occlusion+flock+overlay", 99, 40, cv::Size(160, 120), mono16);
    std::vector<std::uint64_t> ha(40), hb(40);
    cv::Mat f;
    for (int i = 0; i < 40; ++i) {
      a.renderFrame(i, f);
      ha[static_cast<std::size_t>(i)] = frameHash(f);
    }
    for (int i = 39; i >= 0; --i) {
      b.renderFrame(i, f);
      hb[static_cast<std::size_t>(i)] = frameHash(f);
    }
    EXPECT_EQ(ha, hb);
    // Rendering again from the same generator gives the same frame too.
    a.renderFrame(17, f);
    EXPECT_EQ(frameHash(f), ha[17]);
  }
}

TEST(SceneGenerator, DifferentSeedsDiffer) {
  cv::Mat f1, f2;
  for (const char* name : {"demo", "crossing", "tiny"}) {
    auto a = os::makeScenario(name, 1, 10, cv::Size(160, 120));
    auto b = os::makeScenario(name, 2, 10, cv::Size(160, 120));
    a.renderFrame(5, f1);
    b.renderFrame(5, f2);
    EXPECT_NE(frameHash(f1), frameHash(f2)) << name;
    EXPECT_NE(a.truth(5).find(1)->box, b.truth(5).find(1)->box) << name;
  }
}

// Fingerprints of frames rendered in another process (and documented in docs/scenes.md): the
// generator is a pure function of its configuration, here and on any machine.
TEST(SceneGenerator, KnownFrameHashes) {
  cv::Mat f;
  auto g = os::makeScenario("demo", 1, 0, cv::Size(320, 240));
  g.renderFrame(0, f);
  EXPECT_EQ(frameHash(f), 0x38604330befc658fULL) << std::hex << frameHash(f);
  auto m = os::makeScenario("tiny+noise+overlay", 7, 30, cv::Size(160, 128), true);
  m.renderFrame(29, f);
  EXPECT_EQ(frameHash(f), 0xc7b627a56e117334ULL) << std::hex << frameHash(f);
}

TEST(SceneGenerator, OutOfViewLeavesAndComesBack) {
  auto g = os::makeScenario("out_of_view", 3, 0, cv::Size(320, 240));
  std::vector<bool> vis;
  for (int i = 0; i < g.frameCount(); ++i) vis.push_back(g.truth(i).find(1)->visible);
  // visible -> absent -> visible -> absent -> visible
  int changes = 0;
  for (std::size_t i = 1; i < vis.size(); ++i) changes += vis[i] != vis[i - 1];
  EXPECT_TRUE(vis.front());
  EXPECT_TRUE(vis.back());
  EXPECT_EQ(changes, 4);
  const auto absent = std::count(vis.begin(), vis.end(), false);
  EXPECT_GT(absent, g.frameCount() / 8);
  EXPECT_LT(absent, g.frameCount() / 2);
}

TEST(SceneGenerator, CloudOcclusionIsPartialThenFull) {
  auto g = os::makeScenario("crossing+occlusion", 8, 0, cv::Size(320, 240));
  int full = 0, partial = 0, clear = 0;
  bool visible_after_full = false;
  for (int i = 0; i < g.frameCount(); ++i) {
    const auto o = *g.truth(i).find(1);
    if (o.visible_fraction < 0.02f) ++full;
    else if (o.visible_fraction < 0.9f) ++partial;
    else ++clear;
    if (full > 0 && o.visible) visible_after_full = true;
    EXPECT_GT(o.box.area(), 0.0f);  // the box stays (OTB style) but `visible` says absent
    EXPECT_EQ(o.visible, o.visible_fraction >= os::kVisibleThreshold);
  }
  EXPECT_GT(full, 5);
  EXPECT_GT(partial, 3);
  EXPECT_GT(clear, 20);
  EXPECT_TRUE(visible_after_full);
}

TEST(SceneGenerator, FlockAndMultiHaveIdsAndClasses) {
  auto g = os::makeScenario("multi+flock", 2, 30, cv::Size(320, 240));
  const auto t = g.truth(15);
  ASSERT_NE(t.find(1), nullptr);
  ASSERT_NE(t.find(2), nullptr);
  ASSERT_NE(t.find(3), nullptr);
  EXPECT_EQ(t.find(1)->cls, os::ObstacleClass::kMultirotor);
  EXPECT_EQ(t.find(2)->cls, os::ObstacleClass::kFixedWing);
  EXPECT_EQ(t.find(3)->cls, os::ObstacleClass::kBird);
  int birds = 0;
  for (const auto& o : t.obstacles)
    if (o.distractor) {
      ++birds;
      EXPECT_GE(o.id, 101);
      EXPECT_EQ(o.cls, os::ObstacleClass::kBird);
    }
  EXPECT_GE(birds, 12);
}

TEST(SceneGenerator, CoverageRasterIsExactForAxisAlignedShapes) {
  cv::Mat cov = cv::Mat::zeros(8, 8, CV_32FC1);
  const cv::Point2f sq[4] = {{1.25f, 2.0f}, {5.75f, 2.0f}, {5.75f, 6.0f}, {1.25f, 6.0f}};
  os::addPolygonCoverage(sq, 4, cv::Point(0, 0), 4, cov);
  EXPECT_NEAR(cv::sum(cov)[0], 4.5 * 4.0, 1e-4);
  EXPECT_NEAR(cov.at<float>(3, 1), 0.75f, 1e-6);
  EXPECT_NEAR(cov.at<float>(3, 5), 0.75f, 1e-6);
  EXPECT_NEAR(cov.at<float>(3, 3), 1.0f, 1e-6);
  EXPECT_EQ(cov.at<float>(1, 3), 0.0f);
  // A triangle's area, from sub-scanlines.
  cv::Mat c2 = cv::Mat::zeros(40, 40, CV_32FC1);
  const cv::Point2f tri[3] = {{2.0f, 3.0f}, {37.0f, 9.0f}, {11.0f, 35.0f}};
  os::addPolygonCoverage(tri, 3, cv::Point(0, 0), 16, c2);
  const double area = 0.5 * std::fabs((37.0 - 2.0) * (35.0 - 3.0) - (11.0 - 2.0) * (9.0 - 3.0));
  EXPECT_NEAR(cv::sum(c2)[0], area, 0.002 * area);
  EXPECT_NEAR(os::detSin(0.5), std::sin(0.5), 1e-12);
  EXPECT_NEAR(os::detCos(-7.0), std::cos(-7.0), 1e-11);
  EXPECT_NEAR(os::detSin(1234.5), std::sin(1234.5), 1e-9);
}

TEST(SceneGenerator, WritesOtbFolderWithSideFiles) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("ot_scene_test_" + std::to_string(::getpid()))).string();
  for (bool mono16 : {false, true}) {
    std::filesystem::remove_all(dir);
    auto g = os::makeScenario("out_of_view+flock", 5, 12, cv::Size(96, 64), mono16);
    os::writeOtbSequence(g, dir);
    const std::string ext = mono16 ? "png" : "jpg";
    for (int i = 1; i <= 12; ++i) {
      char name[32];
      std::snprintf(name, sizeof(name), "/img/%04d.%s", i, ext.c_str());
      ASSERT_TRUE(std::filesystem::exists(dir + name)) << name;
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/img/0013." + ext));
    std::ifstream gt(dir + "/groundtruth_rect.txt");
    std::string line;
    int lines = 0;
    while (std::getline(gt, line)) {
      ++lines;
      EXPECT_EQ(std::count(line.begin(), line.end(), ','), 3) << line;
    }
    EXPECT_EQ(lines, 12);
    std::ifstream multi(dir + "/groundtruth_multi.csv");
    std::getline(multi, line);
    EXPECT_EQ(line, os::groundTruthMultiHeader());
    int rows = 0;
    while (std::getline(multi, line)) ++rows;
    EXPECT_EQ(rows, 12 * static_cast<int>(g.info().obstacles.size()));
    std::ifstream y(dir + "/scene.yaml");
    std::stringstream ys;
    ys << y.rdbuf();
    EXPECT_NE(ys.str().find("fps: 30"), std::string::npos);
    EXPECT_NE(ys.str().find("seed: 5"), std::string::npos);
    EXPECT_NE(ys.str().find(mono16 ? "encoding: mono16" : "encoding: bgr8"), std::string::npos);
    if (mono16) {
      // PNG keeps the 16 bits: the file holds exactly the rendered frame.
      cv::Mat f;
      g.renderFrame(3, f);
      const cv::Mat back = cv::imread(dir + "/img/0004.png", cv::IMREAD_UNCHANGED);
      ASSERT_EQ(back.type(), CV_16UC1);
      EXPECT_EQ(cv::norm(f, back, cv::NORM_INF), 0.0);
    }
  }
  std::filesystem::remove_all(dir);
  EXPECT_EQ(os::groundTruthLine(nullptr), "0,0,0,0");
}
