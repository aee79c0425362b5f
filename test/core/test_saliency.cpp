// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Saliency detector: Otsu against the paper's formula and cv::threshold, region statistics against
// cv::connectedComponentsWithStats, generated sky / cloud / ground scenes with a known object,
// windowed re-detection in frame coordinates, search windows, parameters, bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/region_extractor.h"
#include "obstacle_tracker/core/saliency.h"
#include "obstacle_tracker/core/salient_region.h"

namespace oc = obstacle_tracker::core;

namespace {

struct Scene {
  cv::Mat frame;   // CV_8UC3 or CV_8UC1
  cv::Rect2f box;  // the object's bounding box
};

// Sky with a vertical gradient, optionally low-frequency "clouds" (blurred noise) and a textured
// ground band at the bottom; one filled ellipse or polygon, brighter or darker than the sky
// around it, 15-80 px, away from the border and above the ground.
Scene makeScene(cv::RNG& rng, cv::Size size, bool colour) {
  const int w = size.width, h = size.height;
  cv::Mat sky(h, w, CV_32FC3);
  const cv::Vec3f top(rng.uniform(90.f, 200.f), rng.uniform(80.f, 190.f), rng.uniform(60.f, 170.f));
  const cv::Vec3f bottom = top + cv::Vec3f(rng.uniform(-40.f, 40.f), rng.uniform(-40.f, 40.f),
                                           rng.uniform(-40.f, 40.f));
  for (int r = 0; r < h; ++r) {
    const float t = static_cast<float>(r) / (h - 1);
    sky.row(r).setTo(cv::Scalar(top * (1 - t) + bottom * t));
  }
  const int kind = rng.uniform(0, 3);  // 0 plain sky, 1 clouds, 2 clouds + ground
  if (kind >= 1) {
    cv::Mat noise(h / 8 + 1, w / 8 + 1, CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
    cv::resize(noise, noise, size, 0, 0, cv::INTER_CUBIC);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), 6.0);
    double lo, hi;
    cv::minMaxLoc(noise, &lo, &hi);
    noise = (noise - lo) / (hi - lo + 1e-6);  // 0..1
    const float amp = rng.uniform(15.f, 35.f);
    cv::Mat n3;
    cv::merge(std::vector<cv::Mat>{noise, noise, noise}, n3);
    sky += n3 * amp;
  }
  int ground_top = h;
  if (kind == 2) {
    ground_top = h - rng.uniform(h / 6, h / 3);
    cv::Mat tex(h - ground_top, w, CV_32FC3);
    rng.fill(tex, cv::RNG::NORMAL, 0.0, 12.0);
    cv::GaussianBlur(tex, tex, cv::Size(0, 0), 1.5);
    tex += cv::Scalar(rng.uniform(30.0, 90.0), rng.uniform(40.0, 100.0), rng.uniform(30.0, 80.0));
    tex.copyTo(sky.rowRange(ground_top, h));
  }
  // The object.
  const int ow = rng.uniform(15, 81), oh = std::max(15, std::min(80, static_cast<int>(ow * rng.uniform(0.4, 1.3))));
  const int margin = 10;
  const int max_y = std::max(margin + 1, ground_top - oh - margin);
  const cv::Point tl(rng.uniform(margin, w - ow - margin), rng.uniform(margin, max_y));
  cv::Mat mask(h, w, CV_8UC1, cv::Scalar(0));
  if (rng.uniform(0, 2) == 0) {
    cv::ellipse(mask, cv::Point(tl.x + ow / 2, tl.y + oh / 2), cv::Size(ow / 2, oh / 2), 0, 0, 360,
                cv::Scalar(255), cv::FILLED, cv::LINE_8);
  } else {
    std::vector<cv::Point> poly;
    const int n = rng.uniform(3, 8);
    for (int k = 0; k < n; ++k) {
      const double a = 2 * CV_PI * (k + rng.uniform(0.0, 0.6)) / n;
      const double rad = rng.uniform(0.7, 1.0);
      poly.emplace_back(tl.x + static_cast<int>(std::lround(ow / 2.0 * (1 + rad * std::cos(a)))),
                        tl.y + static_cast<int>(std::lround(oh / 2.0 * (1 + rad * std::sin(a)))));
    }
    cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255), cv::LINE_8);
  }
  const cv::Scalar around = cv::mean(sky, mask);
  const bool bright = rng.uniform(0, 2) == 0;
  const double delta = rng.uniform(70.0, 110.0) * (bright ? 1.0 : -1.0);
  cv::Scalar obj;
  for (int k = 0; k < 3; ++k) obj[k] = std::min(255.0, std::max(0.0, around[k] + delta + rng.uniform(-15.0, 15.0)));
  sky.setTo(obj, mask);
  Scene s;
  cv::Mat u8;
  sky.convertTo(u8, CV_8U);
  if (colour)
    s.frame = u8;
  else
    cv::cvtColor(u8, s.frame, cv::COLOR_BGR2GRAY);
  s.box = cv::boundingRect(mask);
  return s;
}

// The paper's Otsu (Bharati et al. eqs. 6-11) on an 8-bit image: the largest t maximising
// sigma_b^2(t) = (m_g P1 - m)^2 / (P1 (1 - P1)); pixels > t are salient.
int paperOtsu(const cv::Mat& img) {
  double hist[256] = {0};
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) hist[img.at<uchar>(r, c)] += 1.0;
  const double n = static_cast<double>(img.total());
  double mg = 0.0;
  for (int i = 0; i < 256; ++i) mg += i * hist[i] / n;
  double p1 = 0.0, m = 0.0, best = -1.0;
  int t_best = 0;
  for (int t = 0; t < 256; ++t) {
    p1 += hist[t] / n;
    m += t * hist[t] / n;
    if (p1 <= 1e-12 || p1 >= 1.0 - 1e-12) continue;
    const double s = (mg * p1 - m) * (mg * p1 - m) / (p1 * (1.0 - p1));
    if (s > best + 1e-9) {
      best = s;
      t_best = t;
    }
  }
  return t_best;
}

}  // namespace

TEST(Saliency, OtsuIsThePaperFormulaAndCvThreshold) {
  cv::RNG rng(21);
  oc::RegionExtractor ex;
  oc::Params p;
  std::vector<oc::SalientRegion> regions;
  for (int trial = 0; trial < 30; ++trial) {
    cv::Mat map(60, 80, CV_8UC1);
    rng.fill(map, cv::RNG::NORMAL, rng.uniform(20, 80), rng.uniform(5, 20));
    cv::Mat blob(map.size(), CV_8UC1);
    rng.fill(blob, cv::RNG::NORMAL, rng.uniform(140, 230), rng.uniform(5, 20));
    const cv::Rect r(rng.uniform(5, 40), rng.uniform(5, 30), rng.uniform(5, 30), rng.uniform(5, 25));
    blob(r).copyTo(map(r));
    oc::RegionExtractor::Geometry g;
    g.frame_area = 80 * 60;
    const double t = ex.extract(map, g, p, regions);
    cv::Mat ref;
    const double t_cv = cv::threshold(map, ref, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    EXPECT_EQ(t, t_cv);
    EXPECT_EQ(static_cast<int>(t), paperOtsu(map)) << "trial " << trial;
    EXPECT_EQ(cv::countNonZero(ref != ex.binary()), 0);
    ASSERT_FALSE(regions.empty());
    EXPECT_GE(oc::boxIou(regions[0].box, cv::Rect2f(r)), 0.8f);
  }
}

TEST(Saliency, RegionStatisticsMatchConnectedComponentsWithStats) {
  cv::RNG rng(4);
  oc::RegionExtractor ex;
  oc::Params p;
  p.min_object_area = 1.0;
  p.max_object_area_fraction = 1.0;
  p.reject_border_regions = false;
  std::vector<oc::SalientRegion> regions;
  for (int trial = 0; trial < 20; ++trial) {
    cv::Mat map(50, 70, CV_8UC1, cv::Scalar(10));
    for (int k = 0; k < 6; ++k)
      cv::circle(map, cv::Point(rng.uniform(0, 70), rng.uniform(0, 50)), rng.uniform(1, 8),
                 cv::Scalar(rng.uniform(150, 256)), cv::FILLED);
    oc::RegionExtractor::Geometry g;
    g.offset = cv::Point2f(100, 200);
    g.sx = 2.0f;
    g.sy = 3.0f;
    g.frame_area = 1e9;
    ex.extract(map, g, p, regions);
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(ex.binary(), labels, stats, centroids, 8, CV_32S);
    ASSERT_EQ(static_cast<int>(regions.size()), n - 1);
    for (int i = 1; i < n; ++i) {
      const cv::Rect2f box(100.0f + 2.0f * stats.at<int>(i, cv::CC_STAT_LEFT),
                           200.0f + 3.0f * stats.at<int>(i, cv::CC_STAT_TOP),
                           2.0f * stats.at<int>(i, cv::CC_STAT_WIDTH), 3.0f * stats.at<int>(i, cv::CC_STAT_HEIGHT));
      const float area = 6.0f * stats.at<int>(i, cv::CC_STAT_AREA);
      const double mean = cv::mean(map, labels == i)[0] / 255.0;
      const auto it = std::find_if(regions.begin(), regions.end(),
                                   [&](const oc::SalientRegion& s) { return s.box == box; });
      ASSERT_NE(it, regions.end());
      EXPECT_FLOAT_EQ(it->area, area);
      EXPECT_NEAR(it->mean_saliency, mean, 1e-5);
      EXPECT_NEAR(it->score, area * mean, 1e-2 * area);
    }
    for (size_t i = 1; i < regions.size(); ++i) EXPECT_GE(regions[i - 1].score, regions[i].score);
  }
}

TEST(Saliency, FindsObjectInGeneratedScenes) {
  cv::RNG rng(2026);
  oc::SaliencyDetector det;
  int found = 0;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    const Scene s = makeScene(rng, cv::Size(320, 240), i % 2 == 0);
    const auto& regions = det.detect(s.frame);
    const float best = regions.empty() ? 0.0f : oc::boxIou(regions[0].box, s.box);
    if (best >= 0.8f) ++found;
  }
  EXPECT_GE(found, 190) << found << " of " << n;
  std::printf("generated scenes: %d of %d found with IoU >= 0.8\n", found, n);
}

TEST(Saliency, WindowedRedetectionReturnsFrameCoordinates) {
  cv::RNG rng(99);
  oc::SaliencyDetector det;
  int found = 0;
  const int n = 60;
  for (int i = 0; i < n; ++i) {
    const Scene s = makeScene(rng, cv::Size(640, 480), i % 2 == 1);
    // The last box: the object's box shifted by up to a third of its size (it moved).
    const cv::Rect2f last(s.box.x + rng.uniform(-0.3f, 0.3f) * s.box.width,
                          s.box.y + rng.uniform(-0.3f, 0.3f) * s.box.height, s.box.width, s.box.height);
    const auto& regions = det.detectInWindow(s.frame, last);
    const cv::Rect win = oc::SaliencyDetector::searchWindow(s.frame.size(), last, oc::Params().search_window_scale);
    EXPECT_EQ(det.mapRegion(), win);
    for (const auto& r : regions) {
      EXPECT_TRUE((cv::Rect2f(win) & r.box) == r.box) << "region outside the window";
    }
    if (!regions.empty() && oc::boxIou(regions[0].box, s.box) >= 0.8f) ++found;
  }
  EXPECT_GE(found, 57) << found << " of " << n;
}

TEST(Saliency, WindowedAgreesWithWholeFrameOffsets) {
  // A square of 40 px at a known place: the windowed box is the square in frame coordinates.
  cv::Mat frame(480, 640, CV_8UC1, cv::Scalar(60));
  frame(cv::Rect(401, 133, 40, 40)).setTo(220);
  oc::SaliencyDetector det;
  const auto& regions = det.detectInWindow(frame, cv::Rect2f(395, 140, 40, 40));
  ASSERT_FALSE(regions.empty());
  EXPECT_FLOAT_EQ(regions[0].box.x, 401.0f);
  EXPECT_FLOAT_EQ(regions[0].box.y, 133.0f);
  EXPECT_FLOAT_EQ(regions[0].box.width, 40.0f);
  EXPECT_FLOAT_EQ(regions[0].box.height, 40.0f);
  EXPECT_FLOAT_EQ(regions[0].area, 1600.0f);
  EXPECT_NEAR(regions[0].mean_saliency, 1.0f, 1e-6);
}

TEST(Saliency, SearchWindowKnownValues) {
  using oc::SaliencyDetector;
  const cv::Size f(640, 480);
  // 3 x (20 x 10) = 60 x 30 -> height raised to the 32 px minimum; centre (110, 105).
  EXPECT_EQ(SaliencyDetector::searchWindow(f, cv::Rect2f(100, 100, 20, 10), 3.0), cv::Rect(80, 89, 60, 32));
  // Clipped at the top-left corner.
  EXPECT_EQ(SaliencyDetector::searchWindow(f, cv::Rect2f(0, 0, 20, 20), 3.0), cv::Rect(0, 0, 40, 40));
  // Clipped at the bottom-right corner.
  EXPECT_EQ(SaliencyDetector::searchWindow(f, cv::Rect2f(620, 460, 20, 20), 3.0), cv::Rect(600, 440, 40, 40));
  // Outside the frame, degenerate or non-finite: empty.
  EXPECT_TRUE(SaliencyDetector::searchWindow(f, cv::Rect2f(700, 10, 20, 20), 3.0).empty());
  EXPECT_TRUE(SaliencyDetector::searchWindow(f, cv::Rect2f(10, 10, 0, 20), 3.0).empty());
  EXPECT_TRUE(SaliencyDetector::searchWindow(f, cv::Rect2f(NAN, 10, 5, 5), 3.0).empty());
  // Empty window: empty result, no throw.
  oc::SaliencyDetector det;
  cv::Mat frame(480, 640, CV_8UC1, cv::Scalar(0));
  EXPECT_TRUE(det.detectInWindow(frame, cv::Rect2f(-100, -100, 10, 10)).empty());
}

TEST(Saliency, AreaAndBorderParameters) {
  cv::Mat frame(240, 320, CV_8UC1, cv::Scalar(50));
  frame(cv::Rect(100, 100, 6, 6)).setTo(250);   // 36 px
  frame(cv::Rect(200, 60, 30, 30)).setTo(250);  // 900 px
  oc::Params p;
  p.saliency_max_side = 320;
  p.min_object_area = 100;
  oc::SaliencyDetector det(p);
  auto regions = det.detect(frame);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_FLOAT_EQ(regions[0].area, 900.0f);
  p.min_object_area = 10;
  det.setParams(p);
  EXPECT_EQ(det.detect(frame).size(), 2u);
  p.max_object_area_fraction = 500.0 / (320 * 240);
  det.setParams(p);
  regions = det.detect(frame);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_FLOAT_EQ(regions[0].area, 36.0f);
}

TEST(Saliency, BorderRegionFlagAndRejection) {
  // A bright block glued to the left border except for the seed column: salient, and its box
  // starts at column 1, so it does not touch the border.
  cv::Mat frame(100, 100, CV_8UC1, cv::Scalar(20));
  frame(cv::Rect(0, 30, 60, 40)).setTo(230);  // glued to the left border
  frame(cv::Rect(0, 30, 1, 40)).setTo(20);    // but the seed column stays background
  oc::Params p;
  p.saliency_max_side = 100;
  p.reject_border_regions = false;
  oc::SaliencyDetector det(p);
  const auto& kept = det.detect(frame);
  ASSERT_FALSE(kept.empty());
  EXPECT_FALSE(kept[0].touches_border);  // starts at column 1
  // Flag and rejection of a region that touches the map border, on a given map.
  oc::RegionExtractor ex;
  std::vector<oc::SalientRegion> regions;
  cv::Mat map(40, 40, CV_8UC1, cv::Scalar(0));
  map(cv::Rect(0, 10, 10, 10)).setTo(255);
  map(cv::Rect(20, 20, 10, 10)).setTo(255);
  oc::RegionExtractor::Geometry g;
  g.frame_area = 1600;
  p = oc::Params();
  p.reject_border_regions = false;
  ex.extract(map, g, p, regions);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[0].touches_border + regions[1].touches_border, 1);
  p.reject_border_regions = true;
  ex.extract(map, g, p, regions);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_FALSE(regions[0].touches_border);
  EXPECT_FLOAT_EQ(regions[0].box.x, 20.0f);
}

TEST(Saliency, BuffersAreReused) {
  cv::RNG rng(8);
  oc::SaliencyDetector det;
  const Scene a = makeScene(rng, cv::Size(640, 480), true);
  det.detect(a.frame);
  const uchar* map_data = det.saliencyMap().data;
  det.detect(a.frame);
  EXPECT_EQ(det.saliencyMap().data, map_data);
  // Windows of different (smaller) sizes reuse the same memory once the largest was seen.
  det.detectInWindow(a.frame, cv::Rect2f(300, 200, 80, 80));
  const uchar* win_data = det.saliencyMap().data;
  det.detectInWindow(a.frame, cv::Rect2f(300, 200, 20, 20));
  EXPECT_EQ(det.saliencyMap().data, win_data);
}

TEST(Saliency, OptionsProduceValidMaps) {
  cv::RNG rng(12);
  const Scene s = makeScene(rng, cv::Size(320, 240), true);
  for (int bg = 0; bg < 2; ++bg)
    for (int pp = 0; pp < 2; ++pp)
      for (int med : {0, 5}) {
        oc::Params p;
        p.saliency_backgroundness = bg;
        p.saliency_postprocess = pp;
        p.saliency_median = med;
        oc::SaliencyDetector det(p);
        const auto& regions = det.detect(s.frame);
        const cv::Mat& map = det.saliencyMap();
        ASSERT_EQ(map.type(), CV_8UC1);
        EXPECT_EQ(std::max(map.cols, map.rows), 300);
        double mx = 0.0;
        cv::minMaxLoc(map, nullptr, &mx);
        EXPECT_EQ(mx, 255.0);
        ASSERT_FALSE(regions.empty()) << bg << pp << med;
        EXPECT_GE(oc::boxIou(regions[0].box, s.box), 0.5f) << bg << pp << med;
      }
}

TEST(Saliency, BadInputThrows) {
  oc::SaliencyDetector det;
  EXPECT_THROW(det.detect(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(det.detect(cv::Mat(10, 10, CV_32FC1, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(det.detect(cv::Mat(10, 10, CV_8UC4, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(det.detectInWindow(cv::Mat(), cv::Rect2f(0, 0, 5, 5)), std::invalid_argument);
  EXPECT_THROW(det.detectInWindow(cv::Mat(10, 10, CV_16UC1, cv::Scalar(0)), cv::Rect2f(0, 0, 5, 5)),
               std::invalid_argument);
}

TEST(Saliency, TinyAndThinFramesAreHandled) {
  oc::SaliencyDetector det;
  for (const cv::Size sz : {cv::Size(1, 1), cv::Size(2, 2), cv::Size(1, 500), cv::Size(700, 1), cv::Size(3, 3),
                            cv::Size(5000, 4)}) {
    for (int type : {CV_8UC1, CV_8UC3}) {
      cv::Mat f(sz, type, cv::Scalar::all(90));
      EXPECT_NO_THROW(det.detect(f)) << sz;
      EXPECT_NO_THROW(det.detectInWindow(f, cv::Rect2f(0, 0, 1, 1))) << sz;
      EXPECT_TRUE(det.detect(f).empty()) << sz;  // a flat frame has nothing salient
    }
  }
  // A box half outside the frame: window clipped, regions inside the frame.
  cv::Mat f(100, 100, CV_8UC1, cv::Scalar(30));
  f(cv::Rect(85, 40, 10, 10)).setTo(200);
  const auto& r = det.detectInWindow(f, cv::Rect2f(88, 38, 20, 14));
  ASSERT_FALSE(r.empty());
  EXPECT_FLOAT_EQ(r[0].box.x, 85.0f);
  EXPECT_LE(r[0].box.x + r[0].box.width, 100.0f);
}
