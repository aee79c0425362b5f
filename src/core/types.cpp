// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/core/types.h"

namespace obstacle_tracker {
namespace core {

const char* toString(TrackState state) {
  switch (state) {
    case TrackState::kSearching:
      return "searching";
    case TrackState::kTracking:
      return "tracking";
    case TrackState::kRedetecting:
      return "redetecting";
    case TrackState::kLost:
      return "lost";
  }
  return "unknown";
}

}  // namespace core
}  // namespace obstacle_tracker
