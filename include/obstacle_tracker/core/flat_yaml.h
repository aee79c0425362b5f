// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// A reader for the flat YAML maps that parameter files are (what `rosparam dump` writes for a
// node's private namespace and what print_params --yaml writes): `name: value` lines with
// comments, or one flow map `{name: value, "name": value}` (so JSON works too); several
// `---` documents add up, as `rosparam load` does. Scalars are resolved as YAML 1.1 does (ints
// incl. 0x/0o, floats incl. .inf/.nan, true/false/yes/no/on/off, null/~, quoted strings stay
// strings), a little more leniently about numbers (flat_yaml.cpp lists how). A nested map or
// list under a key is reported as such (the caller ignores it with a message); text that is not
// a map throws std::runtime_error with the line number.
//
// Our own code instead of cv::FileStorage: OpenCV's YAML parser let std::length_error escape on
// fuzzed text (fuzz_params, test_robust_fuzz.cpp) and is not meant for untrusted input. Written
// from the YAML 1.1 spec's scalar resolution rules, no code copied.
#pragma once

#include <string>
#include <vector>

namespace obstacle_tracker {
namespace core {

struct FlatYamlEntry {
  enum Kind { kNumber, kBool, kString, kNull, kNested };
  std::string key;
  Kind kind = kNull;
  double number = 0.0;  // kNumber (may be +-inf or NaN); kBool as 0/1
  std::string text;     // the scalar as written (kString: unquoted content)
  int line = 0;         // 1-based line of the key
};

// Throws std::runtime_error("line N: ...") when the text is not a flat map.
std::vector<FlatYamlEntry> parseFlatYaml(const std::string& text);

}  // namespace core
}  // namespace obstacle_tracker
