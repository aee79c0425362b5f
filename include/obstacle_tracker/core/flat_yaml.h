// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Parameter files as flat YAML maps (what `rosparam dump` writes for a node's private namespace
// and what print_params --yaml writes): `name: value` lines with comments, or a flow map
// `{name: value, "name": value}` (so JSON works too); several `---` documents add up, as
// `rosparam load` does. yaml-cpp parses the text; plain scalars are resolved as YAML 1.1 does
// (ints incl. 0x/0o, floats incl. .inf/.nan, true/false/yes/no/on/off, null/~; quoted strings
// stay strings), a little more leniently about numbers (flat_yaml.cpp lists how). A nested map or
// list under a key is reported as such (the caller ignores it with a message); text that is not
// YAML, or not a map, throws std::runtime_error with the line number.
//
// Not cv::FileStorage: its YAML parser let std::length_error escape on fuzzed text (fuzz_params,
// test_flat_yaml.cpp) and is not meant for untrusted input.
#pragma once

#include <string>
#include <string_view>
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

// Throws std::runtime_error("line N: ...") when the text is not YAML or not a flat map.
std::vector<FlatYamlEntry> parseFlatYaml(const std::string& text);

// Sets e->kind, number and text from a plain (unquoted, untagged) scalar by YAML 1.1's rules
// (yaml_scalar.cpp).
void resolvePlainScalar(std::string_view text, FlatYamlEntry* e);

}  // namespace core
}  // namespace obstacle_tracker
