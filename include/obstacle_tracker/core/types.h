// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <limits>

#include <opencv2/core/types.hpp>

namespace obstacle_tracker {
namespace core {

// Life of a track. The values match the constants of
// msg/Obstacle.msg.
enum class TrackState : std::uint8_t {
  kSearching = 0,    // no track: whole-frame saliency every detection_interval frames
  kTracking = 1,     // the filter's peak is above peak_threshold
  kRedetecting = 2,  // peak fell below: saliency inside the search window around the last box
  kLost = 3,         // max_redetect_failures re-detections failed; the track ends
};

const char* toString(TrackState state);

// One obstacle as the pipeline reports it for one frame.
// Highest confidence an unconfirmed obstacle is reported with (Obstacle::confirmed).
constexpr float kUnconfirmedConfidenceCap = 0.49f;

struct Obstacle {
  int id = -1;                    // stable for the life of a track
  cv::Rect2f box;                 // pixels, top-left corner and size, in the input frame
  float confidence = 0.0f;        // [0, 1]; mapping from peak and PSR documented in kcf.h
  float peak = 0.0f;              // raw maximum of the correlation response
  float psr = 0.0f;               // peak-to-sidelobe ratio of the response
  TrackState state = TrackState::kSearching;
  // Looming (looming.h): the expansion rate d ln(sqrt(w*h)) / dt and
  // the time to contact 1 / expansion_rate, each with its standard deviation.
  double expansion_rate = 0.0;        // 1/s (positive when growing)
  double expansion_rate_sigma = 0.0;  // 1/s
  double time_to_contact = std::numeric_limits<double>::infinity();        // s; +inf when not closing
  double time_to_contact_sigma = std::numeric_limits<double>::infinity();  // s; +inf when not closing
  int age = 0;                    // frames since the track started
  bool model_updated = false;     // the filter learned from this frame (false under occlusion)
  // False while an auto-started track, or one re-acquired on its contrast alone, has not shown
  // itself an obstacle (moved against the background, or grown); its confidence is then below
  // kUnconfirmedConfidenceCap, so that a planner acting on confidence >= 0.5 never acts on an
  // on-screen overlay or a mast.
  bool confirmed = true;
};

}  // namespace core
}  // namespace obstacle_tracker
