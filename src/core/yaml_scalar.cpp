// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// YAML 1.1 resolution of plain scalars (the type repository's bool, int, float and null) as
// rosparam's PyYAML applies it; yaml-cpp leaves plain scalars untyped. A little more lenient
// about numbers: any decimal float ("1e-3", "-.5", ".5e3", "1.0e3", "1e400") is a number here
// where PyYAML's float pattern needs a dot and a signed exponent, as are "09" (decimal), "0o17"
// (YAML 1.2 octal), "-inf", "-.nan" and the bare words inf/nan. Such a file read by
// `rosparam load` gives a string instead, and the nodelet then says "expected a number" and
// keeps the value. Not supported: sexagesimal ints ("1:30").
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>

#include "obstacle_tracker/core/flat_yaml.h"

namespace obstacle_tracker {
namespace core {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// Value of a digit string in `base` (underscores skipped, as YAML 1.1 allows); false if a
// character is not a digit of the base or there is no digit. Accumulated in double so a huge
// literal becomes a huge value (clamped later) rather than overflowing.
bool digitsValue(std::string_view s, int base, double* out) {
  double v = 0.0;
  bool any = false;
  for (char c : s) {
    if (c == '_') continue;
    int d;
    if (isDigit(c)) {
      d = c - '0';
    } else if (c >= 'a' && c <= 'f') {
      d = c - 'a' + 10;
    } else if (c >= 'A' && c <= 'F') {
      d = c - 'A' + 10;
    } else {
      return false;
    }
    if (d >= base) return false;
    v = v * base + d;
    any = true;
  }
  *out = v;
  return any;
}

// Decimal float grammar: digits[.digits][e[+-]digits] or .digits[e...]; parsed with
// std::from_chars (locale independent, unlike strtod).
bool decimalValue(std::string_view s, double* out) {
  std::string clean;
  clean.reserve(s.size());
  for (char c : s) {
    if (c != '_') clean.push_back(c);
  }
  std::size_t i = 0;
  const std::size_t n = clean.size();
  std::size_t mantissa_digits = 0;
  while (i < n && isDigit(clean[i])) ++i, ++mantissa_digits;
  if (i < n && clean[i] == '.') {
    ++i;
    while (i < n && isDigit(clean[i])) ++i, ++mantissa_digits;
  }
  if (mantissa_digits == 0) return false;
  if (i < n && (clean[i] == 'e' || clean[i] == 'E')) {
    ++i;
    if (i < n && (clean[i] == '+' || clean[i] == '-')) ++i;
    std::size_t exp_digits = 0;
    while (i < n && isDigit(clean[i])) ++i, ++exp_digits;
    if (exp_digits == 0) return false;
  }
  if (i != n) return false;
  double v = 0.0;
  const auto r = std::from_chars(clean.data(), clean.data() + n, v);
  if (r.ec == std::errc::result_out_of_range) {
    // Overflow to +inf, underflow to 0 (from_chars leaves v unspecified then): the decimal
    // exponent of the first non-zero mantissa digit plus the written exponent decides.
    const std::size_t e = std::min(clean.find_first_of("eE"), n);
    const std::size_t dot = std::min(clean.find('.'), e);
    const std::size_t first = clean.find_first_of("123456789");
    long magnitude = first < dot ? static_cast<long>(dot - first - 1) : -static_cast<long>(first - dot);
    if (e < n) {
      long ex = 0;
      std::size_t k = e + 1;
      const bool neg = k < n && clean[k] == '-';
      if (k < n && (clean[k] == '+' || clean[k] == '-')) ++k;
      for (; k < n; ++k) ex = std::min(100000L, ex * 10 + (clean[k] - '0'));
      magnitude += neg ? -ex : ex;
    }
    v = magnitude < 0 ? 0.0 : std::numeric_limits<double>::infinity();
  } else if (r.ec != std::errc() || r.ptr != clean.data() + n) {
    return false;
  }
  *out = v;
  return true;
}

}  // namespace

void resolvePlainScalar(std::string_view s, FlatYamlEntry* e) {
  e->text = std::string(s);
  if (s.empty() || s == "~" || s == "null" || s == "Null" || s == "NULL") {
    e->kind = FlatYamlEntry::kNull;
    return;
  }
  static const char* const kTrue[] = {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"};
  static const char* const kFalse[] = {"false", "False", "FALSE", "no",  "No",
                                       "NO",    "off",   "Off",   "OFF"};
  for (const char* t : kTrue) {
    if (s == t) {
      e->kind = FlatYamlEntry::kBool;
      e->number = 1.0;
      return;
    }
  }
  for (const char* f : kFalse) {
    if (s == f) {
      e->kind = FlatYamlEntry::kBool;
      e->number = 0.0;
      return;
    }
  }
  double sign = 1.0;
  std::string_view body = s;
  if (body.front() == '+' || body.front() == '-') {
    sign = body.front() == '-' ? -1.0 : 1.0;
    body.remove_prefix(1);
  }
  double v = 0.0;
  bool ok = false;
  if (body == ".inf" || body == ".Inf" || body == ".INF" || body == "inf" || body == "Inf" ||
      body == "INF") {
    v = std::numeric_limits<double>::infinity();
    ok = true;
  } else if (body == ".nan" || body == ".NaN" || body == ".NAN" || body == "nan" ||
             body == "NaN" || body == "NAN") {
    v = std::numeric_limits<double>::quiet_NaN();
    ok = true;
  } else if (body.size() > 2 && body[0] == '0' && (body[1] == 'x' || body[1] == 'X')) {
    ok = digitsValue(body.substr(2), 16, &v);
  } else if (body.size() > 2 && body[0] == '0' && (body[1] == 'o' || body[1] == 'O')) {
    ok = digitsValue(body.substr(2), 8, &v);
  } else if (body.size() > 2 && body[0] == '0' && (body[1] == 'b' || body[1] == 'B')) {
    ok = digitsValue(body.substr(2), 2, &v);
  } else if (body.size() > 1 && body[0] == '0' &&
             body.find_first_not_of("01234567_") == std::string_view::npos) {
    ok = digitsValue(body.substr(1), 8, &v);  // YAML 1.1 octal, as rosparam reads "010" (= 8)
  } else {
    ok = decimalValue(body, &v);
  }
  if (ok) {
    e->kind = FlatYamlEntry::kNumber;
    e->number = sign * v;
  } else {
    e->kind = FlatYamlEntry::kString;
  }
}

}  // namespace core
}  // namespace obstacle_tracker
