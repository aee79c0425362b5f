// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Deterministic randomness and trigonometry for the scene generator. Everything that decides a
// pixel value goes through these: integer generators (SplitMix64, Vigna 2015, public domain
// reference; xoshiro256**, Blackman & Vigna 2018) with floats derived from the integer bits, and
// sin/cos written with + - * / only, so that the same seed gives the same bytes on any IEEE-754
// machine (no dependence on the C library's transcendental functions or on cv::RNG).
#pragma once

#include <cstdint>

namespace obstacle_tracker {
namespace scene {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64 finaliser: a strong 64-bit mix, used as a stateless hash.
inline std::uint64_t mix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Hash of several integers (order matters).
inline std::uint64_t hashCombine(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0,
                                 std::uint64_t c = 0) {
  return mix64(mix64(mix64(seed ^ mix64(a)) ^ b) ^ mix64(c + 0x632BE59BD9B4E019ULL));
}

// [0, 1) from the top 24 bits: exact in float.
inline float unitFloat(std::uint64_t h) { return static_cast<float>(h >> 40) * (1.0f / 16777216.0f); }
// [0, 1) from the top 53 bits: exact in double.
inline double unitDouble(std::uint64_t h) { return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0); }

// xoshiro256** seeded through SplitMix64.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    std::uint64_t z = seed;
    for (auto& s : s_) {
      z += 0x9E3779B97F4A7C15ULL;
      s = mix64(z);
    }
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  double uniform() { return unitDouble(next()); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Integer in [lo, hi] (inclusive); hi >= lo.
  int uniformInt(int lo, int hi) {
    const std::uint64_t span = static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo + 1);
    return lo + static_cast<int>(next() % span);
  }
  bool chance(double p) { return uniform() < p; }
  // Approximately standard normal (Irwin-Hall sum of 12 uniforms minus 6; bounded at +-6).
  double normal() {
    double s = 0.0;
    for (int i = 0; i < 12; ++i) s += uniform();
    return s - 6.0;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

// sin and cos from basic arithmetic only (range reduction + Taylor series to x^17 on
// [-pi/2, pi/2], absolute error < 1e-11): identical results on every IEEE-754 machine.
double detSin(double x);
double detCos(double x);
inline double degToRad(double deg) { return deg * (kPi / 180.0); }

// 64-bit FNV-1a over bytes (used to fingerprint frames in tests and docs).
std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t h = 0xCBF29CE484222325ULL);

}  // namespace scene
}  // namespace obstacle_tracker
