// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The flat YAML reader behind parameter files (yaml-cpp's parser, our YAML 1.1 scalar
// resolution as rosparam applies it): block and flow maps, and refusal (std::runtime_error with a
// line number) of what is not a flat map. Also the fuzzer's find that made us replace
// cv::FileStorage, and the text on which yaml-cpp's LoadAll never ends.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "obstacle_tracker/core/flat_yaml.h"
#include "obstacle_tracker/core/params.h"

namespace oc = obstacle_tracker::core;
using Entry = oc::FlatYamlEntry;

namespace {

Entry only(const std::string& text) {
  const auto entries = oc::parseFlatYaml(text);
  EXPECT_EQ(entries.size(), 1u) << text;
  return entries.empty() ? Entry() : entries.front();
}

double number(const std::string& value) {
  const Entry e = only("k: " + value);
  EXPECT_EQ(e.kind, Entry::kNumber) << value;
  return e.number;
}

std::string errorOf(const std::string& text) {
  try {
    oc::parseFlatYaml(text);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(FlatYaml, ResolvesNumbersAsYaml11) {
  EXPECT_EQ(number("42"), 42.0);
  EXPECT_EQ(number("-7"), -7.0);
  EXPECT_EQ(number("+3"), 3.0);
  EXPECT_EQ(number("0.25"), 0.25);
  EXPECT_EQ(number(".5"), 0.5);
  EXPECT_EQ(number("5."), 5.0);
  EXPECT_EQ(number("1.5e-3"), 1.5e-3);
  EXPECT_EQ(number("2e3"), 2000.0);  // lenient: PyYAML would read a string
  EXPECT_EQ(number("1_000"), 1000.0);
  EXPECT_EQ(number("0x1F"), 31.0);
  EXPECT_EQ(number("0o17"), 15.0);
  EXPECT_EQ(number("010"), 8.0);  // YAML 1.1 octal, as rosparam reads it
  EXPECT_EQ(number("0b101"), 5.0);
  EXPECT_EQ(number("1e999"), HUGE_VAL);
  EXPECT_EQ(number("1e-999"), 0.0);
  EXPECT_EQ(number(".inf"), HUGE_VAL);
  EXPECT_EQ(number("-.Inf"), -HUGE_VAL);
  EXPECT_TRUE(std::isnan(number(".nan")));
  EXPECT_EQ(number("!!float 3"), 3.0);
  EXPECT_EQ(number("&anchor 4"), 4.0);
}

TEST(FlatYaml, ResolvesBoolsNullsAndStrings) {
  for (const char* t : {"true", "True", "yes", "ON"}) {
    const Entry e = only(std::string("k: ") + t);
    EXPECT_EQ(e.kind, Entry::kBool) << t;
    EXPECT_EQ(e.number, 1.0) << t;
  }
  for (const char* f : {"false", "FALSE", "no", "off"}) {
    const Entry e = only(std::string("k: ") + f);
    EXPECT_EQ(e.kind, Entry::kBool) << f;
    EXPECT_EQ(e.number, 0.0) << f;
  }
  EXPECT_EQ(only("k:").kind, Entry::kNull);
  EXPECT_EQ(only("k: ~").kind, Entry::kNull);
  EXPECT_EQ(only("k: null").kind, Entry::kNull);
  for (const char* s : {"hello", "1.2.3", "0x", "1e", "e5", "--1", "0.5 px"}) {
    EXPECT_EQ(only(std::string("k: ") + s).kind, Entry::kString) << s;
  }
  const Entry quoted = only("k: \"0.5\"");
  EXPECT_EQ(quoted.kind, Entry::kString);  // quoted: a string, as in YAML
  EXPECT_EQ(quoted.text, "0.5");
  EXPECT_EQ(only("k: 'it''s # not a comment'").text, "it's # not a comment");
  // Anchors and aliases: the alias has the anchored value; an unknown alias is an error.
  const auto aliased = oc::parseFlatYaml("a: &v 0.25\nb: *v\nc: &m {x: 1}\nd: *m\n");
  ASSERT_EQ(aliased.size(), 4u);
  EXPECT_EQ(aliased[1].number, 0.25);
  EXPECT_EQ(aliased[3].kind, Entry::kNested);
  EXPECT_NE(errorOf("k: *alias").find("line 1"), std::string::npos);
}

TEST(FlatYaml, ReadsBlockMapsWithCommentsAndDocumentMarkers) {
  const auto entries = oc::parseFlatYaml(
      "\xEF\xBB\xBF%YAML 1.1\n---\n# comment\npeak_threshold: 0.3  # trailing\r\n\n"
      "\"quoted name\": 2\nnested:\n  a: 1\n  b: 2\nlist:\n- 1\n- 2\nflow: {a: 1, b: [2, 3]}\n"
      "last: 5\n...\n---\nsecond_document: 7\n");
  ASSERT_EQ(entries.size(), 7u);
  EXPECT_EQ(entries[0].key, "peak_threshold");
  EXPECT_EQ(entries[0].number, 0.3);
  EXPECT_EQ(entries[0].line, 4);
  EXPECT_EQ(entries[1].key, "quoted name");
  EXPECT_EQ(entries[2].kind, Entry::kNested);
  EXPECT_EQ(entries[3].kind, Entry::kNested);
  EXPECT_EQ(entries[4].kind, Entry::kNested);
  EXPECT_EQ(entries[5].key, "last");
  EXPECT_EQ(entries[5].number, 5.0);
  EXPECT_EQ(entries[6].key, "second_document");  // rosparam loads every document
  EXPECT_EQ(entries[6].number, 7.0);
}

TEST(FlatYaml, ReadsWhatRosparamReadsAcrossLinesAndLineEnds) {
  // `k:` then an indented scalar is `k: scalar`; a plain scalar over two lines is folded text.
  auto entries = oc::parseFlatYaml("k:\n  1.5\nj: 1\n  2\n");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].kind, Entry::kNumber);
  EXPECT_EQ(entries[0].number, 1.5);
  EXPECT_EQ(entries[1].kind, Entry::kString);
  EXPECT_EQ(entries[1].text, "1 2");
  // Old Mac line ends (CR only).
  entries = oc::parseFlatYaml("k: 1\rj: 2\r");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[1].number, 2.0);
  // Quotes inside nested values: it's is plain text, "a\"]" an escaped quote.
  EXPECT_EQ(only("k: [it's, 1]").kind, Entry::kNested);
  EXPECT_EQ(only("k: [\"a\\\"]\"]").kind, Entry::kNested);
  // Tags: core-schema ones are dropped; !!str and rosparam's unit tags keep it a string.
  EXPECT_EQ(only("k: !!float 3").number, 3.0);
  EXPECT_EQ(only("k: !!str 5").kind, Entry::kString);
  EXPECT_EQ(only("k: !degrees 90").kind, Entry::kString);
  entries = oc::parseFlatYaml("{k: !!float 2, j: &x}");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].number, 2.0);
  EXPECT_EQ(entries[1].kind, Entry::kNull);
  EXPECT_EQ(oc::parseFlatYaml("{a: 1}\n...\n").size(), 1u);
}

TEST(FlatYaml, OutOfRangeNumbersSaturateTheRightWay) {
  // Too small to represent: 0, whether the exponent is written or not.
  EXPECT_EQ(number("0." + std::string(330, '0') + "1"), 0.0);
  EXPECT_EQ(number("0." + std::string(330, '0') + "1e5"), 0.0);
  EXPECT_EQ(number("1" + std::string(400, '0')), HUGE_VAL);
  EXPECT_EQ(number("0.001e400"), HUGE_VAL);
  EXPECT_EQ(number("1000e-330"), 0.0);
  EXPECT_EQ(number("-1e400"), -HUGE_VAL);
}

TEST(FlatYaml, ReadsFlowMapsAndJson) {
  const auto entries = oc::parseFlatYaml(
      "{\"peak_threshold\": 0.2, max_obstacles: 3,  # comment\n  nested: {x: [1, {y: 2}]}, "
      "s: 'a,b}'}\n");
  ASSERT_EQ(entries.size(), 4u);
  EXPECT_EQ(entries[0].key, "peak_threshold");
  EXPECT_EQ(entries[0].number, 0.2);
  EXPECT_EQ(entries[1].number, 3.0);
  EXPECT_EQ(entries[2].kind, Entry::kNested);
  EXPECT_EQ(entries[2].line, 2);
  EXPECT_EQ(entries[3].text, "a,b}");
  EXPECT_TRUE(oc::parseFlatYaml("{}").empty());
  EXPECT_TRUE(oc::parseFlatYaml("").empty());
  EXPECT_TRUE(oc::parseFlatYaml("# only a comment\n---\n").empty());
}

TEST(FlatYaml, RefusesWhatIsNotAFlatMapWithTheLine) {
  EXPECT_NE(errorOf("[1, 2]").find("line 1: expected a map of parameter names to values, found a list"),
            std::string::npos);
  EXPECT_NE(errorOf("- 1\n- 2\n").find("found a list"), std::string::npos);
  EXPECT_NE(errorOf("just text").find("found 'just text'"), std::string::npos);
  EXPECT_NE(errorOf("a: 1\n  b: 2\n").find("line 2"), std::string::npos);
  EXPECT_NE(errorOf("a: 1\nb: [1, 2").find("line 2"), std::string::npos);
  EXPECT_NE(errorOf("{a: 1").find("line 1"), std::string::npos);
  EXPECT_NE(errorOf("{a: 1} b").find("line 1"), std::string::npos);
  EXPECT_NE(errorOf("a: \"open").find("line 1"), std::string::npos);
  EXPECT_NE(errorOf("a: 'x' y").find("line 1"), std::string::npos);
  EXPECT_NE(errorOf(": 1").find("line 1: empty parameter name"), std::string::npos);
  EXPECT_NE(errorOf("? [a]\n: 1\n").find("a parameter name must be a word"), std::string::npos);
  // Words without a colon read as a key without a value (yaml-cpp is lenient here); the
  // loader then names the line and the unknown parameter.
  std::vector<std::string> messages;
  oc::loadParamsString("peak_threshold: 0.3\njust words\n", &messages);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("parameters:2: unknown parameter 'just words'"), std::string::npos)
      << messages[0];
}

TEST(FlatYaml, TextOnWhichYamlCppLoadAllNeverEndsIsAnError) {
  // yaml-cpp 0.7's LoadAll allocates without end on this text (a list item whose value is a
  // parenthesised plain scalar with dropping indentation); the event reader refuses it at once.
  const std::string text =
      "\n- macro: exclude_commands\n  condition:\n    (user.uid = 1001 and user.loginuid in (-1, "
      "1001) and proc.exepath = \"/usr/bin/script\" and proc.args in (\n"
      "\"/usr/local/bin/script_metrics.sh\",\n    \"-c rsync\"\n    )  )  \n    )";
  EXPECT_NE(errorOf(text).find("line 2"), std::string::npos) << errorOf(text);
}

TEST(FlatYaml, ParameterLoaderNamesTheLineAndRefusesTheFuzzersFind) {
  std::vector<std::string> messages;
  oc::Params p = oc::loadParamsString(
      "peak_threshold: 0.3\npeak_threshold: 0.35\nmax_obstacles:\nmerge_iou: {a: 1}\n", &messages);
  EXPECT_DOUBLE_EQ(p.peak_threshold, 0.35);
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_NE(messages[0].find("parameters:2: parameter 'peak_threshold' given again"),
            std::string::npos)
      << messages[0];
  EXPECT_NE(messages[1].find("'max_obstacles' is empty"), std::string::npos) << messages[1];
  EXPECT_NE(messages[2].find("'merge_iou' is a map or list"), std::string::npos) << messages[2];

  // A text found by fuzz_params, on which a parser let std::length_error escape (the process
  // died): it must be a std::runtime_error naming the text and line.
  const std::string found("peak_thr%eshold::\xe0\xa4\xcf\xd7 8]\xf3\xff\xff\xff\0\0\0\0\0\0\0\0\0\0"
                          "\0\0\0\0\0\0\0\0\0\x9e\x9e\x9e\x9e\x9e\x9e\x9e\x9e\x9e\x9e\x9e\x9e\x9e"
                          "\x9e\x9e",
                          62);
  try {
    oc::loadParamsString(found, &messages);
    ADD_FAILURE() << "expected a parse error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot parse parameters: line 1"), std::string::npos)
        << e.what();
  }
}
