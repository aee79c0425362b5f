// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Obstacle models for the scene generator: fixed-wing aircraft, multirotors and birds built from
// flat 3-D plates (fuselage side and top profiles, wings, rotor disks...). Any view of the union
// of the plates is a plausible silhouette (head-on aircraft: a thin wing line with the fuselage
// disc; side view: fuselage, fin and edge-on wings), so planar and out-of-plane rotation come for
// free. Each plate is shaded from its normal and a sun direction and carries a colour and a
// thermal value (16-bit counts) for the thermal mode.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "obstacle_tracker/scene/random.h"

namespace obstacle_tracker {
namespace scene {

enum class ObstacleClass { kFixedWing, kMultirotor, kBird };
const char* toString(ObstacleClass c);

struct Material {
  cv::Vec3f bgr{128.0f, 128.0f, 128.0f};  // 0..255
  float thermal = 9000.0f;                 // 16-bit counts in the thermal mode
};

// A flat polygon in body coordinates: x forward (nose), y up, z right. Model units: the largest
// dimension of the model is about 1.
struct Plate {
  std::vector<cv::Point3f> pts;
  Material mat;
  float alpha = 1.0f;  // < 1: translucent (spinning rotor disc)
  int flap = 0;        // +1 / -1: a wing that rotates by +-flap about the body x axis through hinge
  cv::Point3f hinge{0.0f, 0.0f, 0.0f};
};

struct ShapeModel {
  ObstacleClass cls = ObstacleClass::kFixedWing;
  std::vector<Plate> plates;
  float size_m = 1.0f;  // physical length of one model unit (wingspan / diagonal), metres
};

// Models with per-seed variations (colours, proportions).
ShapeModel makeFixedWing(Rng& rng);
ShapeModel makeMultirotor(Rng& rng);
ShapeModel makeBird(Rng& rng);
ShapeModel makeModel(ObstacleClass c, Rng& rng);

// Where and how an obstacle is seen in one frame. Angles in radians.
struct Pose {
  cv::Point2f centre;      // image position of the body origin, pixels
  float scale = 10.0f;     // pixels per model unit
  float yaw = 0.0f;        // about the up axis: 0 = nose to the right, pi/2 = nose at the camera
  float elevation = 0.0f;  // view angle: < 0 the camera looks up at the underside
  float bank = 0.0f;       // about the body x axis
  float roll = 0.0f;       // planar rotation in the image, counter-clockwise
  float flap = 0.0f;       // wing flap angle (birds)
};

struct ProjectedPlate {
  std::vector<cv::Point2f> pts;  // image coordinates (pixel-edge convention of raster.h)
  float depth = 0.0f;            // larger = nearer the camera
  cv::Vec3f bgr;                 // shaded colour at the plate centroid
  float thermal = 0.0f;          // shaded thermal value
  cv::Point2f centroid;
  cv::Point2f gradient;          // relative shading change per pixel (colour *= 1 + g.(p - centroid))
  float alpha = 1.0f;
};

// Projects every plate (weak perspective), shades it, and sorts far to near. `out` is reused.
void projectShape(const ShapeModel& model, const Pose& pose, std::vector<ProjectedPlate>& out);

// Bounding box of projected plates (pixel-edge coordinates); empty rect when none.
cv::Rect2f projectedBounds(const std::vector<ProjectedPlate>& plates);

}  // namespace scene
}  // namespace obstacle_tracker
