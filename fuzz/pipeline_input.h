// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Decodes a fuzzer's byte string into a short run of the core Pipeline (frame sizes, types,
// contents, stamps, parameter changes, startTrack boxes) and executes it. Shared by
// fuzz/fuzz_pipeline.cpp, fuzz/make_seeds.cpp (which writes inputs in this layout) and the
// regression tests in test/core/test_robust_fuzz.cpp (which replay inputs the fuzzer found).
//
// Layout (ByteReader, fuzz_input.h; a short input reads zeros past its end):
//   u8 flags       bit0: CV_8UC3 (else CV_8UC1)
//   u8 width, u8 height           0 gives an empty frame (must be refused)
//   u8 nparams % 4, then nparams x (u8 index into paramTable(), f64 value) -> setParams
//   u8 nframes % 8 + 1, then per frame:
//     u8 op   bits0-1 stamp: 0 += u16 ms, 1 same stamp, 2 -= u16 ms, 3 raw f64
//             bit2 size change: u8 width, u8 height, u8 (bit0 toggles the type)
//             bit3 one parameter change: u8 index, f64 value
//             bits4-5 content: 0 u8 n + n bytes tiled over the frame, 1 u8 constant,
//                              2 rectangle: u8 background, u8 foreground, u8 x, y, w, h
//                                (moves by frame index), 3 uniform noise from a u16 seed
//             bit6 startTrack on a box of 4 f32 (x, y, w, h) instead of process
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "fuzz_input.h"
#include "obstacle_tracker/core/params.h"
#include "obstacle_tracker/core/pipeline.h"

namespace obstacle_tracker {
namespace fuzz {

struct PipelineRunResult {
  int frames = 0;          // process/startTrack calls made
  int refused = 0;         // of which refused with std::invalid_argument (deliberately bad)
  std::string violation;   // non-empty: the contract was broken (crash-worthy)
};

inline void fillFrame(cv::Mat& frame, int mode, ByteReader& in, int index) {
  if (frame.empty()) {
    // Still consume the content bytes so the rest of the input decodes the same way.
  }
  switch (mode) {
    case 0: {
      std::string bytes = in.bytes(in.u8());
      if (frame.empty()) return;
      std::size_t n = frame.total() * frame.elemSize();
      for (int r = 0; r < frame.rows; ++r) {
        std::uint8_t* row = frame.ptr<std::uint8_t>(r);
        std::size_t rowBytes = static_cast<std::size_t>(frame.cols) * frame.elemSize();
        for (std::size_t c = 0; c < rowBytes; ++c) {
          std::size_t k = static_cast<std::size_t>(r) * rowBytes + c;
          row[c] = bytes.empty() ? 0 : static_cast<std::uint8_t>(bytes[k % bytes.size()]);
        }
      }
      (void)n;
      break;
    }
    case 1: {
      std::uint8_t v = in.u8();
      if (!frame.empty()) frame.setTo(cv::Scalar::all(v));
      break;
    }
    case 2: {
      std::uint8_t bg = in.u8(), fg = in.u8();
      int x = in.u8(), y = in.u8(), w = in.u8(), h = in.u8();
      if (frame.empty()) return;
      frame.setTo(cv::Scalar::all(bg));
      cv::rectangle(frame, cv::Rect(x + index, y + index / 2, w, h), cv::Scalar::all(fg),
                    cv::FILLED);
      break;
    }
    default: {
      cv::RNG rng(in.u16());
      if (!frame.empty()) rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
      break;
    }
  }
}

inline std::string checkObstacles(const std::vector<core::Obstacle>& obstacles) {
  for (const core::Obstacle& o : obstacles) {
    if (!std::isfinite(o.box.x) || !std::isfinite(o.box.y) || !std::isfinite(o.box.width) ||
        !std::isfinite(o.box.height)) {
      return "obstacle with a non-finite box";
    }
    if (!(o.confidence >= 0.0f && o.confidence <= 1.0f)) return "confidence outside [0, 1]";
    if (o.id < 0) return "negative obstacle id";
    if (std::isnan(o.expansion_rate) || std::isnan(o.time_to_contact)) {
      return "NaN expansion rate or time to contact";
    }
  }
  return std::string();
}

// Runs the decoded input. Exceptions other than std::invalid_argument on a deliberately invalid
// call (empty frame, non-finite stamp, non-finite or empty startTrack box) propagate, and so
// does std::invalid_argument on a valid call: both are failures for the fuzzer and the tests.
inline PipelineRunResult runPipelineInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  PipelineRunResult result;
  int type = (in.u8() & 1) ? CV_8UC3 : CV_8UC1;
  int width = in.u8(), height = in.u8();
  core::Params params;
  const auto& table = core::paramTable();
  int nparams = in.u8() % 4;
  for (int i = 0; i < nparams; ++i) {
    const core::ParamInfo& info = table[in.u8() % table.size()];
    core::setParam(params, info.name, in.f64());
  }
  core::Pipeline pipeline(params);
  int nframes = in.u8() % 8 + 1;
  double stamp = 1000.0;
  for (int f = 0; f < nframes; ++f) {
    int op = in.u8();
    switch (op & 3) {
      case 0: stamp += in.u16() * 1e-3; break;
      case 1: break;
      case 2: stamp -= in.u16() * 1e-3; break;
      default: stamp = in.f64(); break;
    }
    if (op & 4) {
      width = in.u8();
      height = in.u8();
      if (in.u8() & 1) type = type == CV_8UC1 ? CV_8UC3 : CV_8UC1;
    }
    if (op & 8) {
      const core::ParamInfo& info = table[in.u8() % table.size()];
      core::setParam(params, info.name, in.f64());
      pipeline.setParams(params);
    }
    cv::Mat frame;
    if (width > 0 && height > 0) frame.create(height, width, type);
    fillFrame(frame, (op >> 4) & 3, in, f);
    bool deliberatelyBad = frame.empty() || !std::isfinite(stamp);
    ++result.frames;
    try {
      if (op & 64) {
        const float bx = in.f32(), by = in.f32(), bw = in.f32(), bh = in.f32();  // in this order
        const cv::Rect2f box(bx, by, bw, bh);
        // pipeline.h: the box must be finite, at least 1 x 1 px and overlap the frame; kcf.h:
        // at most 16 times the frame's size.
        const bool badBox = !std::isfinite(box.x) || !std::isfinite(box.y) ||
                            !std::isfinite(box.width) || !std::isfinite(box.height) ||
                            box.width < 1.0f || box.height < 1.0f ||
                            (box & cv::Rect2f(0.0f, 0.0f, static_cast<float>(width),
                                              static_cast<float>(height))).area() <= 0.0f ||
                            box.width > 16.0f * width || box.height > 16.0f * height;
        deliberatelyBad = deliberatelyBad || badBox;
        result.violation = checkObstacles(pipeline.startTrack(frame, stamp, box));
      } else {
        result.violation = checkObstacles(pipeline.process(frame, stamp));
      }
    } catch (const std::invalid_argument& e) {
      if (!deliberatelyBad) {
        result.violation = std::string("std::invalid_argument on a valid frame: ") + e.what();
      }
      if (std::string(e.what()).empty()) result.violation = "std::invalid_argument without a message";
      ++result.refused;
    }
    if (!result.violation.empty()) return result;
    core::TrackState s = pipeline.state();
    if (static_cast<int>(s) > 3) {
      result.violation = "state() out of range";
      return result;
    }
  }
  return result;
}

}  // namespace fuzz
}  // namespace obstacle_tracker
