// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Every tunable of the pipeline, declared once. The list below is the single source of truth:
// the Params struct, the YAML loader, the range checks, the nodelet's ROS parameters and the
// dynamic_reconfigure config all use these names (test_params checks config/ObstacleTracker.cfg,
// config/defaults.yaml and the README table against it).
#pragma once

#include <string>
#include <vector>

namespace obstacle_tracker {
namespace core {

// X(type, name, default, min, max, unit, description)
// type is bool, int or double. min/max are inclusive; a value outside is clamped with a message,
// a NaN is refused (the old value stays) with a message.

// Closed loop.
#define OT_LOOP_PARAMS(X)                                                                          \
  X(double, peak_threshold, 0.10, 0.0, 1.0, "",                                                    \
    "raw KCF response peak below which the track re-detects (the paper's test)")                  \
  X(int, detection_interval, 1, 1, 1000, "frames",                                                 \
    "frames between whole-frame saliency searches while searching")                               \
  X(int, max_obstacles, 1, 1, 16, "", "tracks kept at once (1 = the paper's single-target loop)") \
  X(int, max_redetect_failures, 15, 0, 10000, "frames",                                            \
    "failed re-detections before a track is declared lost")                                       \
  X(double, merge_iou, 0.5, 0.0, 1.0, "", "tracks overlapping more than this IoU are merged")      \
  X(double, looming_rate_noise, 0.3, 0.0, 10.0, "1/s^1.5",                                        \
    "process noise of the expansion rate in the looming filter (how fast closing may change)")    \
  X(bool, looming_from_pixels, true, false, true, "",                                              \
    "measure the expansion by aligning the object's pixels between frames (else box sizes alone)") \
  X(double, collision_bearing_rate, 0.05, 0.0, 10.0, "rad/s",                                     \
    "a closing obstacle whose bearing turns slower than this is on a collision course (needs bearings)") \
  X(double, relative_peak_threshold, 0.4, 0.0, 1.0, "",                                            \
    "also re-detect when the peak falls below this fraction of the track's running mean peak")    \
  X(double, learn_relative_threshold, 0.7, 0.0, 1.0, "",                                           \
    "learn only when peak and PSR reach this fraction of their running means (0 = off)")          \
  X(int, redetect_candidates, 3, 1, 16, "",                                                        \
    "salient regions per re-detection verified against the filter model")                         \
  X(double, redetect_relative_threshold, 0.7, 0.0, 1.0, "",                                        \
    "a re-detected region's verification peak must reach this fraction of the running mean peak") \
  X(double, redetect_solo_peak, 0.5, 0.0, 1.0, "",                                                 \
    "after a failed frame, a salient region alone in the window needs this x peak_threshold (0 = off)")

// Saliency detector (FastMBD, Otsu, regions, auto-initialisation).
#define OT_SALIENCY_PARAMS(X)                                                                      \
  X(double, search_window_scale, 3.0, 1.0, 20.0, "x box",                                          \
    "side of the re-detection window as a multiple of the last box side")                         \
  X(double, min_object_area, 12.0, 1.0, 1.0e6, "px^2",                                             \
    "smallest salient region taken as an object (auto-init: px^2 at auto_init_max_width)")           \
  X(double, max_object_area_fraction, 0.25, 0.0001, 1.0, "",                                       \
    "largest salient region, as a fraction of the frame area")                                    \
  X(int, saliency_max_side, 300, 32, 4096, "px",                                                   \
    "longer side of the image the whole-frame saliency map is computed on")                       \
  X(int, saliency_passes, 3, 1, 10, "", "raster-scan passes of FastMBD")                           \
  X(int, saliency_median, 0, 0, 7, "px",                                                           \
    "median filter aperture applied before FastMBD (0 = off; MB+ uses 5)")                        \
  X(bool, saliency_backgroundness, false, false, true, "",                                         \
    "add MB+'s image-border contrast (backgroundness) map")                                       \
  X(bool, saliency_postprocess, false, false, true, "",                                            \
    "MB+ smoothing by morphological reconstruction and sigmoid contrast stretch")                 \
  X(bool, saliency_rank_by_area, false, false, true, "",                                           \
    "rank salient regions by area (the paper) instead of saliency mass (area x mean saliency)")  \
  X(bool, reject_border_regions, true, false, true, "",                                            \
    "ignore salient regions that touch the frame border")                                         \
  X(int, auto_init_frames, 8, 1, 100, "frames",                                                    \
    "frames a candidate must be seen before auto-initialisation confirms it (1 = single frame)")  \
  X(double, auto_init_min_motion, 4.0, 0.0, 1000.0, "px",                                          \
    "displacement against image and background needed to confirm, px at auto_init_max_width (0 = off)")\
  X(double, auto_init_min_growth, 0.2, 0.0, 10.0, "",                                              \
    "or steady growth of ln(size) over the candidate's history (collision course; 0 = cue off)")  \
  X(bool, auto_init_local_contrast, true, false, true, "",                                         \
    "auto-init candidates from local contrast x MBD, and isolated ones of the contrast (false: MBD alone)") \
  X(int, auto_init_candidates, 24, 1, 64, "",                                                      \
    "candidate map peaks examined per frame by auto-initialisation (besides 8 isolated ones)")    \
  X(int, auto_init_max_width, 640, 64, 8192, "px",                                                 \
    "wider frames are shrunk to this width for auto-initialisation (boxes refined at full size)")  \
  X(bool, auto_init_reject_static, true, false, true, "",                                          \
    "drop auto-init candidates whose pixels have not changed for 3 frames (overlays)")            \
  X(int, auto_init_verify_frames, 20, 0, 10000, "checks",                                          \
    "checks (one per detection_interval frames) after which an auto-started track not yet moving like an obstacle yields to one that does, and one that never moved 2 px in the image to the next persistent candidate (0 = off)") \
  X(double, extent_contrast, 0.1, 0.0, 1.0, "",                                                    \
    "a detected box grows over the pixels around it above this share of its core's contrast (0 = off)")

// Kernelized correlation filter and scale.
#define OT_TRACKER_PARAMS(X)                                                                       \
  X(double, learning_rate, 0.01, 0.0, 1.0, "", "model interpolation factor per frame (eta)")       \
  X(double, learn_threshold, 0.40, 0.0, 1.0, "",                                                   \
    "confidence below which the filter model is not updated (keeps occluders out)")               \
  X(double, kcf_padding, 1.5, 0.0, 5.0, "x box", "context around the box in the filter window")    \
  X(int, kcf_template_size, 96, 32, 256, "px", "longer side of the resized filter window")         \
  X(int, kcf_cell_size, 4, 1, 8, "px", "HOG cell size")                                            \
  X(double, kcf_lambda, 1.0e-4, 1.0e-8, 1.0, "", "ridge-regression regulariser")                   \
  X(double, kcf_kernel_sigma, 0.5, 0.01, 10.0, "", "Gaussian kernel bandwidth")                    \
  X(double, kcf_output_sigma_factor, 0.1, 0.01, 1.0, "",                                           \
    "label Gaussian sigma as a fraction of the target size")                                      \
  X(int, scale_count, 3, 1, 33, "", "scales searched per frame (1 = no scale estimation)")         \
  X(double, scale_step, 1.05, 1.0, 1.5, "", "ratio between neighbouring scales")                 \
  X(double, scale_penalty, 0.95, 0.5, 1.0, "",                                                     \
    "factor on the response peak of non-unit scales (favours keeping the size)")                  \
  X(int, scale_confirm_frames, 4, 1, 30, "",                                                       \
    "frames in a row a larger (or smaller) scale must win before the box is resized, unless the "   \
    "object's own pixel expansions show that trend (1 = at once)")                                  \
  X(double, kcf_min_window, 16.0, 0.0, 1024.0, "px",                                               \
    "smallest side of the filter window in frame pixels (context for tiny targets)")              \
  X(bool, kcf_scale_filter, false, false, true, "",                                                \
    "scale by a DSST 1-D scale filter over scale_count scales (else search them with the KCF)")

#define OT_PARAMS(X) OT_LOOP_PARAMS(X) OT_SALIENCY_PARAMS(X) OT_TRACKER_PARAMS(X)

// One struct per group, so that a component takes only its own (the correlation filter its
// TrackerParams, saliency and auto-initialisation their SaliencyParams); Params holds them all,
// for the pipeline, the loaders and the tools.
#define OT_PARAMS_DECLARE_(type, name, def, lo, hi, unit, doc) type name = def;
struct LoopParams {
  OT_LOOP_PARAMS(OT_PARAMS_DECLARE_)
};
struct SaliencyParams {
  OT_SALIENCY_PARAMS(OT_PARAMS_DECLARE_)
};
struct TrackerParams {
  OT_TRACKER_PARAMS(OT_PARAMS_DECLARE_)
};
#undef OT_PARAMS_DECLARE_

struct Params : LoopParams, SaliencyParams, TrackerParams {};

// One row of the parameter table, for tools that list, load or expose parameters by name.
struct ParamInfo {
  const char* name;
  const char* type;  // "bool", "int" or "double"
  double default_value;
  double min_value;
  double max_value;
  const char* unit;
  const char* description;
};

const std::vector<ParamInfo>& paramTable();
const ParamInfo* findParam(const std::string& name);

// Reads a parameter as a double (bool -> 0/1). Throws std::out_of_range for an unknown name.
double getParam(const Params& params, const std::string& name);

// Sets a parameter by name. A NaN or an unknown name is refused (returns false, params
// unchanged); a value outside [min, max] (including +-inf) is clamped; ints are rounded. When
// `message` is given it receives a sentence naming the parameter and its valid range whenever
// the value was refused, clamped or rounded (empty otherwise).
bool setParam(Params& params, const std::string& name, double value, std::string* message = nullptr);

// Clamps every field into its range (NaN -> default). Returns one message per changed field.
std::vector<std::string> validate(Params& params);
// The same for one group's fields, without messages (a component's own copy of its group).
void clampGroup(SaliencyParams& params);
void clampGroup(TrackerParams& params);

// Loads a flat YAML/JSON map of parameter names to values (flat_yaml.h), on top of `base`.
// Unknown keys and bad values produce messages, never an exception; a file that cannot be read
// or parsed throws std::runtime_error naming the file.
Params loadParamsFile(const std::string& path, std::vector<std::string>* messages,
                      const Params& base = Params());

// Same, from YAML text in memory (used by the fuzzer and tests).
Params loadParamsString(const std::string& yaml, std::vector<std::string>* messages,
                        const Params& base = Params());

// Writes all parameters as YAML (name: value, with the description as a comment).
std::string paramsToYaml(const Params& params);

}  // namespace core
}  // namespace obstacle_tracker
