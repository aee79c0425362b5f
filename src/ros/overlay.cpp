// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/ros/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

namespace obstacle_tracker {
namespace bridge {

cv::Scalar stateColour(core::TrackState state) {
  switch (state) {
    case core::TrackState::kTracking: return cv::Scalar(0, 255, 0);
    case core::TrackState::kRedetecting: return cv::Scalar(0, 165, 255);
    case core::TrackState::kLost: return cv::Scalar(0, 0, 255);
    default: return cv::Scalar(255, 255, 0);
  }
}

namespace {
const char* shortState(core::TrackState state) {
  switch (state) {
    case core::TrackState::kTracking: return "TRK";
    case core::TrackState::kRedetecting: return "REDET";
    case core::TrackState::kLost: return "LOST";
    default: return "SRCH";
  }
}
}  // namespace

void drawOverlay(const cv::Mat& frame, const std::vector<core::Obstacle>& obstacles,
                 const std::string& status, cv::Mat& out) {
  if (frame.type() == CV_8UC1) {
    cv::cvtColor(frame, out, cv::COLOR_GRAY2BGR);
  } else {
    frame.copyTo(out);
  }
  // Line width and text size grow with the image so the overlay stays readable when rviz
  // shrinks a large frame.
  const int side = std::max(out.cols, out.rows);
  const int thickness = std::max(2, side / 240);
  const double font_scale = std::max(0.4, side / 1200.0);
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  for (const core::Obstacle& o : obstacles) {
    const cv::Scalar colour = stateColour(o.state);
    const cv::Rect box(cvRound(o.box.x), cvRound(o.box.y), std::max(1, cvRound(o.box.width)),
                       std::max(1, cvRound(o.box.height)));
    cv::rectangle(out, box, colour, thickness, cv::LINE_8);
    char label[96];
    std::snprintf(label, sizeof(label), "#%d %.2f %s%s", o.id, o.confidence, shortState(o.state),
                  o.confirmed ? "" : " unconfirmed");
    int baseline = 0;
    const cv::Size text = cv::getTextSize(label, font, font_scale, 1, &baseline);
    cv::Point origin(box.x, box.y - thickness - 2);
    if (origin.y - text.height < 0) origin.y = box.y + box.height + text.height + thickness + 2;
    cv::putText(out, label, origin, font, font_scale, colour, std::max(1, thickness / 2), cv::LINE_AA);
    if (std::isfinite(o.time_to_contact) && o.time_to_contact > 0.0) {
      std::snprintf(label, sizeof(label), "ttc %.1fs", o.time_to_contact);
      cv::putText(out, label, origin + cv::Point(0, -text.height - baseline - 2), font, font_scale,
                  colour, std::max(1, thickness / 2), cv::LINE_AA);
    }
  }
  if (!status.empty()) {
    int baseline = 0;
    const cv::Size text = cv::getTextSize(status, font, font_scale, 1, &baseline);
    cv::rectangle(out, cv::Rect(0, 0, text.width + 8, text.height + baseline + 8), cv::Scalar(0, 0, 0),
                  cv::FILLED);
    cv::putText(out, status, cv::Point(4, text.height + 4), font, font_scale, cv::Scalar(255, 255, 255),
                1, cv::LINE_AA);
  }
}

}  // namespace bridge
}  // namespace obstacle_tracker
