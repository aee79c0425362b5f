// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "init_table/variants.h"

namespace obstacle_tracker {
namespace init_table_tool {

namespace oc = obstacle_tracker::core;

std::vector<Variant> ablationVariants() {
  std::vector<Variant> variants;
  oc::Params d;
  variants.push_back({"defaults (persistence + motion + local contrast)", d});
  oc::Params single = d;
  single.auto_init_frames = 1;
  single.auto_init_min_motion = 0.0;
  variants.push_back({"single frame (contrast x MBD, best peak)", single});
  oc::Params single_mbd = single;
  single_mbd.auto_init_local_contrast = false;
  variants.push_back({"single frame, MBD alone at native res", single_mbd});
  oc::Params persist = d;
  persist.auto_init_min_motion = 0.0;
  variants.push_back({"persistence + contrast, no motion", persist});
  oc::Params no_contrast = d;
  no_contrast.auto_init_local_contrast = false;
  variants.push_back({"persistence + motion, MBD alone (no contrast)", no_contrast});
  oc::Params no_static = d;
  no_static.auto_init_reject_static = false;
  variants.push_back({"defaults, no still-pixel rejection", no_static});
  oc::Params border = d;
  border.reject_border_regions = false;
  variants.push_back({"defaults, border regions kept", border});
  for (double m : {2.0, 6.0, 8.0}) {
    oc::Params mm = d;
    mm.auto_init_min_motion = m;
    variants.push_back({"defaults, min motion " + std::to_string(static_cast<int>(m)) + " px", mm});
  }
  for (int n : {5, 8, 10, 12, 15}) {
    if (n == d.auto_init_frames) continue;
    oc::Params pn = d;
    pn.auto_init_frames = n;
    variants.push_back({"defaults, " + std::to_string(n) + " frames", pn});
  }
  return variants;
}

std::vector<Variant> detectorOptions() {
  std::vector<Variant> options;
  oc::Params d;
  options.push_back({"defaults (FastMBD, 300 px, no median, no MB+ terms)", d});
  oc::Params med = d;
  med.saliency_median = 5;
  options.push_back({"+ 5x5 median (MB+ reference)", med});
  oc::Params bg = d;
  bg.saliency_backgroundness = true;
  options.push_back({"+ backgroundness", bg});
  oc::Params pp = d;
  pp.saliency_postprocess = true;
  options.push_back({"+ smoothing and contrast stretch", pp});
  oc::Params mbplus = d;
  mbplus.saliency_median = 5;
  mbplus.saliency_backgroundness = true;
  mbplus.saliency_postprocess = true;
  options.push_back({"MB+ (median + backgroundness + post-processing)", mbplus});
  oc::Params big = d;
  big.saliency_max_side = 640;
  options.push_back({"max side 640 px", big});
  oc::Params border = d;
  border.reject_border_regions = false;
  options.push_back({"border regions kept", border});
  oc::Params by_area = d;
  by_area.saliency_rank_by_area = true;
  options.push_back({"ranked by area (the paper) instead of saliency mass", by_area});
  return options;
}

}  // namespace init_table_tool
}  // namespace obstacle_tracker
