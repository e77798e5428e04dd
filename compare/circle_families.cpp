// Circle-pair families: each named degenerate configuration of the circle
// layer (issue: coaxial, concentric, parallel planes, through the axis, centre
// on the other circle, Villarceau, meridian, mirror symmetry, contact, tilt
// ladders, extreme scales), built in a canonical frame where the distance has a
// closed form, then moved by a random rigid motion.
#include "compare/circle_families.h"

#include "compare/random_geometry.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace revdist {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

Circle3 circle(const Vec3& c, const Vec3& n, double r) { return {c, n, r}; }

CircleFamilyPair finish(const Circle3& a, const Circle3& b, double expected, bool infinite,
                        const Motion& m) {
  CircleFamilyPair out;
  out.pair = {m.apply(a), m.apply(b)};
  out.expected = expected;
  out.infinitely_many = infinite;
  out.scale = circle_pair_scale(out.pair);
  return out;
}

// Distance between coplanar circles with centre distance c: the 2D closed form.
double coplanar_distance(double c, double ra, double rb) {
  return std::max({0.0, c - ra - rb, std::abs(ra - rb) - c});
}

using Maker = CircleFamilyPair (*)(Rng&, int i, int n);

CircleFamilyPair make_random(Rng& rng, int, int) {
  const Circle3 a = circle(rng.box(1), rng.unit(), rng.uniform(0.05, 1.0));
  const Circle3 b = circle(rng.box(1), rng.unit(), rng.uniform(0.05, 1.0));
  return finish(a, b, kNaN, false, Motion{});
}

CircleFamilyPair make_coaxial(Rng& rng, int i, int) {
  // Same axis; i % 4 == 0 makes them concentric and coplanar (h = 0).
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const double h = i % 4 == 0 ? 0.0 : rng.uniform(-1, 1);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(Vec3(0, 0, h), Vec3(0, 0, i % 2 ? 1.0 : -2.5), rb);
  return finish(a, b, std::hypot(ra - rb, h), true, random_motion(rng, 1));
}

CircleFamilyPair make_concentric_tilted(Rng& rng, int, int) {
  // Same centre, planes at an angle: the closest points are where b meets a's plane.
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const double tilt = rng.uniform(0.05, kPi / 2);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(Vec3::Zero(), Vec3(std::sin(tilt), 0, std::cos(tilt)), rb);
  return finish(a, b, std::abs(ra - rb), false, random_motion(rng, 1));
}

CircleFamilyPair make_parallel_planes(Rng& rng, int, int) {
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const double h = rng.uniform(-1, 1), c = rng.uniform(0.01, 2.5);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(Vec3(c, 0, h), Vec3(0, 0, -1), rb);
  return finish(a, b, std::hypot(h, coplanar_distance(c, ra, rb)), false, random_motion(rng, 1));
}

CircleFamilyPair make_coplanar(Rng& rng, int i, int) {
  // Coplanar, disjoint, nested or crossing; i % 5 == 0 makes them tangent (d = 0).
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const double c = i % 5 == 0 ? ra + rb : rng.uniform(0.01, 2.5);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(Vec3(c, 0, 0), Vec3::UnitZ(), rb);
  return finish(a, b, coplanar_distance(c, ra, rb), false, random_motion(rng, 1));
}

CircleFamilyPair make_through_axis(Rng& rng, int, int) {
  // b passes through a point of a's axis: f has a cusp there (a local maximum).
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const Vec3 on_axis(0, 0, rng.uniform(-1, 1));
  const Vec3 nb = rng.unit();
  const Vec3 dir = rng.perpendicular(nb);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(on_axis + rb * dir, nb, rb);
  return finish(a, b, kNaN, false, random_motion(rng, 1));
}

CircleFamilyPair make_centre_on_circle(Rng& rng, int, int) {
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const double phi = rng.uniform(0, 2 * kPi);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(Vec3(ra * std::cos(phi), ra * std::sin(phi), 0), rng.unit(), rb);
  return finish(a, b, kNaN, false, random_motion(rng, 1));
}

CircleFamilyPair make_villarceau(Rng& rng, int i, int) {
  // b is a Villarceau circle of the torus with major circle a (radius R) and
  // minor radius r: every point of b is at distance r from a.
  const double R = rng.uniform(0.5, 1), r = rng.uniform(0.05, 0.45) * R;
  const double s = r / R, c = std::sqrt(1 - s * s);
  const double side = i % 2 ? 1.0 : -1.0;
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), R);
  const Circle3 b = circle(Vec3(0, side * r, 0), Vec3(-s, 0, c), R);
  return finish(a, b, r, true, random_motion(rng, 1));
}

CircleFamilyPair make_meridian(Rng& rng, int i, int) {
  // b lies in a meridian plane of a, centred on a. r_b <= R: a torus' minor
  // circle, constant distance r_b. r_b > R: b crosses the axis and the
  // distance is |r_b - 2R| (the far side of a), attained at one point.
  const double R = rng.uniform(0.3, 1);
  const double rb = i % 2 ? rng.uniform(0.05, 1.0) * R : rng.uniform(1.05, 3.0) * R;
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), R);
  const Circle3 b = circle(Vec3(R, 0, 0), Vec3::UnitY(), rb);
  const double d = rb <= R ? rb : std::abs(rb - 2 * R);
  return finish(a, b, d, rb <= R, random_motion(rng, 1));
}

CircleFamilyPair make_mirror_symmetric(Rng& rng, int, int) {
  // b is symmetric under the reflection y -> -y, which fixes a: minima come in
  // mirror pairs or sit on the mirror plane (double roots of the polynomial).
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const double tilt = rng.uniform(0, kPi);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(Vec3(rng.uniform(-1.5, 1.5), 0, rng.uniform(-1, 1)),
                           Vec3(std::sin(tilt), 0, std::cos(tilt)), rb);
  return finish(a, b, kNaN, false, random_motion(rng, 1));
}

CircleFamilyPair make_intersecting(Rng& rng, int, int) {
  // b passes through a point of a: distance 0.
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const double phi = rng.uniform(0, 2 * kPi);
  const Vec3 p(ra * std::cos(phi), ra * std::sin(phi), 0);
  const Vec3 nb = rng.unit();
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(p + rb * rng.perpendicular(nb), nb, rb);
  // Rounding of the construction moves b off a by ~1e-16; the closed form is 0.
  return finish(a, b, 0.0, false, random_motion(rng, 1));
}

CircleFamilyPair make_tilt_ladder(Rng& rng, int i, int) {
  // Near-coaxial and near-coplanar pairs: tilt 1e-3 ... 1e-12 away from a
  // degenerate configuration. No closed form: the exact engine is the judge.
  const double tilt = std::pow(10.0, -3 - (i % 10));
  const double ra = rng.uniform(0.1, 1), rb = rng.uniform(0.1, 1);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  Circle3 b;
  if (i % 2 == 0)  // near coaxial: axis tilted, centre nudged off the axis
    b = circle(Vec3(tilt * rng.uniform(-1, 1), 0, rng.uniform(-1, 1)), Vec3(std::sin(tilt), 0, std::cos(tilt)), rb);
  else  // near coplanar: tilted and lifted slightly out of a's plane
    b = circle(Vec3(rng.uniform(0.01, 2), 0, tilt * rng.uniform(-1, 1)), Vec3(0, std::sin(tilt), std::cos(tilt)), rb);
  return finish(a, b, kNaN, false, random_motion(rng, 1));
}

CircleFamilyPair make_scaled(Rng& rng, int i, int) {
  // Random pairs at scales 1e-6 ... 1e6.
  const double s = std::pow(10.0, -6 + (i % 13));
  const Circle3 a = circle(s * rng.box(1), rng.unit(), s * rng.uniform(0.05, 1));
  const Circle3 b = circle(s * rng.box(1), rng.unit(), s * rng.uniform(0.05, 1));
  return finish(a, b, kNaN, false, Motion{});
}

CircleFamilyPair make_far_from_origin(Rng& rng, int, int) {
  // Unit-size pairs whose centres are 1e6 from the origin.
  const Vec3 far = 1e6 * rng.unit();
  const Circle3 a = circle(far + rng.box(1), rng.unit(), rng.uniform(0.05, 1));
  const Circle3 b = circle(far + rng.box(1), rng.unit(), rng.uniform(0.05, 1));
  return finish(a, b, kNaN, false, Motion{});
}

CircleFamilyPair make_radius_ratio(Rng& rng, int i, int) {
  // Radius ratios up to 1e6, either circle the big one.
  const double big = 1.0, small = std::pow(10.0, -2 - (i % 5));
  const double ra = i % 2 ? big : small, rb = i % 2 ? small : big;
  const Circle3 a = circle(rng.box(1), rng.unit(), ra);
  const Circle3 b = circle(rng.box(1), rng.unit(), rb);
  return finish(a, b, kNaN, false, Motion{});
}

CircleFamilyPair make_point_circle(Rng& rng, int i, int) {
  // b has radius 0; i % 4 == 0 puts the point on a's axis (all of a equidistant).
  const double ra = rng.uniform(0.1, 1);
  const double h = rng.uniform(-1, 1);
  const double rho = i % 4 == 0 ? 0.0 : rng.uniform(0, 2);
  const Circle3 a = circle(Vec3::Zero(), Vec3::UnitZ(), ra);
  const Circle3 b = circle(Vec3(rho, 0, h), rng.unit(), 0.0);
  return finish(a, b, std::hypot(h, rho - ra), rho == 0.0, random_motion(rng, 1));
}

CircleFamilyPair make_points(Rng& rng, int, int) {
  const Vec3 p = rng.box(1), q = rng.box(1);
  return finish(circle(p, rng.unit(), 0.0), circle(q, rng.unit(), 0.0), (p - q).norm(), false, Motion{});
}

struct Entry {
  CircleFamily family;
  Maker make;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> all = {
      {{"random", "random centres in [-1,1]^3, random normals, radii in [0.05,1]", false}, make_random},
      {{"coaxial", "same axis, incl. concentric coplanar: sqrt(dR^2 + h^2), infinitely many"}, make_coaxial},
      {{"concentric_tilted", "same centre, tilted planes: |Ra - Rb|"}, make_concentric_tilted},
      {{"parallel_planes", "parallel planes, not coaxial: 2D distance plus height"}, make_parallel_planes},
      {{"coplanar", "same plane: disjoint, nested, crossing, tangent"}, make_coplanar},
      {{"through_axis", "b passes through a's axis (cusp of f)"}, make_through_axis},
      {{"centre_on_circle", "b's centre lies on a"}, make_centre_on_circle},
      {{"villarceau", "b a Villarceau circle of the torus around a: constant distance r"}, make_villarceau},
      {{"meridian", "b in a meridian plane, centred on a: r_b, or |r_b - 2R| past the axis"}, make_meridian},
      {{"mirror_symmetric", "b symmetric under a mirror that fixes a (double roots)"}, make_mirror_symmetric},
      {{"intersecting", "b passes through a point of a: distance 0"}, make_intersecting},
      {{"tilt_ladder", "tilt 1e-3 ... 1e-12 from coaxial or coplanar"}, make_tilt_ladder},
      {{"scaled", "random pairs at scales 1e-6 ... 1e6"}, make_scaled},
      {{"far_from_origin", "unit pairs 1e6 from the origin"}, make_far_from_origin},
      {{"radius_ratio", "radius ratios up to 1e6"}, make_radius_ratio},
      {{"point_circle", "radius 0 against a circle, incl. a point on the axis"}, make_point_circle},
      {{"points", "both radii 0"}, make_points},
  };
  return all;
}

}  // namespace

double circle_pair_scale(const CirclePair& p) {
  return std::max({p.a.radius, p.b.radius, (p.a.center - p.b.center).norm()});
}

const std::vector<CircleFamily>& circle_families() {
  static const std::vector<CircleFamily> all = [] {
    std::vector<CircleFamily> v;
    for (const auto& e : entries()) v.push_back(e.family);
    return v;
  }();
  return all;
}

std::vector<CircleFamilyPair> make_circle_family(const std::string& name, int n, std::uint64_t seed) {
  for (const auto& e : entries()) {
    if (e.family.name != name) continue;
    // One stream per family, so adding a family does not change the others.
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a: the same stream on every platform
    for (unsigned char ch : name) h = (h ^ ch) * 1099511628211ull;
    Rng rng(seed ^ h);
    std::vector<CircleFamilyPair> out;
    out.reserve(n);
    for (int i = 0; i < n; ++i) out.push_back(e.make(rng, i, n));
    return out;
  }
  throw std::invalid_argument("unknown circle family \"" + name + "\"");
}

CircleFamilyPair make_circle_family_pair(const std::string& name, long index, std::uint64_t seed) {
  for (const auto& e : entries()) {
    if (e.family.name != name) continue;
    Rng rng(seed);
    // The makers cycle their variants on i with periods 2, 4, 5 and 10 (n is unused).
    return e.make(rng, static_cast<int>(index % 60), 60);
  }
  throw std::invalid_argument("unknown circle family \"" + name + "\"");
}

}  // namespace revdist
