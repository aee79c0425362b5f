// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// Writes the seed corpora of the fuzz targets: make_seeds OUTDIR creates OUTDIR/fuzz_params/ and
// OUTDIR/fuzz_pipeline/ with a few small inputs each (valid YAML, bad values, a moving bright
// square, noise, tiny frames, stamps going backwards...). Generated at run time so that no binary
// corpus is stored in the repository.
#include <cstdint>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <sys/stat.h>
#include <vector>

#include "fuzz_input.h"
#include "obstacle_tracker/core/params.h"

namespace oc = obstacle_tracker::core;
using obstacle_tracker::fuzz::ByteWriter;

namespace {

void writeFile(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::cerr << "cannot write " << path << "\n";
    std::exit(1);
  }
}

ByteWriter paramsSeed(const std::string& yaml) {
  ByteWriter w;
  w.u16(static_cast<unsigned>(yaml.size()));
  w.bytes(yaml);
  return w;
}

int paramIndex(const std::string& name) {
  const auto& t = oc::paramTable();
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (name == t[i].name) return static_cast<int>(i);
  }
  return 0;
}

// Header of a pipeline input: type, size, no parameter change, frame count.
ByteWriter pipelineHeader(bool colour, int w, int h, int frames) {
  ByteWriter b;
  b.u8(colour ? 1 : 0);
  b.u8(w);
  b.u8(h);
  b.u8(0);
  b.u8(frames - 1);
  return b;
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Raw parameter operations after an empty YAML: bad values through the numeric setter, an
// unknown name, an integer setter out of range and a YAML fragment cut short.
ByteWriter paramsSetterSeed() {
  ByteWriter w = paramsSeed("");
  for (double v : {kNaN, kInf, -kInf, -1.0, 1e300, 0.5}) {
    w.u8(0);
    w.u8(paramIndex("max_obstacles"));
    w.f64(v);
  }
  w.u8(1);
  w.u8(7);
  w.bytes("unknown");
  w.f64(1.0);
  w.u8(3);
  w.u8(paramIndex("kcf_template_size"));
  w.u16(0xffff);
  w.u16(0x7fff);
  w.u8(4);
  w.u8(20);
  w.bytes("scale_count: -77\n  x");
  return w;
}

std::vector<ByteWriter> paramsSeeds() {
  std::vector<ByteWriter> p;
  p.push_back(paramsSeed(oc::paramsToYaml(oc::Params())));
  p.push_back(paramsSeed("peak_threshold: .nan\nsearch_window_scale: -3\nmax_obstacles: 1e300\n"
                         "kcf_lambda: .inf\nsaliency_backgroundness: maybe\nno_such: 1\n"));
  p.push_back(paramsSeed("%YAML 1.2\n---\n{\"detection_interval\": 2.6, \"scale_step\": 7}\n"));
  p.push_back(paramsSeed("- a\n- b\n"));
  p.push_back(paramsSeed("peak_threshold: [1, 2]\nmerge_iou: {a: 1}\nlearning_rate: \"0.1\"\n"));
  p.push_back(paramsSetterSeed());
  return p;
}

// A bright square moving on a dark background: reaches tracking.
ByteWriter movingSquareSeed(bool colour) {
  ByteWriter b = pipelineHeader(colour, 96, 72, 8);
  for (int f = 0; f < 8; ++f) {
    b.u8(0 | (2 << 4));
    b.u16(33);
    b.u8(20);
    b.u8(230);
    b.u8(30);
    b.u8(25);
    b.u8(12);
    b.u8(10);
  }
  return b;
}

// Same with duplicate stamps, a stamp going backwards, a NaN stamp and a size change.
ByteWriter badStampsSeed() {
  ByteWriter b = pipelineHeader(false, 64, 48, 6);
  const int ops[] = {0, 1, 2, 3, 4, 0};
  for (int f = 0; f < 6; ++f) {
    b.u8(ops[f] | (2 << 4));
    if (ops[f] == 0 || ops[f] == 2) b.u16(500);
    if (ops[f] == 3) b.f64(kNaN);
    if (ops[f] == 4) {
      b.u8(80);
      b.u8(40);
      b.u8(1);
      b.u16(40);
    }
    b.u8(0);
    b.u8(255);
    b.u8(20);
    b.u8(15);
    b.u8(8);
    b.u8(8);
  }
  return b;
}

// A tiny or degenerate frame size, constant and noise frames.
ByteWriter tinyFrameSeed(int w, int h) {
  ByteWriter b = pipelineHeader(false, w, h, 3);
  for (int f = 0; f < 3; ++f) {
    b.u8(0 | ((f == 2 ? 3 : 1) << 4));
    b.u16(40);
    b.u16(f == 0 ? 0 : 255);
  }
  return b;
}

// startTrack on a box, then parameter changes (NaN, huge) while tracking.
ByteWriter startTrackSeed() {
  ByteWriter b = pipelineHeader(true, 128, 96, 5);
  b.u8(0 | (2 << 4) | 64);
  b.u16(40);
  for (int v : {10, 200, 40, 30, 16, 16}) b.u8(v);
  for (float v : {38.f, 28.f, 20.f, 20.f}) b.f32(v);
  for (int f = 0; f < 4; ++f) {
    b.u8(0 | 8 | (2 << 4));
    b.u16(40);
    b.u8(f);
    b.f64(f % 2 ? kNaN : 1e300);
    for (int v : {10, 200, 40, 30, 16, 16}) b.u8(v);
  }
  return b;
}

// Raw bytes tiled: a gradient.
ByteWriter gradientSeed() {
  ByteWriter b = pipelineHeader(false, 200, 150, 2);
  for (int f = 0; f < 2; ++f) {
    b.u8(0);
    b.u16(40);
    b.u8(255);
    for (int i = 0; i < 255; ++i) b.u8(i);
  }
  return b;
}

// Layout in pipeline_input.h.
std::vector<ByteWriter> pipelineSeeds() {
  std::vector<ByteWriter> q;
  for (bool colour : {false, true}) q.push_back(movingSquareSeed(colour));
  q.push_back(badStampsSeed());
  // Tiny and degenerate frames: 1x1, 2x2, 255x1, 1x255, 0x0.
  for (auto wh : std::vector<std::pair<int, int>>{{1, 1}, {2, 2}, {255, 1}, {1, 255}, {0, 0}}) {
    q.push_back(tinyFrameSeed(wh.first, wh.second));
  }
  q.push_back(startTrackSeed());
  q.push_back(gradientSeed());
  return q;
}

void writeSeeds(const std::string& dir, const std::vector<ByteWriter>& seeds) {
  for (std::size_t i = 0; i < seeds.size(); ++i) writeFile(dir + "/seed_" + std::to_string(i), seeds[i].data());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_make_seeds OUTDIR\n";
    return 2;
  }
  std::string out = argv[1];
  mkdir(out.c_str(), 0755);
  std::string pdir = out + "/fuzz_params", qdir = out + "/fuzz_pipeline";
  mkdir(pdir.c_str(), 0755);
  mkdir(qdir.c_str(), 0755);
  const std::vector<ByteWriter> p = paramsSeeds();
  writeSeeds(pdir, p);
  const std::vector<ByteWriter> q = pipelineSeeds();
  writeSeeds(qdir, q);
  std::cout << "wrote " << p.size() << " fuzz_params and " << q.size() << " fuzz_pipeline seeds to "
            << out << "\n";
  return 0;
}
