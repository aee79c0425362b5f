// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/scale_alignment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "obstacle_tracker/core/box_geometry.h"
#include "obstacle_tracker/core/image_pyramid.h"

namespace obstacle_tracker {
namespace core {

namespace {

constexpr double kMaxSigma = 0.05;        // ln units: a fit less certain than this is no measurement
constexpr double kMinResidualSigma = 1.0; // grey levels: quantisation, so a perfect fit has weights

// Level-l coordinate of a level-0 coordinate (2x2-mean pyramid, image_pyramid.h).
double toLevel(double v, int level) {
  for (int l = 0; l < level; ++l) v = (v + 0.5) * 0.5 - 0.5;
  return v;
}

// Median of v[0, n) (reorders v).
double medianOf(std::vector<float>& v, std::size_t n) {
  const std::size_t mid = n / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.begin() + static_cast<long>(n));
  return v[mid];
}

}  // namespace

ScaleEstimate ScaleAlignment::estimate(const cv::Mat& reference, const cv::Mat& current, const cv::Rect& region) {
  if (reference.type() != CV_8UC1 || current.type() != CV_8UC1 || reference.size() != current.size()) {
    throw std::invalid_argument("ScaleAlignment: two CV_8UC1 patches of the same size are needed");
  }
  ScaleEstimate out;
  if ((region & cv::Rect(0, 0, reference.cols, reference.rows)) != region || region.width < 4 ||
      region.height < 4) {
    return out;
  }
  reference.convertTo(levels_[0].ref, CV_32F);
  current.convertTo(levels_[0].cur, CV_32F);
  // Smoothing first widens the range over which the linearisation holds: a texture of 1-2 px
  // detail moves out of it at a few percent of scale, and the fit then stops short.
  binomialBlur(levels_[0].ref, blur_buffer_);
  binomialBlur(levels_[0].cur, blur_buffer_);
  for (int l = 1; l < kLevels; ++l) {
    halveImage(levels_[l - 1].ref, levels_[l].ref);
    halveImage(levels_[l - 1].cur, levels_[l].cur);
  }
  for (auto& lv : levels_) centralGradients(lv.ref, lv.grad_x, lv.grad_y);
  residuals_.reserve(static_cast<std::size_t>(region.area()));  // allocates once per patch size
  double a = 0.0;  // ln s
  cv::Point2d t(0.0, 0.0);
  double var_ls = 0.0;
  for (int l = kLevels - 1; l >= 0; --l) {
    const double x0 = toLevel(region.x, l), y0 = toLevel(region.y, l);
    const double x1 = toLevel(region.x + region.width - 1, l), y1 = toLevel(region.y + region.height - 1, l);
    const cv::Rect2f r(static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(x1 - x0),
                       static_cast<float>(y1 - y0));
    // The coarse level only has to bring the fine one into its range; the fine one must converge.
    if (!alignLevel(levels_[l], r, a, t, var_ls) && l == 0) return out;
    if (l > 0) t *= 2.0;
  }
  const double sigma = std::sqrt(var_ls);
  if (!(std::abs(a) <= kMaxLogScale) || !(sigma <= kMaxSigma)) return out;
  out.valid = true;
  out.log_scale = a;
  out.sigma = sigma;
  out.shift = cv::Point2f(static_cast<float>(t.x), static_cast<float>(t.y));
  return out;
}

// Gauss-Newton iterations on one level. W(x) = c + e^a (x - c) + t maps the reference region
// into the current patch; the inverse compositional step (Baker & Matthews eq. 31-35) linearises
// at the reference, whose steepest-descent images are [grad I . (x - c), I_x, I_y].
bool ScaleAlignment::alignLevel(const Level& lv, const cv::Rect2f& r, double& a, cv::Point2d& t, double& var_ls) {
  const cv::Point2d c = boxCentre(cv::Rect2d(r));
  const double cx = c.x, cy = c.y;
  const int xa = static_cast<int>(std::ceil(r.x)), xb = static_cast<int>(std::floor(r.x + r.width));
  const int ya = static_cast<int>(std::ceil(r.y)), yb = static_cast<int>(std::floor(r.y + r.height));
  double sigma_r = 0.0;  // robust residual scale of the previous iteration (0: none yet)
  bool converged = false;
  Eigen::Matrix3d h;
  for (int it = 0; it < kIterations; ++it) {
    const double s = std::exp(a);
    // The upper triangle of H and b, summed in double (a region has up to 128^2 pixels).
    double hss = 0.0, hsx = 0.0, hsy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0, bs = 0.0, bx = 0.0, by = 0.0;
    residuals_.clear();
    for (int y = ya; y <= yb; ++y) {
      const float* gx = lv.grad_x.ptr<float>(y);
      const float* gy = lv.grad_y.ptr<float>(y);
      const float* ref = lv.ref.ptr<float>(y);
      const float wy = static_cast<float>(cy + s * (y - cy) + t.y);
      const float dy = static_cast<float>(y - cy);
      for (int x = xa; x <= xb; ++x) {
        const float wx = static_cast<float>(cx + s * (x - cx) + t.x);
        if (!bilinearInside(lv.cur, wx, wy)) continue;
        const float e = bilinearAt(lv.cur, wx, wy) - ref[x];
        const float abs_e = std::abs(e);
        residuals_.push_back(abs_e);
        // Huber weight against the previous iteration's robust scale.
        const float w = sigma_r > 0.0 && abs_e > kHuber * sigma_r ? static_cast<float>(kHuber * sigma_r) / abs_e : 1.0f;
        const float sd_s = gx[x] * static_cast<float>(x - cx) + gy[x] * dy;  // steepest descent, scale
        const float wsx = w * gx[x], wsy = w * gy[x], wss = w * sd_s;
        hss += wss * sd_s;
        hsx += wss * gx[x];
        hsy += wss * gy[x];
        hxx += wsx * gx[x];
        hxy += wsx * gy[x];
        hyy += wsy * gy[x];
        bs += wss * e;
        bx += wsx * e;
        by += wsy * e;
      }
    }
    h << hss, hsx, hsy, hsx, hxx, hxy, hsy, hxy, hyy;
    const Eigen::Vector3d b(bs, bx, by);
    if (residuals_.size() < 16) return false;
    sigma_r = std::max(kMinResidualSigma, 1.4826 * medianOf(residuals_, residuals_.size()));
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(h);
    if (!lu.isInvertible()) return false;
    const Eigen::Vector3d dp = lu.solve(b);
    if (!dp.allFinite()) return false;
    // W(x; p) o W(x; dp)^-1: scale e^a / (1 + da), shift t - e^a dt / (1 + da).
    const double k = 1.0 + dp(0);
    if (!(k > 0.5)) return false;
    t.x -= s * dp(1) / k;
    t.y -= s * dp(2) / k;
    a -= std::log(k);
    if (std::abs(dp(0)) < kEpsilon && std::abs(dp(1)) < kShiftEpsilon && std::abs(dp(2)) < kShiftEpsilon) {
      converged = true;
      break;
    }
  }
  const Eigen::Matrix3d cov = h.inverse();
  var_ls = cov(0, 0) * sigma_r * sigma_r;
  return converged && std::isfinite(var_ls);
}

}  // namespace core
}  // namespace obstacle_tracker
