// An independent check of the distance engines on the true (input) surfaces:
// nearest points on a profile, the support function of a solid, and a dense
// brute force with Newton refinement that returns genuine surface points.
// Uses only core/ curve evaluation, never the biarc trees or fast/ kernels.
#pragma once
#include <vector>

#include "core/profile.h"
#include "core/vec.h"

namespace revdist {

// A profile with dense samples, for nearest points in the meridian half-plane.
class ProfileNearest {
 public:
  ProfileNearest(const Profile& profile, int samples_per_piece = 256);
  // Distance from q = (r, z) to the profile curves (the nearest sample, then
  // safeguarded Newton on the piece parameter). The foot is a point of the
  // curve, so the value is never below the true distance (to rounding).
  double distance(const Vec2& q, Vec2* foot = nullptr) const;
  // Ray parity of q against the sample polyline: inside the solid? Right when q
  // is farther from the curve than the polyline's chordal error.
  bool inside(const Vec2& q) const;
  const Profile& profile() const { return *profile_; }
  double size() const { return size_; }  // largest |coordinate| of the samples

 private:
  const Profile* profile_;
  std::vector<Vec2> pts_;
  std::vector<int> piece_;
  std::vector<double> u_;
  double size_ = 0.0;
};

// A solid at a pose: world = R * local + t.
struct PosedProfile {
  const ProfileNearest* nearest = nullptr;
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  // (rho, z) of a world point in the solid's meridian half-plane.
  Vec2 local_rz(const Vec3& x_W, Vec3* e_r = nullptr) const;
  // Distance of a world point from the surface.
  double surface_distance(const Vec3& x_W) const;
};

struct BruteResult {
  double distance = 0.0;  // |point_a - point_b|: an upper bound of the surface distance
  Vec3 point_a = Vec3::Zero(), point_b = Vec3::Zero();
};

// Brute force of the distance between two posed surfaces: a grid of n_u points
// per piece by n_theta angles on each surface, each measured exactly against
// the other surface in its meridian plane (a point's distance to a surface of
// revolution is its 2D distance to the profile there), then Newton on the grid
// point's (u, theta) from the best `keep` starts, both ways. Every returned
// pair is genuine, so the value is >= the surface distance, which is >= the
// solid distance; when the surfaces are apart and not nested it equals the
// solid distance to the refinement's accuracy.
BruteResult brute_surface_distance(const PosedProfile& a, const PosedProfile& b, int n_u = 24, int n_theta = 48,
                                   int keep = 4);

// Support function of a solid of revolution in local direction n (unit):
// max over the solid of n . x = max over the profile of r * |n_xy| + z * n_z.
// Closed forms for lines and arcs, samples + Newton for curves.
double profile_support(const Profile& profile, const Vec3& n_local);

}  // namespace revdist
