// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// MbdSaliency (mbd_saliency.h): the MBD saliency map of an image by FastMBD (mbd.h; Zhang et al.,
// "Minimum Barrier Salient Object Detection at 80 FPS", ICCV 2015) on Lab (colour) or grey
// (thermal), optionally with MB+'s backgroundness map and its smoothing and contrast stretch.
#include "obstacle_tracker/core/mbd_saliency.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/frame_check.h"
#include "obstacle_tracker/core/mbd.h"

namespace obstacle_tracker {
namespace core {

namespace {

// Morphological reconstruction by dilation of `marker` under `mask` (both CV_8U, marker <= mask),
// in place, by Vincent's sequential raster algorithm (IEEE TIP 1993): alternate forward and
// backward 8-connected passes until nothing changes (bounded; like FastMBD, a few passes suffice).
void reconstructByDilation(cv::Mat& marker, const cv::Mat& mask, int max_passes = 8) {
  const int rows = marker.rows, cols = marker.cols;
  for (int p = 0; p < max_passes; ++p) {
    bool changed = false;
    const bool forward = (p % 2) == 0;
    for (int i = 0; i < rows; ++i) {
      const int r = forward ? i : rows - 1 - i;
      const int rn = forward ? r - 1 : r + 1;
      uchar* j = marker.ptr<uchar>(r);
      const uchar* m = mask.ptr<uchar>(r);
      const uchar* jn = (rn >= 0 && rn < rows) ? marker.ptr<uchar>(rn) : nullptr;
      for (int k = 0; k < cols; ++k) {
        const int c = forward ? k : cols - 1 - k;
        const int cp = forward ? c - 1 : c + 1;
        uchar v = j[c];
        if (cp >= 0 && cp < cols) v = std::max(v, j[cp]);
        if (jn) {
          v = std::max(v, jn[c]);
          if (c > 0) v = std::max(v, jn[c - 1]);
          if (c + 1 < cols) v = std::max(v, jn[c + 1]);
        }
        v = std::min(v, m[c]);
        if (v != j[c]) {
          j[c] = v;
          changed = true;
        }
      }
    }
    if (!changed && p > 0) break;
  }
}

}  // namespace

void MbdSaliency::compute(const cv::Mat& image, const SaliencyParams& params, cv::Mat& out) {
  requireFrame(image, "MbdSaliency::compute");
  const int rows = image.rows, cols = image.cols, cn = image.channels();
  cv::Mat src = image;
  if (cn == 3) {
    cv::Mat lab = lab_.get(rows, cols, CV_8UC3);
    cv::cvtColor(image, lab, cv::COLOR_BGR2Lab);
    src = lab;
  }
  if (params.saliency_median >= 3) {
    cv::Mat med = median_.get(rows, cols, src.type());
    cv::medianBlur(src, med, params.saliency_median | 1);
    src = med;
  }
  cv::Mat dist = dist_.get(rows, cols, src.type());
  cv::Mat upper = upper_.get(rows, cols, src.type());
  cv::Mat lower = lower_.get(rows, cols, src.type());
  fastMbd(src, params.saliency_passes, dist, upper, lower);

  // Sum of the per-channel maps, max-normalised to 0..255 (MB+ sums the Lab channel maps).
  const bool use_float = cn == 3 || params.saliency_backgroundness;  // sums reach 765
  if (!use_float) {
    double mx = 0.0;
    cv::minMaxLoc(dist, nullptr, &mx);
    const int peak = static_cast<int>(mx);
    if (peak > 0)
      dist.convertTo(out, CV_8U, 255.0 / peak);
    else
      out.setTo(0);
  } else {
    cv::Mat f = fmap_.get(rows, cols, CV_32F);
    sumChannels(dist, cn, f);
    if (params.saliency_backgroundness && rows >= 4 && cols >= 4) addBackgroundness(src, f);
    f.convertTo(out, CV_8U, 255.0);
  }
  if (params.saliency_postprocess) postprocess(out);
}

// The per-channel MBD maps summed (MB+ sums the Lab channel maps) into f, max-normalised to 0..1.
void MbdSaliency::sumChannels(const cv::Mat& dist, int cn, cv::Mat& f) {
  const int rows = dist.rows, cols = dist.cols;
  float fmax = 0.0f;
  for (int r = 0; r < rows; ++r) {
    const uchar* d = dist.ptr<uchar>(r);
    float* o = f.ptr<float>(r);
    if (cn == 3) {
      for (int c = 0; c < cols; ++c) {
        o[c] = static_cast<float>(d[3 * c] + d[3 * c + 1] + d[3 * c + 2]);
        fmax = std::max(fmax, o[c]);
      }
    } else {
      for (int c = 0; c < cols; ++c) {
        o[c] = d[c];
        fmax = std::max(fmax, o[c]);
      }
    }
  }
  if (fmax > 0.0f) f *= 1.0f / fmax;
}

// MB+ backgroundness (Zhang et al. 2015, Sec. 4) added to f, then f max-normalised again.
void MbdSaliency::addBackgroundness(const cv::Mat& src, cv::Mat& f) {
  const int rows = src.rows, cols = src.cols, cn = src.channels();
  // Colour distance of every pixel to each of
  // the four 10 % border strips, whitened by the strip's covariance; each map normalised; the
  // four summed minus the largest (one border may hold the object).
  const int th = std::max(1, rows / 10), tw = std::max(1, cols / 10);
  const cv::Rect strips[4] = {cv::Rect(0, 0, cols, th), cv::Rect(0, rows - th, cols, th),
                              cv::Rect(0, 0, tw, rows), cv::Rect(cols - tw, 0, tw, rows)};
  cv::Mat bg = fbg_.get(rows, cols, CV_32FC4);
  float maxes[4] = {0, 0, 0, 0};
  for (int s = 0; s < 4; ++s) {
    cv::Matx33d cov = cv::Matx33d::zeros();
    cv::Vec3d mean(0, 0, 0);
    const cv::Mat strip = src(strips[s]);
    const double n = static_cast<double>(strips[s].area());
    for (int r = 0; r < strip.rows; ++r) {
      const uchar* p = strip.ptr<uchar>(r);
      for (int c = 0; c < strip.cols; ++c)
        for (int k = 0; k < cn; ++k) mean[k] += p[c * cn + k];
    }
    mean *= 1.0 / n;
    for (int r = 0; r < strip.rows; ++r) {
      const uchar* p = strip.ptr<uchar>(r);
      for (int c = 0; c < strip.cols; ++c)
        for (int a = 0; a < cn; ++a)
          for (int b = 0; b < cn; ++b)
            cov(a, b) += (p[c * cn + a] - mean[a]) * (p[c * cn + b] - mean[b]);
    }
    cov *= 1.0 / n;
    for (int k = 0; k < 3; ++k) cov(k, k) += (k < cn) ? 1.0 : 1.0;  // regulariser, 1 level^2
    const cv::Matx33d inv = cov.inv(cv::DECOMP_CHOLESKY);
    for (int r = 0; r < rows; ++r) {
      const uchar* p = src.ptr<uchar>(r);
      cv::Vec4f* o = bg.ptr<cv::Vec4f>(r);
      for (int c = 0; c < cols; ++c) {
        double v[3] = {0, 0, 0};
        for (int k = 0; k < cn; ++k) v[k] = p[c * cn + k] - mean[k];
        double q = 0.0;
        for (int a = 0; a < cn; ++a)
          for (int b = 0; b < cn; ++b) q += v[a] * inv(a, b) * v[b];
        const float d = static_cast<float>(std::sqrt(std::max(0.0, q)));
        o[c][s] = d;
        maxes[s] = std::max(maxes[s], d);
      }
    }
  }
  float bmax = 0.0f;
  cv::Mat b = tmp_a_.get(rows, cols, CV_32F);
  for (int r = 0; r < rows; ++r) {
    const cv::Vec4f* o = bg.ptr<cv::Vec4f>(r);
    float* q = b.ptr<float>(r);
    for (int c = 0; c < cols; ++c) {
      float sum = 0.0f, mx = 0.0f;
      for (int s = 0; s < 4; ++s) {
        const float v = maxes[s] > 0.0f ? o[c][s] / maxes[s] : 0.0f;
        sum += v;
        mx = std::max(mx, v);
      }
      q[c] = sum - mx;
      bmax = std::max(bmax, q[c]);
    }
  }
  if (bmax > 0.0f) f += b * (1.0f / bmax);
  double m2 = 0.0;
  cv::minMaxLoc(f, nullptr, &m2);
  const float fmax = static_cast<float>(m2);
  if (fmax > 0.0f) f *= 1.0f / fmax;
}

void MbdSaliency::postprocess(cv::Mat& out) {
  const int rows = out.rows, cols = out.cols;
  // MB+ smoothing: opening then closing by reconstruction with a square of side
  // 50 * sqrt(mean saliency) (at 300 px; scaled with the map size), then a sigmoid contrast
  // stretch S' = 1 / (1 + exp(-10 (S - t))) around t = midpoint of the mean saliencies above
  // and below half the maximum.
  const double mean = cv::mean(out)[0] / 255.0;
  const int side = std::max(1, static_cast<int>(std::lround(50.0 * std::sqrt(mean) *
                                                            std::max(rows, cols) / 300.0)));
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(side, side));
  cv::Mat a = tmp_b_.get(rows, cols, CV_8U);
  cv::erode(out, a, kernel);
  reconstructByDilation(a, out);  // opening by reconstruction
  // Closing by reconstruction = complement of the opening by reconstruction of the complement.
  cv::bitwise_not(a, a);
  cv::erode(a, out, kernel);
  reconstructByDilation(out, a);
  cv::bitwise_not(out, out);
  double mx = 0.0;
  cv::minMaxLoc(out, nullptr, &mx);
  if (mx > 0.0) {
    double hi = 0.0, lo = 0.0;
    long nh = 0, nl = 0;
    for (int r = 0; r < rows; ++r) {
      const uchar* p = out.ptr<uchar>(r);
      for (int c = 0; c < cols; ++c) {
        if (p[c] > mx / 2) {
          hi += p[c];
          ++nh;
        } else {
          lo += p[c];
          ++nl;
        }
      }
    }
    const double t = 0.5 * ((nh ? hi / nh : mx) + (nl ? lo / nl : 0.0)) / mx;
    // Normalised so the maximum stays 255.
    const double top = 1.0 / (1.0 + std::exp(-10.0 * (1.0 - t)));
    uchar lut[256];
    for (int v = 0; v < 256; ++v)
      lut[v] = cv::saturate_cast<uchar>(255.0 / (1.0 + std::exp(-10.0 * (v / mx - t))) / top);
    for (int r = 0; r < rows; ++r) {
      uchar* p = out.ptr<uchar>(r);
      for (int c = 0; c < cols; ++c) p[c] = lut[p[c]];
    }
  }
}

}  // namespace core
}  // namespace obstacle_tracker
