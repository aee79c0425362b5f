// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// libFuzzer target for the parameter layer: loadParamsString on arbitrary text, setParam with
// arbitrary names and doubles (NaN, +-inf, huge, denormal), raw out-of-range fields through
// validate(). Must never crash; std::runtime_error from the loader (unparsable text) is the only
// exception allowed. After every step each parameter must lie in its range and the YAML written
// by paramsToYaml must load back to the same values without a message.
//
// Input layout (see fuzz_input.h): u16 yaml length, the yaml text, then operations
// (u8 kind, ...) until the input ends.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "fuzz_input.h"
#include "obstacle_tracker/core/params.h"

namespace oc = obstacle_tracker::core;
using obstacle_tracker::fuzz::ByteReader;

namespace {

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_params: invariant broken: %s\n", what.c_str());
  std::abort();
}

void checkInRange(const oc::Params& p, const char* after) {
  for (const oc::ParamInfo& info : oc::paramTable()) {
    double v = oc::getParam(p, info.name);
    if (!(v >= info.min_value && v <= info.max_value)) {
      fail(std::string(info.name) + " = " + std::to_string(v) + " out of range after " + after);
    }
  }
}

void checkRoundTrip(const oc::Params& p) {
  std::vector<std::string> messages;
  oc::Params back = oc::loadParamsString(oc::paramsToYaml(p), &messages);
  if (!messages.empty()) fail("paramsToYaml output reloads with a message: " + messages.front());
  for (const oc::ParamInfo& info : oc::paramTable()) {
    double a = oc::getParam(p, info.name);
    double b = oc::getParam(back, info.name);
    if (std::fabs(a - b) > 1e-8 * std::max(1.0, std::fabs(a))) {
      fail(std::string("round trip changed ") + info.name + ": " + std::to_string(a) + " -> " +
           std::to_string(b));
    }
  }
}

const double kInteresting[] = {
    std::numeric_limits<double>::quiet_NaN(),   std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(),   0.0,
    -0.0,                                       1e308,
    -1e308,                                     std::numeric_limits<double>::denorm_min(),
    2147483647.5,                               -2147483648.5,
    9.3e18,                                     -9.3e18,
    0.5,                                        -1.0};

// Writes a raw value straight into a field (what a caller might do before validate()). Only
// values representable in the field's type, so the write itself is defined behaviour.
void writeRaw(oc::Params& p, std::size_t index, ByteReader& in) {
  std::size_t i = 0;
#define OT_FUZZ_RAW_(type, name, def, lo, hi, unit, doc) \
  if (i++ == index) writeField(p.name, in);
  auto writeField = [](auto& field, ByteReader& r) {
    using T = std::decay_t<decltype(field)>;
    if constexpr (std::is_same_v<T, bool>) {
      field = (r.u8() & 1) != 0;
    } else if constexpr (std::is_same_v<T, int>) {
      const std::uint32_t hi = r.u16();
      const std::uint32_t lo = r.u16();
      field = static_cast<int>(hi << 16 | lo);
    } else {
      field = r.f64();
    }
  };
  OT_PARAMS(OT_FUZZ_RAW_)
#undef OT_FUZZ_RAW_
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const auto& table = oc::paramTable();
  oc::Params p;

  std::string yaml = in.bytes(in.u16() % 4096);
  try {
    std::vector<std::string> messages;
    p = oc::loadParamsString(yaml, &messages);
    checkInRange(p, "loadParamsString");
    for (const std::string& m : messages) {
      if (m.empty()) fail("empty loader message");
    }
  } catch (const std::runtime_error&) {
    // Unparsable text: refused with a message naming the source. Allowed.
  }

  int ops = 0;
  while (!in.empty() && ops++ < 64) {
    std::string msg;
    switch (in.u8() % 5) {
      case 0: {
        const oc::ParamInfo& info = table[in.u8() % table.size()];
        double before = oc::getParam(p, info.name);
        double value = in.f64();
        bool ok = oc::setParam(p, info.name, value, &msg);
        if (std::isnan(value) && (ok || oc::getParam(p, info.name) != before)) fail("NaN accepted");
        if (!ok && !std::isnan(value)) fail(std::string("refused ") + info.name);
        if ((!ok || oc::getParam(p, info.name) != value) && msg.find(info.name) == std::string::npos) {
          fail("no message naming " + std::string(info.name) + " (got '" + msg + "')");
        }
        break;
      }
      case 1: {
        std::string name = in.bytes(in.u8() % 40);
        bool known = oc::findParam(name) != nullptr;
        bool ok = oc::setParam(p, name, in.f64(), &msg);
        if (!known && ok) fail("unknown name accepted");
        break;
      }
      case 2: {
        const oc::ParamInfo& info = table[in.u8() % table.size()];
        oc::setParam(p, info.name, kInteresting[in.u8() % (sizeof kInteresting / sizeof(double))],
                     &msg);
        break;
      }
      case 3: {
        writeRaw(p, in.u8() % table.size(), in);
        std::vector<std::string> messages = oc::validate(p);
        (void)messages;
        break;
      }
      case 4: {
        try {
          std::vector<std::string> messages;
          p = oc::loadParamsString(in.bytes(in.u8()), &messages, p);
        } catch (const std::runtime_error&) {
        }
        break;
      }
    }
    checkInRange(p, "an operation");
  }
  checkRoundTrip(p);
  return 0;
}
