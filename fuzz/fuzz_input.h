// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Reads typed values from a fuzzer's byte string. Running out of bytes yields zeros, so every
// input, however short, decodes to something. Shared by the fuzz targets and by the program that
// writes their seed corpora, so both agree on the layout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace obstacle_tracker {
namespace fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool empty() const { return pos_ >= size_; }
  std::size_t remaining() const { return empty() ? 0 : size_ - pos_; }

  std::uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  // Each byte read in its own statement: the order of operands (and of function arguments) is
  // unspecified in C++, and GCC and clang differ, which would decode one input two ways.
  std::uint16_t u16() {
    const unsigned lo = u8();
    const unsigned hi = u8();
    return static_cast<std::uint16_t>(lo | (hi << 8));
  }
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  // Any bit pattern, so NaN, +-inf, denormals and huge values all occur.
  double f64() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= static_cast<std::uint64_t>(u8()) << (8 * i);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  float f32() {
    std::uint32_t bits = 0;
    for (int i = 0; i < 4; ++i) bits |= static_cast<std::uint32_t>(u8()) << (8 * i);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  // Up to n bytes as a string (fewer when the input ends).
  std::string bytes(std::size_t n) {
    std::size_t k = n < remaining() ? n : remaining();
    std::string s(reinterpret_cast<const char*>(data_ + pos_), k);
    pos_ += k;
    return s;
  }
  std::string rest() { return bytes(remaining()); }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// Appends typed values in the layout ByteReader reads (for seed corpora).
class ByteWriter {
 public:
  void u8(unsigned v) { out_.push_back(static_cast<std::uint8_t>(v)); }
  void u16(unsigned v) {
    u8(v & 0xff);
    u8((v >> 8) & 0xff);
  }
  void i16(int v) { u16(static_cast<unsigned>(static_cast<std::uint16_t>(static_cast<std::int16_t>(v)))); }
  void f64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof v);
    for (int i = 0; i < 8; ++i) u8(static_cast<unsigned>((bits >> (8 * i)) & 0xff));
  }
  void f32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof v);
    for (int i = 0; i < 4; ++i) u8((bits >> (8 * i)) & 0xff);
  }
  void bytes(const std::string& s) { out_.insert(out_.end(), s.begin(), s.end()); }
  const std::vector<std::uint8_t>& data() const { return out_; }

 private:
  std::vector<std::uint8_t> out_;
};

}  // namespace fuzz
}  // namespace obstacle_tracker
