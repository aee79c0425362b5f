// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Parameter files read with yaml-cpp's event parser (flat_yaml.h). Events rather than
// YAML::LoadAll for two reasons: a flat map needs no node tree (values under a nested map or
// list are skipped, not stored), and LoadAll loops without end, allocating until the process
// dies, on some malformed text (yaml-cpp 0.7, as Debian 12 ships it: a list item whose
// indentation drops inside a parenthesised plain scalar; test_flat_yaml.cpp has the text). Here
// a parser that returns more documents than the text has characters has stopped advancing,
// and that is a parse error.
#include "obstacle_tracker/core/flat_yaml.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>

namespace obstacle_tracker {
namespace core {

namespace {

std::string lineOf(const YAML::Mark& mark) {
  return mark.is_null() ? std::string("line ?") : "line " + std::to_string(mark.line + 1);
}

[[noreturn]] void notAFlatMap(const YAML::Mark& mark, const std::string& what) {
  throw std::runtime_error(lineOf(mark) + ": " + what);
}

// yaml-cpp's tag of a scalar: "?" plain (resolved by YAML 1.1's rules), "!" quoted (a string),
// "tag:yaml.org,2002:..." a core-schema tag, anything else an application tag such as
// rosparam's !degrees, which is not converted (so the value is not taken for a number).
void resolveScalar(const std::string& tag, const std::string& value, FlatYamlEntry* e) {
  static const std::string kCore = "tag:yaml.org,2002:";
  if (tag == "?" || tag == kCore + "float" || tag == kCore + "int" || tag == kCore + "bool") {
    resolvePlainScalar(value, e);
  } else {
    e->kind = FlatYamlEntry::kString;
    e->text = value;
  }
}

// Collects `key: value` pairs of each document's top-level map. Depth 0 is outside any
// collection, 1 inside the top-level map, deeper inside a nested value (skipped).
class FlatMapCollector : public YAML::EventHandler {
 public:
  std::vector<FlatYamlEntry> entries;

  void OnDocumentStart(const YAML::Mark&) override { depth_ = 0; }
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    FlatYamlEntry value;
    value.kind = FlatYamlEntry::kNull;
    onLeaf(mark, anchor, value, "");
  }

  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const auto found = anchors_.find(anchor);
    FlatYamlEntry value;
    if (found != anchors_.end()) value = found->second;
    onLeaf(mark, 0, value, value.kind == FlatYamlEntry::kString ? value.text : "");
  }

  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& text) override {
    FlatYamlEntry value;
    resolveScalar(tag, text, &value);
    onLeaf(mark, anchor, value, text);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    if (depth_ == 0) notAFlatMap(mark, "expected a map of parameter names to values, found a list");
    onCollectionStart(mark, anchor);
  }
  void OnSequenceEnd() override { --depth_; }

  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    if (depth_ == 0) {
      depth_ = 1;
      expecting_key_ = true;
      return;
    }
    onCollectionStart(mark, anchor);
  }
  void OnMapEnd() override { --depth_; }

 private:
  // A scalar, null or alias: a key or a value in the top-level map, or skipped when nested.
  void onLeaf(const YAML::Mark& mark, YAML::anchor_t anchor, FlatYamlEntry value,
              const std::string& text) {
    if (anchor != 0) anchors_[anchor] = value;
    if (depth_ == 0) {
      if (value.kind == FlatYamlEntry::kNull) return;  // an empty document
      notAFlatMap(mark, "expected a map of parameter names to values, found '" + text + "'");
    }
    if (depth_ > 1) return;
    if (expecting_key_) {
      if (value.kind == FlatYamlEntry::kNull || text.empty()) {
        notAFlatMap(mark, "empty parameter name");
      }
      FlatYamlEntry entry;
      entry.key = text;
      entry.line = mark.line + 1;
      entries.push_back(entry);
    } else {
      FlatYamlEntry& entry = entries.back();
      entry.kind = value.kind;
      entry.number = value.number;
      entry.text = value.text;
    }
    expecting_key_ = !expecting_key_;
  }

  void onCollectionStart(const YAML::Mark& mark, YAML::anchor_t anchor) {
    if (anchor != 0) anchors_[anchor].kind = FlatYamlEntry::kNested;
    if (depth_ == 1) {
      if (expecting_key_) notAFlatMap(mark, "a parameter name must be a word, not a map or list");
      entries.back().kind = FlatYamlEntry::kNested;
      expecting_key_ = true;
    }
    ++depth_;
  }

  int depth_ = 0;
  bool expecting_key_ = true;
  std::map<YAML::anchor_t, FlatYamlEntry> anchors_;
};

}  // namespace

std::vector<FlatYamlEntry> parseFlatYaml(const std::string& input) {
  // Old Mac line ends (CR only), which YAML allows and yaml-cpp does not read, become LF.
  std::string text = input;
  if (text.find('\n') == std::string::npos) std::replace(text.begin(), text.end(), '\r', '\n');
  std::istringstream stream(text);
  FlatMapCollector collector;
  try {
    YAML::Parser parser(stream);
    // rosparam loads every document of a file into the same namespace, so later documents add
    // to (and override) the earlier ones here too.
    std::size_t documents = 0;
    while (parser.HandleNextDocument(collector)) {
      if (++documents > text.size() + 1) {
        throw std::runtime_error("line ?: the YAML parser stopped advancing (malformed text)");
      }
    }
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(lineOf(e.mark) + ", column " + std::to_string(e.mark.column + 1) +
                             ": " + e.msg);
  }
  return collector.entries;
}

}  // namespace core
}  // namespace obstacle_tracker
