// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/eval/sequence.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

namespace fs = std::filesystem;

namespace obstacle_tracker {
namespace eval {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

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

std::vector<std::string> listImages(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const std::string p = it->path().string();
    if (hasImageExtension(p)) names.push_back(it->path().filename().string());
  }
  std::sort(names.begin(), names.end(), naturalLess);
  std::vector<std::string> files;
  files.reserve(names.size());
  for (const auto& n : names) files.push_back((dir / n).string());
  return files;
}

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
    std::string text = readText(p);
    if (std::string(name) == "fps.txt") text = "fps " + text;  // a bare number
    const double fps = parseFpsText(text);
    if (fps > 0.0) return fps;
  }
  return 0.0;
}

// A robust [low, high] range from a histogram of integer values 0..65535.
void histogramRange(const std::vector<int>& hist, double total, double lo_pct, double hi_pct,
                    double* lo, double* hi) {
  const double lo_count = total * lo_pct / 100.0;
  const double hi_count = total * hi_pct / 100.0;
  double acc = 0.0;
  int l = -1, h = -1;
  for (int v = 0; v < static_cast<int>(hist.size()); ++v) {
    acc += hist[v];
    if (l < 0 && acc > lo_count) l = v;
    if (h < 0 && acc >= hi_count) {
      h = v;
      break;
    }
  }
  if (l < 0) l = 0;
  if (h < 0) h = static_cast<int>(hist.size()) - 1;
  *lo = l;
  *hi = h;
}

}  // namespace

// ---- Ground truth ------------------------------------------------------------------------------

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
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open ground-truth file '" + path + "'");
  return parseGroundTruth(in, path);
}

// ---- Frames ------------------------------------------------------------------------------------

FrameConverter::FrameConverter(double low_percent, double high_percent, double smoothing)
    : low_percent_(std::clamp(low_percent, 0.0, 100.0)),
      high_percent_(std::clamp(high_percent, 0.0, 100.0)),
      smoothing_(std::clamp(smoothing, 1e-6, 1.0)) {
  if (high_percent_ <= low_percent_) {
    throw std::invalid_argument("FrameConverter: high_percent must exceed low_percent");
  }
}

void FrameConverter::reset() {
  have_range_ = false;
  low_ = 0.0;
  high_ = 255.0;
}

const cv::Mat& FrameConverter::convert(const cv::Mat& in) {
  if (in.empty()) throw std::invalid_argument("FrameConverter: empty frame");
  const int ch = in.channels();
  if (ch < 1 || ch > 4) {
    throw std::invalid_argument("FrameConverter: unsupported channel count " + std::to_string(ch));
  }
  const int depth = in.depth();
  if (depth == CV_8U && (ch == 1 || ch == 3)) {
    out_ = in;
    return out_;
  }

  // Bring the channel layout to 1 or 3 first (at the input depth).
  const cv::Mat* src = &in;
  if (ch == 4) {
    cv::cvtColor(in, work_, cv::COLOR_BGRA2BGR);
    src = &work_;
  } else if (ch == 2) {
    cv::extractChannel(in, work_, 0);
    src = &work_;
  }
  if (depth == CV_8U) {
    if (src == &work_) {
      out_ = work_;  // already converted into our buffer
    } else {
      src->copyTo(out_);
    }
    return out_;
  }

  // Robust range of the values.
  double lo = 0.0, hi = 0.0;
  if (depth == CV_16U) {
    histogram_.assign(65536, 0);
    const int cols = src->cols * src->channels();
    for (int r = 0; r < src->rows; ++r) {
      const auto* p = src->ptr<std::uint16_t>(r);
      for (int c = 0; c < cols; ++c) ++histogram_[p[c]];
    }
    histogramRange(histogram_, static_cast<double>(src->total()) * src->channels(), low_percent_,
                   high_percent_, &lo, &hi);
  } else {
    // Other depths (8S, 16S, 32S, 32F, 64F): a strided sample of finite values.
    if (src->depth() == CV_32F) {
      float_ = *src;  // shallow; cloned below before any change
    } else {
      src->convertTo(float_, CV_MAKETYPE(CV_32F, src->channels()));
    }
    samples_.clear();
    const std::size_t n = float_.total() * float_.channels();
    const std::size_t step = std::max<std::size_t>(1, n / 65536);
    const int cols = float_.cols * float_.channels();
    std::size_t k = 0;
    bool non_finite = false;
    for (int r = 0; r < float_.rows; ++r) {
      const float* p = float_.ptr<float>(r);
      for (int c = 0; c < cols; ++c, ++k) {
        if (!std::isfinite(p[c])) {
          non_finite = true;
        } else if (k % step == 0) {
          samples_.push_back(p[c]);
        }
      }
    }
    if (!samples_.empty()) {
      auto pick = [&](double pct) {
        const std::size_t idx = std::min(
            samples_.size() - 1, static_cast<std::size_t>(pct / 100.0 * (samples_.size() - 1) + 0.5));
        std::nth_element(samples_.begin(), samples_.begin() + static_cast<long>(idx), samples_.end());
        return static_cast<double>(samples_[idx]);
      };
      lo = pick(low_percent_);
      hi = pick(high_percent_);
    }
    if (non_finite) {
      // NaN -> the low end; +-inf saturate in the conversion below.
      if (float_.data == in.data || float_.data == work_.data) float_ = float_.clone();
      cv::patchNaNs(float_, lo);
    }
    src = &float_;
  }
  if (have_range_) {
    low_ = (1.0 - smoothing_) * low_ + smoothing_ * lo;
    high_ = (1.0 - smoothing_) * high_ + smoothing_ * hi;
  } else {
    low_ = lo;
    high_ = hi;
    have_range_ = true;
  }
  const double span = std::max(high_ - low_, 1e-6);
  const double alpha = 255.0 / span;
  src->convertTo(out_, CV_MAKETYPE(CV_8U, src->channels()), alpha, -low_ * alpha);  // saturates
  return out_;
}

cv::Mat toCoreFrame(const cv::Mat& in) {
  FrameConverter conv;
  cv::Mat out = conv.convert(in);
  return out.data == in.data ? out : out.clone();
}

// ---- Sequences ---------------------------------------------------------------------------------

struct Sequence::Video {
  cv::VideoCapture cap;
};

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

Sequence::Sequence(const std::string& path, const std::string& ground_truth_path) : path_(path) {
  std::error_code ec;
  const fs::path p(path);
  std::string gt_file = ground_truth_path;
  if (fs::is_directory(p, ec)) {
    name_ = fs::path(p).lexically_normal().filename().string();
    if (name_.empty() || name_ == ".") name_ = p.lexically_normal().parent_path().filename().string();
    fs::path img_dir = p / "img";
    if (fs::is_directory(img_dir, ec) && !listImages(img_dir).empty()) {
      files_ = listImages(img_dir);
    } else {
      img_dir = p;
      files_ = listImages(p);
    }
    if (files_.empty()) throw std::runtime_error("no image files in '" + path + "'");
    if (gt_file.empty()) {
      for (const char* n : {"groundtruth_rect.txt", "groundtruth.txt", "groundtruth_rect.1.txt"}) {
        if (fs::is_regular_file(p / n, ec)) {
          gt_file = (p / n).string();
          break;
        }
      }
    }
    kind_ = gt_file.empty() ? Kind::kImageFolder : Kind::kOtbFolder;
    frame_count_ = static_cast<int>(files_.size());
    double f = fpsFromFolder(p);
    if (f <= 0.0 && img_dir != p) f = fpsFromFolder(img_dir);
    fps_ = f > 0.0 ? f : 30.0;
  } else if (fs::is_regular_file(p, ec)) {
    if (hasImageExtension(path)) {
      throw std::runtime_error("'" + path +
                               "' is a single image; give the folder that holds the sequence");
    }
    kind_ = Kind::kVideo;
    name_ = p.stem().string();
    video_ = std::make_unique<Video>();
    if (!video_->cap.open(path) || !video_->cap.isOpened()) {
      throw std::runtime_error("cannot open video '" + path + "'");
    }
    const double f = video_->cap.get(cv::CAP_PROP_FPS);
    const fs::path scene_dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    double fs_fps = 0.0;
    {
      // generate_scene writes <stem>_scene.yaml beside a video.
      std::error_code ec2;
      const fs::path side = scene_dir / (p.stem().string() + "_scene.yaml");
      if (fs::is_regular_file(side, ec2)) fs_fps = parseFpsText(readText(side));
      if (fs_fps <= 0.0) fs_fps = fpsFromFolder(scene_dir);
    }
    fps_ = (std::isfinite(f) && f > 0.0 && f < 1000.0) ? f : (fs_fps > 0.0 ? fs_fps : 30.0);
    const double n = video_->cap.get(cv::CAP_PROP_FRAME_COUNT);
    frame_count_ = (std::isfinite(n) && n > 0.0) ? static_cast<int>(n) : 0;
    if (gt_file.empty()) {
      const fs::path dir = p.parent_path();
      for (const std::string& n2 : {p.stem().string() + "_groundtruth_rect.txt", p.stem().string() + ".txt",
                                    p.stem().string() + "_gt.txt", std::string("groundtruth_rect.txt")}) {
        if (fs::is_regular_file(dir / n2, ec)) {
          gt_file = (dir / n2).string();
          break;
        }
      }
    }
  } else {
    throw std::runtime_error("'" + path + "' is neither a folder nor a file");
  }
  if (!gt_file.empty()) ground_truth_ = loadGroundTruth(gt_file);
}

Sequence::~Sequence() = default;

cv::Rect2f Sequence::groundTruthAt(int index) const {
  if (index < 0 || index >= static_cast<int>(ground_truth_.size())) return cv::Rect2f();
  return ground_truth_[static_cast<std::size_t>(index)];
}

bool Sequence::read(cv::Mat& frame) {
  if (kind_ == Kind::kVideo) {
    if (!video_->cap.read(frame) || frame.empty()) return false;
    ++position_;
    return true;
  }
  if (position_ >= static_cast<int>(files_.size())) return false;
  const std::string& file = files_[static_cast<std::size_t>(position_)];
  frame = cv::imread(file, cv::IMREAD_UNCHANGED);
  if (frame.empty()) throw std::runtime_error("cannot decode image '" + file + "'");
  ++position_;
  return true;
}

void Sequence::seek(int index) {
  if (index < 0 || (frame_count_ > 0 && index > frame_count_)) {
    throw std::out_of_range("Sequence::seek: frame " + std::to_string(index) + " outside [0, " +
                            std::to_string(frame_count_) + "]");
  }
  if (kind_ != Kind::kVideo) {
    position_ = index;
    return;
  }
  if (index < position_) {
    video_->cap.release();
    if (!video_->cap.open(path_)) throw std::runtime_error("cannot re-open video '" + path_ + "'");
    position_ = 0;
  }
  while (position_ < index) {
    if (!video_->cap.grab()) break;
    ++position_;
  }
}

}  // namespace eval
}  // namespace obstacle_tracker
