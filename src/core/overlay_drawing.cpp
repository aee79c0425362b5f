// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/overlay_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "obstacle_tracker/core/box_geometry.h"

namespace obstacle_tracker {
namespace core {

cv::Scalar stateColour(TrackState state) {
  switch (state) {
    case TrackState::kTracking: return cv::Scalar(0, 255, 0);
    case TrackState::kRedetecting: return cv::Scalar(0, 165, 255);
    case TrackState::kLost: return cv::Scalar(0, 0, 255);
    default: return cv::Scalar(255, 255, 0);
  }
}

namespace {

const char* shortState(TrackState state) {
  switch (state) {
    case TrackState::kTracking: return "TRK";
    case TrackState::kRedetecting: return "REDET";
    case TrackState::kLost: return "LOST";
    default: return "SRCH";
  }
}

// Line width and text size grow with the image so the overlay stays readable when rviz shrinks a
// large frame.
struct OverlayStyle {
  explicit OverlayStyle(const cv::Size& image)
      : thickness(std::max(2, std::max(image.width, image.height) / 240)),
        font_scale(std::max(0.4, std::max(image.width, image.height) / 1200.0)) {}
  int thickness;
  double font_scale;
  int font = cv::FONT_HERSHEY_SIMPLEX;
};

void drawObstacle(const Obstacle& o, const OverlayStyle& style, cv::Mat& out) {
  const cv::Scalar colour = stateColour(o.state);
  const cv::Rect box(cvRound(o.box.x), cvRound(o.box.y), std::max(1, cvRound(o.box.width)),
                     std::max(1, cvRound(o.box.height)));
  cv::rectangle(out, box, colour, style.thickness, cv::LINE_8);
  char label[96];
  std::snprintf(label, sizeof(label), "#%d %.2f %s%s", o.id, o.confidence, shortState(o.state),
                o.confirmed ? "" : " unconfirmed");
  int baseline = 0;
  const cv::Size text = cv::getTextSize(label, style.font, style.font_scale, 1, &baseline);
  cv::Point origin(box.x, box.y - style.thickness - 2);
  if (origin.y - text.height < 0) origin.y = box.y + box.height + text.height + style.thickness + 2;
  const int text_thickness = std::max(1, style.thickness / 2);
  cv::putText(out, label, origin, style.font, style.font_scale, colour, text_thickness, cv::LINE_AA);
  if (std::isfinite(o.time_to_contact) && o.time_to_contact > 0.0) {
    std::snprintf(label, sizeof(label), "ttc %.1fs", o.time_to_contact);
    cv::putText(out, label, origin + cv::Point(0, -text.height - baseline - 2), style.font, style.font_scale,
                colour, text_thickness, cv::LINE_AA);
  }
}

void drawStatus(const std::string& status, const OverlayStyle& style, cv::Mat& out) {
  int baseline = 0;
  const cv::Size text = cv::getTextSize(status, style.font, style.font_scale, 1, &baseline);
  cv::rectangle(out, cv::Rect(0, 0, text.width + 8, text.height + baseline + 8), cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(out, status, cv::Point(4, text.height + 4), style.font, style.font_scale, cv::Scalar(255, 255, 255),
              1, cv::LINE_AA);
}

}  // namespace

void drawOverlay(const cv::Mat& frame, const std::vector<Obstacle>& obstacles, const OverlayExtras& extras,
                 cv::Mat& out) {
  if (frame.type() == CV_8UC1) {
    cv::cvtColor(frame, out, cv::COLOR_GRAY2BGR);
  } else {
    frame.copyTo(out);
  }
  const OverlayStyle style(out.size());
  if (!boxIsAbsent(extras.ground_truth)) {
    // Beneath the obstacles and thinner, so a box on the ground truth still shows its state colour.
    const cv::Rect truth(cvRound(extras.ground_truth.x), cvRound(extras.ground_truth.y),
                         std::max(1, cvRound(extras.ground_truth.width)),
                         std::max(1, cvRound(extras.ground_truth.height)));
    cv::rectangle(out, truth, cv::Scalar(255, 255, 255), std::max(1, style.thickness / 2), cv::LINE_8);
  }
  for (const Obstacle& o : obstacles) drawObstacle(o, style, out);
  if (!extras.status.empty()) drawStatus(extras.status, style, out);
}

}  // namespace core
}  // namespace obstacle_tracker
