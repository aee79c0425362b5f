// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/scene/shapes.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace obstacle_tracker {
namespace scene {

const char* toString(ObstacleClass c) {
  switch (c) {
    case ObstacleClass::kFixedWing: return "fixed_wing";
    case ObstacleClass::kMultirotor: return "multirotor";
    case ObstacleClass::kBird: return "bird";
  }
  return "unknown";
}

namespace {

using P3 = cv::Point3f;

Material mat(float b, float g, float r, float thermal) {
  Material m;
  m.bgr = cv::Vec3f(b, g, r);
  m.thermal = thermal;
  return m;
}

Plate plate(std::vector<P3> pts, const Material& m, float alpha = 1.0f) {
  Plate p;
  p.pts = std::move(pts);
  p.mat = m;
  p.alpha = alpha;
  return p;
}

// Profile in the xy plane (side view) at z = z0 from (x, y) pairs.
std::vector<P3> sideProfile(const std::vector<cv::Point2f>& xy, float z0) {
  std::vector<P3> p;
  for (const auto& v : xy) p.emplace_back(v.x, v.y, z0);
  return p;
}

// Symmetric top profile in the xz plane at y = y0 from (x, half-width) pairs, nose first.
std::vector<P3> topProfile(const std::vector<cv::Point2f>& xw, float y0) {
  std::vector<P3> p;
  for (const auto& v : xw) p.emplace_back(v.x, y0, -v.y);
  for (auto it = xw.rbegin(); it != xw.rend(); ++it) p.emplace_back(it->x, y0, it->y);
  return p;
}

enum class Axis { kX, kY, kZ };

// Ellipse in the plane normal to `normal` around c, radii ra, rb along the plane's two axes.
std::vector<P3> ellipse(P3 c, Axis normal, float ra, float rb, int n = 20) {
  std::vector<P3> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * kPi * i / n;
    const float u = static_cast<float>(detCos(a)) * ra, v = static_cast<float>(detSin(a)) * rb;
    switch (normal) {
      case Axis::kX: p.emplace_back(c.x, c.y + v, c.z + u); break;
      case Axis::kY: p.emplace_back(c.x + u, c.y, c.z + v); break;
      case Axis::kZ: p.emplace_back(c.x + u, c.y + v, c.z); break;
    }
  }
  return p;
}

// Axis-aligned rectangle in the plane normal to `normal`, centred at c, sizes a x b.
std::vector<P3> rect(P3 c, Axis normal, float a, float b) {
  const float ha = 0.5f * a, hb = 0.5f * b;
  switch (normal) {
    case Axis::kX: return {{c.x, c.y - hb, c.z - ha}, {c.x, c.y - hb, c.z + ha}, {c.x, c.y + hb, c.z + ha}, {c.x, c.y + hb, c.z - ha}};
    case Axis::kY: return {{c.x - ha, c.y, c.z - hb}, {c.x + ha, c.y, c.z - hb}, {c.x + ha, c.y, c.z + hb}, {c.x - ha, c.y, c.z + hb}};
    case Axis::kZ: return {{c.x - ha, c.y - hb, c.z}, {c.x + ha, c.y - hb, c.z}, {c.x + ha, c.y + hb, c.z}, {c.x - ha, c.y + hb, c.z}};
  }
  return {};
}

// A thin bar from a to b in the horizontal plane (y fixed) of the given width.
std::vector<P3> barXZ(P3 a, P3 b, float width) {
  const float dx = b.x - a.x, dz = b.z - a.z;
  const float len = std::sqrt(dx * dx + dz * dz);
  const float nx = -dz / len * 0.5f * width, nz = dx / len * 0.5f * width;
  return {{a.x + nx, a.y, a.z + nz}, {b.x + nx, b.y, b.z + nz}, {b.x - nx, b.y, b.z - nz}, {a.x - nx, a.y, a.z - nz}};
}

// The same bar, standing vertically (height h centred on y).
std::vector<P3> barVertical(P3 a, P3 b, float h) {
  return {{a.x, a.y - 0.5f * h, a.z}, {b.x, b.y - 0.5f * h, b.z}, {b.x, b.y + 0.5f * h, b.z}, {a.x, a.y + 0.5f * h, a.z}};
}

float pick(Rng& rng, float lo, float hi) { return static_cast<float>(rng.uniform(lo, hi)); }

}  // namespace

ShapeModel makeFixedWing(Rng& rng) {
  ShapeModel m;
  m.cls = ObstacleClass::kFixedWing;
  m.size_m = pick(rng, 10.0f, 12.5f);  // light aircraft wingspan
  // Livery: white / light grey / yellow body, coloured stripe.
  const int livery = rng.uniformInt(0, 2);
  const Material body = livery == 0 ? mat(228, 228, 230, 9800) : livery == 1 ? mat(185, 188, 192, 9700) : mat(60, 200, 235, 9750);
  const Material stripe = rng.chance(0.5) ? mat(150, 70, 30, 9900) : mat(40, 40, 170, 9900);
  const Material dark = mat(55, 50, 48, 9600);
  const Material engine = mat(90, 90, 95, 12800);
  const float fl = pick(rng, 0.82f, 0.95f);  // fuselage length relative to span
  const float fh = pick(rng, 0.09f, 0.12f);  // fuselage height
  const float n = 0.5f * fl, t = -0.5f * fl;
  auto X = [&](float u) { return t + u * (n - t); };  // 0 = tail, 1 = nose
  // Fuselage side and top profiles.
  m.plates.push_back(plate(sideProfile({{X(1.0f), 0.0f}, {X(0.98f), 0.3f * fh}, {X(0.9f), 0.5f * fh}, {X(0.75f), 0.55f * fh},
                                         {X(0.3f), 0.45f * fh}, {X(0.05f), 0.35f * fh}, {X(0.0f), 0.3f * fh},
                                         {X(0.0f), 0.12f * fh}, {X(0.2f), -0.15f * fh}, {X(0.75f), -0.45f * fh},
                                         {X(0.9f), -0.4f * fh}, {X(0.98f), -0.25f * fh}}, 0.0f), body));
  const int fus = static_cast<int>(m.plates.size()) - 1;
  m.plates.push_back(plate(topProfile({{X(1.0f), 0.0f}, {X(0.97f), 0.25f * fh}, {X(0.88f), 0.45f * fh}, {X(0.75f), 0.5f * fh},
                                        {X(0.25f), 0.35f * fh}, {X(0.0f), 0.1f * fh}}, 0.0f), body));
  m.plates.push_back(plate(ellipse({X(0.75f), 0.05f * fh, 0.0f}, Axis::kX, 0.5f * fh, 0.5f * fh, 16), body));
  // Stripe and windows: decals drawn just in front of the fuselage side.
  Plate s = plate(sideProfile({{X(0.95f), -0.05f * fh}, {X(0.05f), 0.15f * fh}, {X(0.05f), 0.28f * fh}, {X(0.95f), 0.1f * fh}}, 0.0f), stripe);
  s.hinge = P3(static_cast<float>(fus), 0, 0);  // hinge.x of a decal = index of its parent (see below)
  s.flap = 2;
  m.plates.push_back(s);
  Plate w = plate(sideProfile({{X(0.9f), 0.22f * fh}, {X(0.55f), 0.22f * fh}, {X(0.55f), 0.42f * fh}, {X(0.86f), 0.45f * fh}}, 0.0f), dark);
  w.hinge = P3(static_cast<float>(fus), 0, 0);
  w.flap = 2;
  m.plates.push_back(w);
  // Wings (one non-convex polygon), slightly below the fuselage axis, with a little sweep.
  const float rc = pick(rng, 0.14f, 0.18f), tc = pick(rng, 0.08f, 0.11f), wx = X(pick(rng, 0.55f, 0.68f));
  const float sweep = pick(rng, 0.0f, 0.06f), wy = -0.1f * fh;
  m.plates.push_back(plate({{wx + 0.5f * rc, wy, -0.04f}, {wx + 0.5f * tc - sweep, wy, -0.5f}, {wx - 0.5f * tc - sweep, wy, -0.5f},
                            {wx - 0.5f * rc, wy, -0.04f}, {wx - 0.5f * rc, wy, 0.04f}, {wx - 0.5f * tc - sweep, wy, 0.5f},
                            {wx + 0.5f * tc - sweep, wy, 0.5f}, {wx + 0.5f * rc, wy, 0.04f}}, body));
  // Tailplane and fin.
  m.plates.push_back(plate({{X(0.16f), 0.25f * fh, 0.0f}, {X(0.03f), 0.25f * fh, -0.17f}, {X(-0.03f), 0.25f * fh, -0.17f},
                            {X(0.0f), 0.25f * fh, 0.0f}, {X(-0.03f), 0.25f * fh, 0.17f}, {X(0.03f), 0.25f * fh, 0.17f}}, body));
  m.plates.push_back(plate(sideProfile({{X(0.2f), 0.4f * fh}, {X(0.04f), 2.1f * fh}, {X(-0.03f), 2.1f * fh}, {X(0.0f), 0.3f * fh}}, 0.0f), stripe));
  // Engine: nose cowling disc (hot in the thermal mode) and propeller disc.
  m.plates.push_back(plate(ellipse({X(1.0f), 0.0f, 0.0f}, Axis::kX, 0.22f * fh, 0.22f * fh, 12), engine));
  m.plates.push_back(plate(ellipse({X(1.0f) + 0.005f, 0.0f, 0.0f}, Axis::kX, 0.9f * fh, 0.9f * fh, 20), mat(70, 70, 70, 10200), 0.25f));
  return m;
}

ShapeModel makeMultirotor(Rng& rng) {
  ShapeModel m;
  m.cls = ObstacleClass::kMultirotor;
  m.size_m = pick(rng, 0.4f, 0.9f);  // diagonal including rotors
  const bool white = rng.chance(0.35);
  const Material body = white ? mat(222, 222, 225, 10400) : mat(48, 46, 44, 10600);
  const Material arm = white ? mat(200, 200, 205, 10300) : mat(38, 38, 38, 10400);
  const Material motor = mat(70, 70, 75, 12600);
  const Material rotor = mat(60, 60, 60, 9600);
  const Material accent = rng.chance(0.5) ? mat(30, 30, 200, 10500) : mat(0, 140, 235, 10500);
  const float bw = pick(rng, 0.18f, 0.24f), bh = pick(rng, 0.07f, 0.1f);
  const float arm_r = 0.5f - 0.15f;  // rotor centres at distance arm_r * sqrt(2)/... (diagonal)
  const float rr = pick(rng, 0.12f, 0.15f);
  // Body: three orthogonal plates (a rounded box), a top cover and a gimbal/camera below.
  m.plates.push_back(plate(ellipse({0, 0, 0}, Axis::kY, 0.5f * bw, 0.45f * bw, 16), body));
  m.plates.push_back(plate(rect({0, 0, 0}, Axis::kZ, bw, bh), body));
  m.plates.push_back(plate(rect({0, 0, 0}, Axis::kX, 0.9f * bw, bh), body));
  m.plates.push_back(plate(ellipse({0.02f, 0.5f * bh, 0}, Axis::kY, 0.3f * bw, 0.25f * bw, 12), accent));
  m.plates.push_back(plate(ellipse({0.3f * bw, -0.6f * bh, 0}, Axis::kZ, 0.25f * bh, 0.35f * bh, 10), mat(30, 30, 30, 11000)));
  const float d = arm_r / std::sqrt(2.0f) * 1.0f;
  const float cx[4] = {d, d, -d, -d}, cz[4] = {d, -d, d, -d};
  for (int i = 0; i < 4; ++i) {
    const P3 end(cx[i], 0.0f, cz[i]);
    m.plates.push_back(plate(barXZ({0, 0, 0}, end, 0.035f), arm));
    m.plates.push_back(plate(barVertical({0, 0, 0}, end, 0.03f), arm));
    m.plates.push_back(plate(rect({cx[i], 0.03f, cz[i]}, Axis::kZ, 0.05f, 0.06f), motor));
    m.plates.push_back(plate(rect({cx[i], 0.03f, cz[i]}, Axis::kX, 0.05f, 0.06f), motor));
    m.plates.push_back(plate(ellipse({cx[i], 0.065f, cz[i]}, Axis::kY, rr, rr, 24), rotor, 0.3f));
  }
  // Landing legs.
  for (float z : {-0.07f, 0.07f}) {
    m.plates.push_back(plate({{0.05f, -0.02f, z}, {0.09f, -0.16f, z * 1.4f}, {0.075f, -0.165f, z * 1.4f}, {0.035f, -0.02f, z}}, arm));
    m.plates.push_back(plate({{-0.05f, -0.02f, z}, {-0.09f, -0.16f, z * 1.4f}, {-0.075f, -0.165f, z * 1.4f}, {-0.035f, -0.02f, z}}, arm));
  }
  return m;
}

ShapeModel makeBird(Rng& rng) {
  ShapeModel m;
  m.cls = ObstacleClass::kBird;
  m.size_m = pick(rng, 0.6f, 1.3f);  // wingspan
  const bool gull = rng.chance(0.5);
  const Material body = gull ? mat(215, 215, 212, 10100) : mat(40, 42, 45, 10200);
  const Material wing = gull ? mat(165, 165, 160, 9900) : mat(35, 38, 42, 9950);
  const Material tip = gull ? mat(35, 35, 35, 9900) : mat(55, 58, 62, 9900);
  const Material beak = mat(20, 140, 220, 10000);
  m.plates.push_back(plate(ellipse({0.0f, 0.0f, 0.0f}, Axis::kZ, 0.2f, 0.045f, 16), body));
  m.plates.push_back(plate(ellipse({0.0f, 0.0f, 0.0f}, Axis::kY, 0.2f, 0.05f, 16), body));
  m.plates.push_back(plate(ellipse({0.2f, 0.025f, 0.0f}, Axis::kZ, 0.045f, 0.04f, 12), body));
  m.plates.push_back(plate({{0.24f, 0.02f, 0}, {0.3f, 0.01f, 0}, {0.24f, 0.0f, 0}}, beak));
  m.plates.push_back(plate({{-0.16f, 0.0f, -0.03f}, {-0.3f, 0.0f, -0.07f}, {-0.3f, 0.0f, 0.07f}, {-0.16f, 0.0f, 0.03f}}, body));
  for (int side : {-1, 1}) {
    const float s = static_cast<float>(side);
    // Inner wing, then the outer wing with notched primaries.
    Plate inner = plate({{0.07f, 0.01f, s * 0.03f}, {0.05f, 0.01f, s * 0.26f}, {-0.08f, 0.01f, s * 0.26f}, {-0.08f, 0.01f, s * 0.03f}}, wing);
    inner.flap = side;
    inner.hinge = P3(0.0f, 0.01f, s * 0.03f);
    m.plates.push_back(inner);
    Plate outer = plate({{0.05f, 0.01f, s * 0.26f}, {-0.01f, 0.01f, s * 0.5f}, {-0.04f, 0.01f, s * 0.47f}, {-0.05f, 0.01f, s * 0.44f},
                         {-0.07f, 0.01f, s * 0.41f}, {-0.08f, 0.01f, s * 0.37f}, {-0.08f, 0.01f, s * 0.26f}}, tip);
    outer.flap = side;
    outer.hinge = inner.hinge;
    m.plates.push_back(outer);
  }
  return m;
}

ShapeModel makeModel(ObstacleClass c, Rng& rng) {
  switch (c) {
    case ObstacleClass::kFixedWing: return makeFixedWing(rng);
    case ObstacleClass::kMultirotor: return makeMultirotor(rng);
    case ObstacleClass::kBird: return makeBird(rng);
  }
  return makeFixedWing(rng);
}

namespace {

struct Rot {
  float m[3][3];
  P3 apply(const P3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
};

Rot mul(const Rot& a, const Rot& b) {
  Rot r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
  return r;
}

Rot rotX(float a) {
  const float c = static_cast<float>(detCos(a)), s = static_cast<float>(detSin(a));
  return {{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
}
Rot rotY(float a) {  // x -> z for positive a (nose towards the camera)
  const float c = static_cast<float>(detCos(a)), s = static_cast<float>(detSin(a));
  return {{{c, 0, -s}, {0, 1, 0}, {s, 0, c}}};
}
Rot rotZ(float a) {
  const float c = static_cast<float>(detCos(a)), s = static_cast<float>(detSin(a));
  return {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}

P3 normalOf(const std::vector<P3>& p) {  // Newell's method
  P3 n(0, 0, 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const P3& a = p[i];
    const P3& b = p[(i + 1) % p.size()];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  const float l = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  return l > 0.0f ? P3(n.x / l, n.y / l, n.z / l) : P3(0, 0, 1);
}

}  // namespace

void projectShape(const ShapeModel& model, const Pose& pose, std::vector<ProjectedPlate>& out) {
  const Rot view = mul(rotZ(pose.roll), mul(rotX(pose.elevation), mul(rotY(pose.yaw), rotX(pose.bank))));
  // Sun direction in view coordinates (x right, y up, z towards the camera).
  const P3 light(0.35f, 0.85f, 0.39f);
  const cv::Point2f light_img(light.x, -light.y);
  const float light_img_len = std::sqrt(light_img.x * light_img.x + light_img.y * light_img.y);
  const std::size_t np = model.plates.size();
  out.resize(np);
  for (std::size_t k = 0; k < np; ++k) {
    const Plate& pl = model.plates[k];
    ProjectedPlate& pp = out[k];
    // Wing flap (flap = +-1): rotate about the body x axis through the hinge, tips up for
    // positive flap; every other plate is only turned by the view.
    const bool flapping = pl.flap == 1 || pl.flap == -1;
    const Rot f = rotX(flapping ? static_cast<float>(pl.flap) * pose.flap : 0.0f);
    pp.pts.resize(pl.pts.size());
    float depth = 0.0f;
    cv::Point2f c(0, 0);
    std::vector<P3> world(pl.pts.size());
    for (std::size_t i = 0; i < pl.pts.size(); ++i) {
      const P3 w = flapping ? view.apply(f.apply(pl.pts[i] - pl.hinge) + pl.hinge) : view.apply(pl.pts[i]);
      world[i] = w;
      pp.pts[i] = cv::Point2f(pose.centre.x + pose.scale * w.x, pose.centre.y - pose.scale * w.y);
      depth += w.z;
      c += pp.pts[i];
    }
    pp.depth = depth / static_cast<float>(pl.pts.size());
    pp.centroid = c * (1.0f / static_cast<float>(pl.pts.size()));
    const P3 n = normalOf(world);
    const float lam = std::fabs(n.x * light.x + n.y * light.y + n.z * light.z);
    const float b = 0.55f + 0.5f * lam;
    pp.bgr = pl.mat.bgr * b;
    pp.thermal = pl.mat.thermal + (b - 0.8f) * 250.0f;
    pp.alpha = pl.alpha;
    // Shading gradient across the plate: brighter towards the sun, +-15 % over its extent.
    float ext = 0.0f;
    for (const auto& p : pp.pts) ext = std::max(ext, std::fabs(p.x - pp.centroid.x) + std::fabs(p.y - pp.centroid.y));
    const float g = ext > 0.5f ? 0.15f / ext / light_img_len : 0.0f;
    pp.gradient = cv::Point2f(light_img.x * g, light_img.y * g);
  }
  // Decals (flap == 2, hinge.x = parent index) sit just in front of their parent.
  for (std::size_t k = 0; k < np; ++k) {
    const Plate& pl = model.plates[k];
    if (pl.flap == 2) out[k].depth = out[static_cast<std::size_t>(pl.hinge.x)].depth + 1e-4f;
  }
  // Far to near (stable: ties keep model order).
  std::vector<std::size_t> order(np);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return out[a].depth < out[b].depth; });
  thread_local std::vector<ProjectedPlate> sorted;
  sorted.resize(np);
  for (std::size_t k = 0; k < np; ++k) std::swap(sorted[k], out[order[k]]);
  std::swap(sorted, out);
}

cv::Rect2f projectedBounds(const std::vector<ProjectedPlate>& plates) {
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (const auto& pl : plates)
    for (const auto& p : pl.pts) {
      x0 = std::min(x0, p.x);
      y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
  if (x1 < x0) return cv::Rect2f();
  return cv::Rect2f(x0, y0, x1 - x0, y1 - y0);
}

}  // namespace scene
}  // namespace obstacle_tracker
