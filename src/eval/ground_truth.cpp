// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Ground-truth files (one box per line, 4 numbers x,y,w,h or 8 polygon corners) and tracker box
// files (x,y,w,h[,confidence[,time_to_contact]]): one tokenizer for both; the rules are in
// sequence.h.
#include "obstacle_tracker/eval/sequence.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace obstacle_tracker {
namespace eval {

namespace {

bool isSeparator(char c) { return c == ',' || c == ';' || c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

// Splits on any run of separators; returns false when a token is not a number.
bool parseNumbers(const std::string& line, std::vector<double>* values) {
  values->clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && isSeparator(line[i])) ++i;
    if (i >= n) break;
    std::size_t j = i;
    while (j < n && !isSeparator(line[j])) ++j;
    const std::string token = line.substr(i, j - i);
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') return false;
    values->push_back(v);
    i = j;
  }
  return true;
}

bool isBlank(const std::string& line) {
  return std::all_of(line.begin(), line.end(), [](char c) { return isSeparator(c); });
}

// A directory opens as a stream that reads nothing, which would pass for an empty file.
std::ifstream openTextFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  std::ifstream in;
  if (!std::filesystem::is_directory(path, ec)) in.open(path);
  if (!in.is_open()) throw std::runtime_error("cannot open " + what + " '" + path + "'");
  return in;
}

}  // namespace

bool parseGroundTruthLine(const std::string& line, cv::Rect2f* box) {
  std::vector<double> v;
  if (isBlank(line)) {
    *box = cv::Rect2f();
    return true;
  }
  if (!parseNumbers(line, &v)) return false;
  cv::Rect2f r;
  if (v.size() == 4) {
    for (double x : v) {
      if (!std::isfinite(x)) {
        *box = cv::Rect2f();
        return true;
      }
    }
    r = cv::Rect2f(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]),
                   static_cast<float>(v[3]));
  } else if (v.size() == 8) {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (int k = 0; k < 4; ++k) {
      if (!std::isfinite(v[2 * k]) || !std::isfinite(v[2 * k + 1])) {
        *box = cv::Rect2f();
        return true;
      }
      x0 = std::min(x0, v[2 * k]);
      x1 = std::max(x1, v[2 * k]);
      y0 = std::min(y0, v[2 * k + 1]);
      y1 = std::max(y1, v[2 * k + 1]);
    }
    r = cv::Rect2f(static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(x1 - x0),
                   static_cast<float>(y1 - y0));
  } else {
    return false;
  }
  *box = isPresent(r) ? r : cv::Rect2f();
  return true;
}

std::vector<cv::Rect2f> parseGroundTruth(std::istream& in, const std::string& source) {
  std::vector<cv::Rect2f> boxes;
  std::string line;
  int line_no = 0;
  int trailing_blank = 0;
  while (std::getline(in, line)) {
    ++line_no;
    cv::Rect2f box;
    if (!parseGroundTruthLine(line, &box)) {
      if (line_no == 1) continue;  // a header such as "x,y,w,h"
      throw std::runtime_error(source + ":" + std::to_string(line_no) +
                               ": not a box (expected 4 numbers x,y,w,h or 8 polygon corners): '" +
                               line.substr(0, 80) + "'");
    }
    trailing_blank = isBlank(line) ? trailing_blank + 1 : 0;
    boxes.push_back(box);
  }
  boxes.resize(boxes.size() - static_cast<std::size_t>(trailing_blank));
  return boxes;
}

std::vector<cv::Rect2f> loadGroundTruth(const std::string& path) {
  std::ifstream in = openTextFile(path, "ground-truth file");
  return parseGroundTruth(in, path);
}

TrackerBoxes parseTrackerBoxes(std::istream& in, const std::string& source) {
  TrackerBoxes out;
  std::string line;
  std::vector<double> v;
  int line_no = 0;
  int blank_run = 0;  // blank lines not yet known to be trailing
  while (std::getline(in, line)) {
    ++line_no;
    if (isBlank(line)) {
      ++blank_run;
      continue;
    }
    const auto fail = [&](const std::string& why) {
      return std::runtime_error(source + ":" + std::to_string(line_no) + ": " + why + ": '" +
                                line.substr(0, 80) + "'");
    };
    if (blank_run > 0) {
      throw std::runtime_error(source + ":" + std::to_string(line_no - blank_run) +
                               ": blank line (a tracker box file has a line for every frame)");
    }
    if (!parseNumbers(line, &v) || v.size() < 4 || v.size() > 6) {
      throw fail("not a tracker box (expected x,y,w,h[,confidence[,time_to_contact]])");
    }
    const float confidence = v.size() > 4 ? static_cast<float>(v[4]) : 1.0f;
    if (!std::isfinite(confidence)) throw fail("the confidence is not a finite number");
    const cv::Rect2f r(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]),
                       static_cast<float>(v[3]));
    const bool finite = std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.width) &&
                        std::isfinite(r.height);
    out.boxes.push_back(finite && isPresent(r) ? r : cv::Rect2f());
    out.confidence.push_back(confidence);
  }
  return out;
}

TrackerBoxes loadTrackerBoxes(const std::string& path) {
  std::ifstream in = openTextFile(path, "box file");
  return parseTrackerBoxes(in, path);
}

}  // namespace eval
}  // namespace obstacle_tracker
