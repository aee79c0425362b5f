// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/params.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "obstacle_tracker/core/flat_yaml.h"


namespace obstacle_tracker {
namespace core {

namespace {

template <typename T>
double toDouble(T v) {
  return static_cast<double>(v);
}

template <typename T>
void assign(T& field, double v) {
  field = static_cast<T>(v);
}
template <>
void assign<bool>(bool& field, double v) {
  field = v != 0.0;
}

std::string formatValue(const ParamInfo& info, double v) {
  std::ostringstream os;
  if (std::string(info.type) == "bool") {
    os << (v != 0.0 ? "true" : "false");
  } else if (std::string(info.type) == "int") {
    os << static_cast<long long>(v);
  } else {
    os << std::setprecision(9) << v;
  }
  return os.str();
}

std::string rangeText(const ParamInfo& info) {
  return "[" + formatValue(info, info.min_value) + ", " + formatValue(info, info.max_value) + "]";
}

}  // namespace

const std::vector<ParamInfo>& paramTable() {
  static const std::vector<ParamInfo> table = {
#define OT_PARAMS_INFO_(type, name, def, lo, hi, unit, doc) \
  ParamInfo{#name, #type, toDouble<type>(def), toDouble<type>(lo), toDouble<type>(hi), unit, doc},
      OT_PARAMS(OT_PARAMS_INFO_)
#undef OT_PARAMS_INFO_
  };
  return table;
}

const ParamInfo* findParam(const std::string& name) {
  for (const ParamInfo& info : paramTable()) {
    if (name == info.name) return &info;
  }
  return nullptr;
}

double getParam(const Params& params, const std::string& name) {
#define OT_PARAMS_GET_(type, pname, def, lo, hi, unit, doc) \
  if (name == #pname) return toDouble<type>(params.pname);
  OT_PARAMS(OT_PARAMS_GET_)
#undef OT_PARAMS_GET_
  throw std::out_of_range("unknown parameter '" + name + "'");
}

bool setParam(Params& params, const std::string& name, double value, std::string* message) {
  if (message) message->clear();
  const ParamInfo* info = findParam(name);
  if (!info) {
    if (message) *message = "unknown parameter '" + name + "' ignored";
    return false;
  }
  if (std::isnan(value)) {
    if (message) {
      *message = "parameter '" + name + "' = NaN refused; valid range " + rangeText(*info) +
                 ", keeping " + formatValue(*info, getParam(params, name));
    }
    return false;
  }
  double v = value;
  std::string type = info->type;
  if (v < info->min_value) v = info->min_value;
  if (v > info->max_value) v = info->max_value;
  if (type == "int") v = std::round(v);
  if (type == "bool") v = (v != 0.0) ? 1.0 : 0.0;
  if (message && v != value) {
    std::ostringstream os;
    os << "parameter '" << name << "' = " << std::setprecision(9) << value << " is outside "
       << (type == "int" ? "the integers of " : "") << "its valid range " << rangeText(*info)
       << "; using " << formatValue(*info, v);
    *message = os.str();
  }
#define OT_PARAMS_SET_(type, pname, def, lo, hi, unit, doc) \
  if (name == #pname) {                                    \
    assign<type>(params.pname, v);                         \
    return true;                                           \
  }
  OT_PARAMS(OT_PARAMS_SET_)
#undef OT_PARAMS_SET_
  return false;
}

namespace {

// A group's field into its range, silently (NaN -> default; ints and bools as they are).
void clampField(double& v, double def, double lo, double hi) {
  if (std::isnan(v)) v = def;
  v = std::min(hi, std::max(lo, v));
}
void clampField(int& v, double, double lo, double hi) {
  v = std::min(static_cast<int>(hi), std::max(static_cast<int>(lo), v));
}
void clampField(bool&, double, double, double) {}

}  // namespace

void clampGroup(SaliencyParams& params) {
#define OT_PARAMS_CLAMP_(type, name, def, lo, hi, unit, doc) clampField(params.name, def, lo, hi);
  OT_SALIENCY_PARAMS(OT_PARAMS_CLAMP_)
#undef OT_PARAMS_CLAMP_
}

void clampGroup(TrackerParams& params) {
#define OT_PARAMS_CLAMP_(type, name, def, lo, hi, unit, doc) clampField(params.name, def, lo, hi);
  OT_TRACKER_PARAMS(OT_PARAMS_CLAMP_)
#undef OT_PARAMS_CLAMP_
}

std::vector<std::string> validate(Params& params) {
  std::vector<std::string> messages;
  for (const ParamInfo& info : paramTable()) {
    double v = getParam(params, info.name);
    std::string msg;
    if (std::isnan(v)) {
      setParam(params, info.name, info.default_value);
      messages.push_back("parameter '" + std::string(info.name) + "' = NaN refused; valid range " +
                         rangeText(info) + ", using the default " +
                         formatValue(info, info.default_value));
      continue;
    }
    setParam(params, info.name, v, &msg);
    if (!msg.empty()) messages.push_back(msg);
  }
  return messages;
}

namespace {

// Applies the entries of a flat YAML map (flat_yaml.h) on top of `base`. Unknown names and
// values that are not numbers produce messages; only text that is not a map throws.
Params loadParamsText(const std::string& yaml, const std::string& what,
                      std::vector<std::string>* messages, const Params& base) {
  std::vector<FlatYamlEntry> entries;
  try {
    entries = parseFlatYaml(yaml);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot parse " + what + ": " + e.what());
  }
  Params params = base;
  std::vector<std::string> seen;
  for (const FlatYamlEntry& entry : entries) {
    const std::string& name = entry.key;
    const std::string where = what + ":" + std::to_string(entry.line);
    const ParamInfo* info = findParam(name);
    if (!info) {
      if (messages) messages->push_back(where + ": unknown parameter '" + name + "' ignored");
      continue;
    }
    if (std::find(seen.begin(), seen.end(), name) != seen.end() && messages) {
      messages->push_back(where + ": parameter '" + name + "' given again; the last one counts");
    }
    seen.push_back(name);
    if (entry.kind != FlatYamlEntry::kNumber && entry.kind != FlatYamlEntry::kBool) {
      if (messages) {
        const char* what_it_is = entry.kind == FlatYamlEntry::kNested ? "a map or list"
                                 : entry.kind == FlatYamlEntry::kNull ? "empty"
                                                                      : "not a number";
        messages->push_back(where + ": parameter '" + name + "' is " + what_it_is +
                            (entry.kind == FlatYamlEntry::kString ? " ('" + entry.text + "')" : "") +
                            "; keeping " + formatValue(*info, getParam(params, name)));
      }
      continue;
    }
    std::string msg;
    setParam(params, name, entry.number, &msg);
    if (!msg.empty() && messages) messages->push_back(where + ": " + msg);
  }
  return params;
}

}  // namespace

Params loadParamsFile(const std::string& path, std::vector<std::string>* messages,
                      const Params& base) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw std::runtime_error("cannot read parameter file '" + path + "': it is a directory");
  }
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open parameter file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw std::runtime_error("cannot read parameter file '" + path + "'");
  return loadParamsText(text.str(), path, messages, base);
}

Params loadParamsString(const std::string& yaml, std::vector<std::string>* messages,
                        const Params& base) {
  return loadParamsText(yaml, "parameters", messages, base);
}

std::string paramsToYaml(const Params& params) {
  std::ostringstream os;
  for (const ParamInfo& info : paramTable()) {
    os << "# " << info.description;
    if (info.unit[0] != '\0') os << " [" << info.unit << "]";
    os << ", range " << rangeText(info) << "\n";
    os << info.name << ": " << formatValue(info, getParam(params, info.name)) << "\n";
  }
  return os.str();
}

}  // namespace core
}  // namespace obstacle_tracker
