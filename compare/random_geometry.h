// Seeded random geometry shared by the circle families and the tests: unit
// vectors, boxes, perpendiculars, rigid motions. Header only (the tests of
// fast/ use it without linking compare/).
#pragma once
#include <cstdint>
#include <random>

#include "core/circle3.h"
#include "core/vec.h"

namespace revdist {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : gen_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen_); }
  // A uniformly distributed unit vector.
  Vec3 unit() {
    std::normal_distribution<double> g;
    Vec3 v;
    do { v = Vec3(g(gen_), g(gen_), g(gen_)); } while (v.squaredNorm() < 1e-12);
    return v.normalized();
  }
  Vec3 box(double s) { return Vec3(uniform(-s, s), uniform(-s, s), uniform(-s, s)); }
  // A unit vector perpendicular to n.
  Vec3 perpendicular(const Vec3& n) {
    Vec3 v;
    do { v = unit().cross(n); } while (v.squaredNorm() < 1e-6);
    return v.normalized();
  }
  std::mt19937_64& gen() { return gen_; }

 private:
  std::mt19937_64 gen_;
};

struct Motion {
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  Circle3 apply(const Circle3& c) const { return {R * c.center + t, R * c.normal, c.radius}; }
};

// A uniformly random rotation and a translation in [-translation, translation]^3.
inline Motion random_motion(Rng& rng, double translation) {
  const Eigen::Quaterniond q(Eigen::Vector4d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1),
                                             rng.uniform(-1, 1)).normalized());
  return {q.toRotationMatrix(), rng.box(translation)};
}

}  // namespace revdist
