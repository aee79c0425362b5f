// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Flat YAML map reader for parameter files; see flat_yaml.h for what it accepts and why it is
// not cv::FileStorage. Scalar resolution follows the YAML 1.1 type repository (bool, int, float,
// null) as rosparam's PyYAML applies it, but is more lenient about numbers: any decimal float
// ("1e-3", "-.5", ".5e3", "1.0e3", "1e400") is a number here where PyYAML's float pattern needs a
// dot and a signed exponent, as are "09" (decimal), "0o17" (YAML 1.2 octal), "-inf", "-.nan"
// and the bare words inf/nan. Such a file read by `rosparam load` gives a string instead, and
// the nodelet then says "expected a number" and keeps the value. Not supported: sexagesimal
// ints ("1:30"), rosparam's !degrees/!radians (the value becomes a string, with a message), and
// multi-line quoted or flow values.
#include "obstacle_tracker/core/flat_yaml.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace obstacle_tracker {
namespace core {

namespace {

[[noreturn]] void parseError(int line, const std::string& what) {
  throw std::runtime_error("line " + std::to_string(line) + ": " + what);
}

bool isBlank(char c) { return c == ' ' || c == '\t'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (isBlank(s.front()) || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (isBlank(s.back()) || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

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

void resolvePlain(std::string_view s, FlatYamlEntry* e) {
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

// Reads a quoted scalar starting at s[*pos] (a ' or "); leaves *pos after the closing quote.
// Returns false if the line ends first.
bool readQuoted(std::string_view s, std::size_t* pos, std::string* out) {
  const char q = s[*pos];
  std::size_t i = *pos + 1;
  out->clear();
  while (i < s.size()) {
    const char c = s[i];
    if (q == '\'' && c == '\'') {
      if (i + 1 < s.size() && s[i + 1] == '\'') {
        out->push_back('\'');
        i += 2;
        continue;
      }
      *pos = i + 1;
      return true;
    }
    if (q == '"' && c == '\\' && i + 1 < s.size()) {
      const char x = s[i + 1];
      out->push_back(x == 'n' ? '\n' : x == 't' ? '\t' : x);
      i += 2;
      continue;
    }
    if (q == '"' && c == '"') {
      *pos = i + 1;
      return true;
    }
    out->push_back(c);
    ++i;
  }
  return false;
}

// Drops an anchor (&name) and a core-schema tag (!!int, !!float, !!bool, !!null) in front of a
// value; the token ends at a blank or at one of `stop` (",}" in a flow map). Any other tag
// (!!str, rosparam's !degrees / !radians, a local !tag) is reported through *other_tag and the
// value is then taken as a string (we do not convert units). An alias (*name) is kept and
// resolves as a string (we do not follow references).
std::string_view dropPropertyTokens(std::string_view v, std::string_view stop, std::string* other_tag) {
  for (int k = 0; k < 2 && !v.empty() && (v.front() == '&' || v.front() == '!'); ++k) {
    std::size_t end = 0;
    while (end < v.size() && !isBlank(v[end]) && stop.find(v[end]) == std::string_view::npos) ++end;
    const std::string_view token = v.substr(0, end);
    if (token.front() == '!' && token != "!!int" && token != "!!float" && token != "!!bool" &&
        token != "!!null") {
      *other_tag = std::string(token);
    }
    v.remove_prefix(end);
    // Leading blanks only: the caller counts the characters that are left.
    while (!v.empty() && isBlank(v.front())) v.remove_prefix(1);
  }
  return v;
}

// Removes a comment: '#' at the start or after a blank, outside quotes.
std::string_view stripComment(std::string_view s) {
  char quote = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quote) {
      if (quote == '\'' && c == '\'' && i + 1 < s.size() && s[i + 1] == '\'') {
        ++i;  // '' inside single quotes
      } else if (quote == '"' && c == '\\') {
        ++i;  // escaped character inside double quotes
      } else if (c == quote) {
        quote = 0;
      }
      continue;
    }
    if ((c == '"' || c == '\'') && (i == 0 || isBlank(s[i - 1]) || s[i - 1] == ':' ||
                                    s[i - 1] == '{' || s[i - 1] == ',' || s[i - 1] == '[')) {
      quote = c;
    } else if (c == '#' && (i == 0 || isBlank(s[i - 1]))) {
      return s.substr(0, i);
    }
  }
  return s;
}

// A value (after the key's colon) in block or flow context. `stop` lists the characters that
// end a plain scalar (",}" in a flow map). Sets e->kind/number/text; returns the number of
// characters used.
std::size_t readValue(std::string_view s, std::string_view stop, FlatYamlEntry* e, int line) {
  std::size_t i = 0;
  while (i < s.size() && isBlank(s[i])) ++i;
  std::string other_tag;
  std::string_view rest = dropPropertyTokens(s.substr(i), stop, &other_tag);
  i = s.size() - rest.size();
  if (rest.empty() || stop.find(rest.front()) != std::string_view::npos) {
    e->kind = FlatYamlEntry::kNull;
    return i;
  }
  const char c = rest.front();
  if (c == '"' || c == '\'') {
    std::size_t pos = 0;
    if (!readQuoted(rest, &pos, &e->text)) parseError(line, "unterminated quoted value");
    e->kind = FlatYamlEntry::kString;
    return i + pos;
  }
  if (c == '{' || c == '[') {
    // A nested collection: skip it, balanced, quote-aware.
    int depth = 0;
    char quote = 0;
    std::size_t j = 0;
    for (; j < rest.size(); ++j) {
      const char d = rest[j];
      if (quote) {
        if (quote == '"' && d == '\\') {
          ++j;  // escaped character
        } else if (d == quote) {
          quote = 0;
        }
        continue;
      }
      // A quote opens a scalar only where a scalar can start (it's, a"b are plain text).
      const char before = j == 0 ? ' ' : rest[j - 1];
      if ((d == '"' || d == '\'') &&
          (isBlank(before) || before == '[' || before == '{' || before == ',' || before == ':')) {
        quote = d;
      }
      if (d == '{' || d == '[') ++depth;
      if (d == '}' || d == ']') {
        if (--depth == 0) break;
      }
    }
    if (j == rest.size()) parseError(line, "unclosed '" + std::string(1, c) + "'");
    e->kind = FlatYamlEntry::kNested;
    e->text = std::string(rest.substr(0, j + 1));
    return i + j + 1;
  }
  if (c == '|' || c == '>') {
    e->kind = FlatYamlEntry::kString;  // block scalar: its indented lines follow
    e->text = std::string(trim(rest));
    return s.size();
  }
  std::size_t j = 0;
  while (j < rest.size() && stop.find(rest[j]) == std::string_view::npos) ++j;
  resolvePlain(trim(rest.substr(0, j)), e);
  if (!other_tag.empty() && e->kind != FlatYamlEntry::kNull) {
    e->kind = FlatYamlEntry::kString;  // e.g. !degrees 90: not converted, so not a number
    e->text = other_tag + " " + e->text;
  }
  return i + j;
}

// Position of the key's ':' (followed by a blank or the end) in a plain key, or npos.
std::size_t plainKeyColon(std::string_view s) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == ':' && (i + 1 == s.size() || isBlank(s[i + 1]))) return i;
  }
  return std::string_view::npos;
}

std::vector<FlatYamlEntry> parseFlow(std::string_view text, int first_line) {
  // Comments are removed line by line first; then the map is read as one stream.
  std::string flat;
  std::vector<int> line_of;  // source line of each character of `flat`
  int line = first_line;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view l = stripComment(text.substr(start, end - start));
    flat.append(l.data(), l.size());
    flat.push_back(' ');
    line_of.insert(line_of.end(), l.size() + 1, line);
    ++line;
    start = end + 1;
  }
  std::string_view s(flat);
  std::size_t i = 0;
  auto skipBlank = [&] {
    while (i < s.size() && (isBlank(s[i]) || s[i] == '\r')) ++i;
  };
  auto lineAt = [&](std::size_t k) { return line_of.empty() ? first_line : line_of[std::min(k, line_of.size() - 1)]; };
  std::vector<FlatYamlEntry> entries;
  skipBlank();
  if (i >= s.size() || s[i] != '{') parseError(lineAt(i), "expected '{'");
  ++i;
  bool closed = false;
  while (true) {
    skipBlank();
    if (i >= s.size()) break;
    if (s[i] == '}') {
      ++i;
      closed = true;
      break;
    }
    FlatYamlEntry e;
    e.line = lineAt(i);
    if (s[i] == '"' || s[i] == '\'') {
      if (!readQuoted(s, &i, &e.key)) parseError(e.line, "unterminated quoted key");
      skipBlank();
      if (i >= s.size() || s[i] != ':') parseError(e.line, "expected ':' after the key");
      ++i;
    } else {
      std::size_t k = i;
      while (k < s.size() && s[k] != ':' && s[k] != ',' && s[k] != '}') ++k;
      if (k >= s.size() || s[k] != ':') parseError(e.line, "expected 'name: value' in the map");
      e.key = std::string(trim(s.substr(i, k - i)));
      i = k + 1;
    }
    if (e.key.empty()) parseError(e.line, "empty parameter name");
    i += readValue(s.substr(i), ",}", &e, e.line);
    entries.push_back(std::move(e));
    skipBlank();
    if (i < s.size() && s[i] == ',') {
      ++i;
      continue;
    }
    if (i < s.size() && s[i] == '}') continue;
    if (i < s.size()) parseError(lineAt(i), "expected ',' or '}'");
  }
  if (!closed) parseError(lineAt(s.size()), "unclosed '{'");
  skipBlank();
  if (s.substr(i, 3) == "...") {  // a document end marker may follow
    i += 3;
    skipBlank();
  }
  if (i < s.size()) parseError(lineAt(i), "text after the closing '}'");
  return entries;
}

}  // namespace

std::vector<FlatYamlEntry> parseFlatYaml(const std::string& input) {
  // Old Mac line ends (CR only) become LF; CRLF is handled per line.
  std::string storage;
  std::string_view text(input);
  if (text.find('\n') == std::string_view::npos && text.find('\r') != std::string_view::npos) {
    storage = input;
    std::replace(storage.begin(), storage.end(), '\r', '\n');
    text = storage;
  }
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte order mark
  std::vector<FlatYamlEntry> entries;
  bool content = false;  // a key or the flow map has been seen
  // What indented lines after the last key mean: nothing (an error), its value (it was
  // empty: `k:` then `  1.5`), a continued plain scalar, a block scalar's text, or a nested
  // collection (ignored by the caller with a message).
  enum class Tail { kNone, kEmpty, kPlain, kBlock, kNested } tail = Tail::kNone;
  int line = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view raw = text.substr(start, end - start);
    const std::size_t line_start = start;
    start = end + 1;
    ++line;
    std::string_view l = stripComment(raw);
    while (!l.empty() && (isBlank(l.back()) || l.back() == '\r')) l.remove_suffix(1);
    if (trim(l).empty()) continue;
    if (l.front() == '%') continue;  // directive (%YAML 1.1, %TAG)
    // Document markers: rosparam loads every document of a file into the same namespace, so
    // later documents add to (and override) the earlier ones here too.
    if (l == "..." || l.substr(0, 4) == "... ") {
      tail = Tail::kNone;
      continue;
    }
    if (l.substr(0, 3) == "---" && (l.size() == 3 || isBlank(l[3]))) {
      tail = Tail::kNone;
      l = trim(l.substr(3));
      if (l.empty()) continue;
    }
    const std::size_t indent = l.find_first_not_of(" \t");
    const std::string_view body = trim(l);
    const bool list_item = body.substr(0, 2) == "- " || body == "-";
    if (indent > 0 || list_item) {
      if (!entries.empty()) {
        FlatYamlEntry& last = entries.back();
        if (tail == Tail::kEmpty) {
          if (indent > 0 && !list_item && plainKeyColon(body) == std::string_view::npos &&
              std::string_view("[{\"'|>&!*").find(body.front()) == std::string_view::npos) {
            resolvePlain(body, &last);  // `k:` then an indented scalar is `k: scalar`
            tail = Tail::kPlain;
          } else {
            last.kind = FlatYamlEntry::kNested;
            tail = Tail::kNested;
          }
          continue;
        }
        if (tail == Tail::kPlain && indent > 0 && !list_item &&
            plainKeyColon(body) == std::string_view::npos) {
          last.kind = FlatYamlEntry::kString;  // a plain scalar over several lines: folded text
          last.text += " " + std::string(body);
          continue;
        }
        if (tail == Tail::kBlock || tail == Tail::kNested) continue;
      }
      if (!content && list_item) {
        parseError(line, "expected a map of parameter names to values, found a list");
      }
      parseError(line, "unexpected indentation (parameter files are flat 'name: value' maps)");
    }
    if (!content && (l.front() == '{')) {
      return parseFlow(text.substr(line_start + (l.data() - raw.data())), line);
    }
    if (l.front() == '[') {
      parseError(line, "expected a map of parameter names to values, found a list");
    }
    if (l.front() == '{' || l.front() == '}' || l.front() == ']' || l.front() == ',') {
      parseError(line, "unexpected '" + std::string(1, l.front()) + "'");
    }
    FlatYamlEntry e;
    e.line = line;
    std::size_t after_colon;
    if (l.front() == '"' || l.front() == '\'') {
      std::size_t pos = 0;
      if (!readQuoted(l, &pos, &e.key)) parseError(line, "unterminated quoted name");
      while (pos < l.size() && isBlank(l[pos])) ++pos;
      if (pos >= l.size() || l[pos] != ':') parseError(line, "expected ':' after the name");
      after_colon = pos + 1;
    } else {
      const std::size_t colon = plainKeyColon(l);
      if (colon == std::string_view::npos) parseError(line, "expected 'name: value'");
      e.key = std::string(trim(l.substr(0, colon)));
      after_colon = colon + 1;
    }
    if (e.key.empty()) parseError(line, "empty parameter name");
    const std::string_view value = l.substr(after_colon);
    const std::size_t used = readValue(value, "", &e, line);
    if (!trim(value.substr(used)).empty()) {
      parseError(line, "unexpected text after the value of '" + e.key + "'");
    }
    const char first = trim(value).empty() ? '\0' : trim(value).front();
    if (e.kind == FlatYamlEntry::kNull && first == '\0') {
      tail = Tail::kEmpty;
    } else if (first == '|' || first == '>') {
      tail = Tail::kBlock;
    } else if (e.kind == FlatYamlEntry::kNested) {
      tail = Tail::kNested;
    } else if (first == '"' || first == '\'') {
      tail = Tail::kNone;
    } else {
      tail = Tail::kPlain;
    }
    entries.push_back(std::move(e));
    content = true;
  }
  return entries;
}

}  // namespace core
}  // namespace obstacle_tracker
