// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Inputs found by the libFuzzer targets (fuzz/), replayed through the same decoder as regression
// tests. Each entry says what it found. A new crash: copy the bytes of
// _build/fuzz/artifacts/fuzz_pipeline-crash-* here (xxd -i) with a line on what it was.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../../fuzz/pipeline_input.h"

namespace {

struct FoundInput {
  const char* what;
  std::vector<std::uint8_t> bytes;
};

const std::vector<FoundInput>& foundInputs() {
  static const std::vector<FoundInput> inputs = {
      {"startTrack on a 4e21 px box overlapping a 96x72 frame: int overflow in KcfTracker's "
       "resample (segfault in Release); now refused with std::invalid_argument (box more than 16x "
       "the frame). Also exposed that the decoder read function arguments in an unspecified order.",
       {0x00, 0x60, 0x48, 0x00, 0x07, 0x20, 0x21, 0x00, 0x14, 0xe6, 0x1e, 0x19, 0x0c, 0x0a, 0x20,
        0x21, 0x00, 0x14, 0xe6, 0x1e, 0x19, 0x0c, 0x0a, 0x20, 0x21, 0x00, 0x14, 0xe6, 0xff, 0xff,
        0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x1e, 0x19, 0x0c, 0x0a, 0x20, 0x25, 0x21, 0x00, 0x14,
        0xe6, 0x1e, 0x19, 0x0c, 0x0a, 0x20, 0x21, 0x00, 0x14, 0xe6, 0x1e, 0x19, 0x0c, 0x0a, 0x20,
        0x21, 0x00, 0x14, 0xe6, 0x1e, 0x6b, 0x63, 0x66, 0x5f, 0x73, 0x63, 0x61, 0x6c, 0x65, 0x5f,
        0x66, 0x69, 0x6c, 0x74, 0x65, 0x72, 0x19, 0x0c, 0x0a, 0x20, 0x21, 0x00, 0x14, 0xe6, 0x1e,
        0x19, 0x0c, 0x0a, 0x20, 0x21, 0x00, 0x14, 0xe6, 0x1e, 0x19, 0x0c, 0x0a}},
  };
  return inputs;
}

}  // namespace

TEST(RobustFuzz, InputsTheFuzzerFoundRunCleanly) {
  for (const FoundInput& input : foundInputs()) {
    const auto r = obstacle_tracker::fuzz::runPipelineInput(input.bytes.data(), input.bytes.size());
    EXPECT_EQ(r.violation, "") << input.what;
    EXPECT_GT(r.frames, 0) << input.what;
  }
}

TEST(RobustFuzz, DecoderReadsTheSameValuesWithEveryCompiler) {
  // The layout is little-endian and sequential: u16 0x1234 from {0x34, 0x12}.
  const std::uint8_t bytes[] = {0x34, 0x12, 0x00, 0x00, 0x80, 0x3f};
  obstacle_tracker::fuzz::ByteReader in(bytes, sizeof bytes);
  EXPECT_EQ(in.u16(), 0x1234);
  EXPECT_EQ(in.f32(), 1.0f);
  EXPECT_TRUE(in.empty());
  EXPECT_EQ(in.u8(), 0);  // past the end: zeros
}
