// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Finding a sequence's files on disk (sequence_files.h), and the rules sequence.h declares for
// image extensions, fps texts and which folders are sequences with a ground truth.
#include "sequence_files.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "obstacle_tracker/eval/sequence.h"

namespace fs = std::filesystem;

namespace obstacle_tracker {
namespace eval {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Natural order: runs of digits compare as numbers, the rest byte by byte.
bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool da = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
    const bool db = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
    if (da && db) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      std::size_t is = i, js = j;
      while (is + 1 < ie && a[is] == '0') ++is;  // skip leading zeros
      while (js + 1 < je && b[js] == '0') ++js;
      if (ie - is != je - js) return ie - is < je - js;
      const int c = a.compare(is, ie - is, b, js, je - js);
      if (c != 0) return c < 0;
      if (ie - i != je - j) return ie - i < je - j;  // more leading zeros first
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

bool hasVideoExtension(const std::string& path) {
  const std::string ext = lower(fs::path(path).extension().string());
  static const char* kExt[] = {".mp4", ".avi", ".mkv", ".mov", ".webm", ".m4v", ".mpg", ".mpeg", ".wmv", ".ts"};
  for (const char* e : kExt) {
    if (ext == e) return true;
  }
  return false;
}

// The files of dir (not hidden ones) whose path `wanted` accepts, in natural name order.
std::vector<std::string> listFiles(const fs::path& dir, bool (*wanted)(const std::string&)) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const std::string name = it->path().filename().string();
    // Hidden files are not frames (macOS writes ._NAME beside each file on exFAT drives).
    if (name.empty() || name[0] == '.') continue;
    if (wanted(it->path().string())) names.push_back(name);
  }
  std::sort(names.begin(), names.end(), naturalLess);
  std::vector<std::string> files;
  files.reserve(names.size());
  for (const auto& n : names) files.push_back((dir / n).string());
  return files;
}

std::vector<std::string> listImages(const fs::path& dir) { return listFiles(dir, hasImageExtension); }

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

double fpsFromFolder(const fs::path& dir) {
  for (const char* name : {"scene.yaml", "scene.yml", "scene.txt", "fps.txt"}) {
    const fs::path p = dir / name;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) continue;
    const std::string text = readText(p);
    double fps = parseFpsText(text);
    // fps.txt may hold a bare number instead of an `fps` entry.
    if (fps <= 0.0 && std::string(name) == "fps.txt") fps = parseFpsText("fps " + text);
    if (fps > 0.0) return fps;
  }
  return 0.0;
}

// The first of the names that is a file in dir; empty when none is.
std::string firstFileIn(const fs::path& dir, const std::vector<std::string>& names) {
  std::error_code ec;
  for (const std::string& name : names) {
    if (fs::is_regular_file(dir / name, ec)) return (dir / name).string();
  }
  return std::string();
}

}  // namespace

bool hasImageExtension(const std::string& path) {
  const std::string ext = lower(fs::path(path).extension().string());
  static const char* kExt[] = {".jpg", ".jpeg", ".png", ".bmp", ".tif", ".tiff", ".pgm",
                               ".ppm", ".pbm",  ".webp", ".jp2", ".exr", ".hdr"};
  for (const char* e : kExt) {
    if (ext == e) return true;
  }
  return false;
}

double parseFpsText(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::size_t i = 0;
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (lower(line.substr(i, 3)) != "fps") continue;
    i += 3;
    if (i < line.size() && (std::isalnum(static_cast<unsigned char>(line[i])) || line[i] == '_')) {
      continue;  // fps_something
    }
    while (i < line.size() && (line[i] == ':' || line[i] == '=' || line[i] == ' ' || line[i] == '\t' ||
                               line[i] == '"' || line[i] == '\'')) {
      ++i;
    }
    const char* start = line.c_str() + i;
    char* end = nullptr;
    const double v = std::strtod(start, &end);
    if (end != start && std::isfinite(v) && v > 0.0) return v;
  }
  return 0.0;
}

std::string sequenceFolderName(const fs::path& folder) {
  std::string name = fs::path(folder).lexically_normal().filename().string();
  if (name.empty() || name == ".") name = folder.lexically_normal().parent_path().filename().string();
  return name;
}

std::vector<std::string> listSequenceImages(const fs::path& folder, fs::path* image_folder) {
  std::error_code ec;
  const fs::path img_dir = folder / "img";
  if (fs::is_directory(img_dir, ec)) {
    std::vector<std::string> files = listImages(img_dir);
    if (!files.empty()) {
      *image_folder = img_dir;
      return files;
    }
  }
  *image_folder = folder;
  return listImages(folder);
}

std::vector<std::string> listFolderVideos(const fs::path& folder) {
  return listFiles(folder, hasVideoExtension);
}

double sequenceFolderFps(const fs::path& folder, const fs::path& image_folder) {
  double fps = fpsFromFolder(folder);
  if (fps <= 0.0 && image_folder != folder) fps = fpsFromFolder(image_folder);
  return fps;
}

double videoSceneFps(const fs::path& video) {
  const fs::path scene_dir = video.parent_path().empty() ? fs::path(".") : video.parent_path();
  double fps = 0.0;
  // generate_scene writes <stem>_scene.yaml beside a video.
  std::error_code ec;
  const fs::path side = scene_dir / (video.stem().string() + "_scene.yaml");
  if (fs::is_regular_file(side, ec)) fps = parseFpsText(readText(side));
  if (fps <= 0.0) fps = fpsFromFolder(scene_dir);
  return fps;
}

std::string folderGroundTruthFile(const fs::path& folder) {
  return firstFileIn(folder, {"groundtruth_rect.txt", "groundtruth.txt", "groundtruth_rect.1.txt"});
}

std::string videoGroundTruthFile(const fs::path& video) {
  const std::string stem = video.stem().string();
  return firstFileIn(video.parent_path(), {stem + "_groundtruth_rect.txt", stem + ".txt",
                                           stem + "_gt.txt", "groundtruth_rect.txt"});
}

bool folderHasGroundTruth(const std::string& folder) {
  const fs::path dir(folder);
  if (!folderGroundTruthFile(dir).empty()) return true;
  // Without a file of its own, only a folder that Sequence reads as one video has the video's.
  fs::path image_folder;
  if (!listSequenceImages(dir, &image_folder).empty()) return false;
  const std::vector<std::string> videos = listFolderVideos(dir);
  return videos.size() == 1 && !videoGroundTruthFile(videos.front()).empty();
}

std::vector<std::string> listSequences(const std::string& root, std::vector<std::string>* skipped) {
  std::vector<fs::path> dirs;
  std::error_code ec;
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code type_ec;  // a broken link is no folder, and does not end the listing
    if (!name.empty() && name[0] != '.' && it->is_directory(type_ec)) dirs.push_back(it->path());
  }
  std::sort(dirs.begin(), dirs.end());
  std::vector<std::string> sequences;
  for (const fs::path& dir : dirs) {
    if (folderHasGroundTruth(dir.string())) {
      sequences.push_back(dir.string());
    } else if (skipped) {
      skipped->push_back(dir.string());
    }
  }
  return sequences;
}

}  // namespace eval
}  // namespace obstacle_tracker
