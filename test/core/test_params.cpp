// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/params.h"

namespace oc = obstacle_tracker::core;

namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(Params, DefaultsLieInTheirRanges) {
  oc::Params p;
  EXPECT_TRUE(oc::validate(p).empty());
  for (const auto& info : oc::paramTable()) {
    EXPECT_LE(info.min_value, info.default_value) << info.name;
    EXPECT_GE(info.max_value, info.default_value) << info.name;
    EXPECT_EQ(oc::getParam(p, info.name), info.default_value) << info.name;
  }
}

TEST(Params, NanIsRefusedAndOutOfRangeIsClampedWithAMessage) {
  oc::Params p;
  std::string msg;
  EXPECT_FALSE(oc::setParam(p, "peak_threshold", std::numeric_limits<double>::quiet_NaN(), &msg));
  EXPECT_NE(msg.find("peak_threshold"), std::string::npos);
  EXPECT_NE(msg.find("[0, 1]"), std::string::npos) << msg;
  EXPECT_DOUBLE_EQ(p.peak_threshold, oc::Params().peak_threshold);

  EXPECT_TRUE(oc::setParam(p, "search_window_scale", -3.0, &msg));
  EXPECT_DOUBLE_EQ(p.search_window_scale, 1.0);
  EXPECT_NE(msg.find("search_window_scale"), std::string::npos);

  EXPECT_TRUE(oc::setParam(p, "max_obstacles", std::numeric_limits<double>::infinity(), &msg));
  EXPECT_EQ(p.max_obstacles, 16);
  EXPECT_FALSE(msg.empty());

  EXPECT_TRUE(oc::setParam(p, "detection_interval", 2.6, &msg));
  EXPECT_EQ(p.detection_interval, 3);

  EXPECT_TRUE(oc::setParam(p, "learning_rate", 0.05, &msg));
  EXPECT_TRUE(msg.empty()) << msg;
  EXPECT_DOUBLE_EQ(p.learning_rate, 0.05);

  EXPECT_FALSE(oc::setParam(p, "no_such_parameter", 1.0, &msg));
  EXPECT_NE(msg.find("no_such_parameter"), std::string::npos);
}

TEST(Params, ValidateClampsEveryField) {
  oc::Params p;
  p.kcf_cell_size = -5;
  p.learning_rate = std::numeric_limits<double>::quiet_NaN();
  p.scale_step = 100.0;
  auto messages = oc::validate(p);
  EXPECT_EQ(messages.size(), 3u);
  EXPECT_EQ(p.kcf_cell_size, 1);
  EXPECT_DOUBLE_EQ(p.learning_rate, oc::Params().learning_rate);
  EXPECT_DOUBLE_EQ(p.scale_step, 1.5);
}

// A component's own group is clamped on arrival (clampGroup) as validate() clamps the whole
// Params: every field of the group pushed below its minimum, above its maximum and (doubles) to
// NaN comes back as validate() makes it.
template <typename Group>
void expectGroupClampsLikeValidate(const oc::Params& pushed) {
  Group group = pushed;
  oc::clampGroup(group);
  oc::Params whole = pushed;
  oc::validate(whole);
  const Group& expected = whole;
  oc::Params from_group;
  static_cast<Group&>(from_group) = group;
  oc::Params from_whole;
  static_cast<Group&>(from_whole) = expected;
  for (const oc::ParamInfo& info : oc::paramTable()) {
    EXPECT_EQ(oc::getParam(from_group, info.name), oc::getParam(from_whole, info.name)) << info.name;
  }
}

// Every double and int field at `offset` from the bound `bound` (or NaN for doubles).
oc::Params pushedTo(double oc::ParamInfo::*bound, double offset, bool nan) {
  oc::Params p;
#define OT_TEST_PUSH_(type, name, def, lo, hi, unit, doc)                                 \
  {                                                                                       \
    const oc::ParamInfo* info = oc::findParam(#name);                                     \
    const double v = nan ? std::numeric_limits<double>::quiet_NaN() : info->*bound + offset; \
    if constexpr (std::is_same_v<type, double>) {                                         \
      p.name = v;                                                                         \
    } else if constexpr (std::is_same_v<type, int>) {                                     \
      if (!nan) p.name = static_cast<int>(v);                                             \
    }                                                                                     \
  }
  OT_PARAMS(OT_TEST_PUSH_)
#undef OT_TEST_PUSH_
  return p;
}

TEST(Params, GroupsClampLikeValidate) {
  for (const oc::Params& pushed : {pushedTo(&oc::ParamInfo::min_value, -1.0, false),
                                   pushedTo(&oc::ParamInfo::max_value, 1.0, false),
                                   pushedTo(&oc::ParamInfo::min_value, 0.0, true)}) {
    expectGroupClampsLikeValidate<oc::SaliencyParams>(pushed);
    expectGroupClampsLikeValidate<oc::TrackerParams>(pushed);
  }
}

TEST(Params, YamlLoaderReportsBadValuesAndNeverThrowsOnContent) {
  std::vector<std::string> messages;
  oc::Params p = oc::loadParamsString(
      "peak_threshold: 0.3\nmax_obstacles: 500\nlearning_rate: .nan\nbogus: 1\n"
      "saliency_backgroundness: true\nsearch_window_scale: hello\n",
      &messages);
  EXPECT_DOUBLE_EQ(p.peak_threshold, 0.3);
  EXPECT_EQ(p.max_obstacles, 16);
  EXPECT_DOUBLE_EQ(p.learning_rate, oc::Params().learning_rate);
  EXPECT_TRUE(p.saliency_backgroundness);
  EXPECT_DOUBLE_EQ(p.search_window_scale, oc::Params().search_window_scale);
  EXPECT_GE(messages.size(), 4u);
  EXPECT_THROW(oc::loadParamsFile("/nonexistent/params.yaml", &messages), std::runtime_error);
  EXPECT_THROW(oc::loadParamsFile("/tmp", &messages), std::runtime_error);  // a directory
  EXPECT_THROW(oc::loadParamsString("[unclosed", &messages), std::runtime_error);
}

TEST(Params, YamlRoundTrip) {
  oc::Params p;
  p.peak_threshold = 0.123;
  p.kcf_template_size = 64;
  p.reject_border_regions = false;
  std::vector<std::string> messages;
  oc::Params q = oc::loadParamsString(oc::paramsToYaml(p), &messages);
  EXPECT_TRUE(messages.empty());
  for (const auto& info : oc::paramTable()) {
    EXPECT_DOUBLE_EQ(oc::getParam(q, info.name), oc::getParam(p, info.name)) << info.name;
  }
}

// The parameter is declared once (params.h); the YAML defaults and the README table must carry
// the same names and defaults; the dynamic_reconfigure .cfg reads params.h itself.
TEST(Params, DefaultsYamlAndReadmeMatchTheCore) {
  const std::string root = OT_SOURCE_DIR;
  std::vector<std::string> messages;
  oc::Params fromYaml = oc::loadParamsFile(root + "/config/defaults.yaml", &messages);
  EXPECT_TRUE(messages.empty()) << messages.front();
  const std::string yaml = readFile(root + "/config/defaults.yaml");
  const std::string readme = readFile(root + "/README.md");
  const std::string cfg = readFile(root + "/config/ObstacleTracker.cfg");
  EXPECT_NE(cfg.find("params.h"), std::string::npos);
  for (const auto& info : oc::paramTable()) {
    EXPECT_NE(yaml.find(std::string("\n") + info.name + ":"), std::string::npos)
        << info.name << " missing from config/defaults.yaml";
    EXPECT_DOUBLE_EQ(oc::getParam(fromYaml, info.name), info.default_value)
        << info.name << " default differs in config/defaults.yaml";
    EXPECT_NE(readme.find(std::string("| `") + info.name + "` |"), std::string::npos)
        << info.name << " missing from README's parameter table";
  }
}
