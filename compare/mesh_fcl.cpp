// Inscribed meshes of solids of revolution and FCL 0.7 mesh-mesh distance (the
// baseline of `revdist compare` and `revdist bench`; NOTES.md section 5).
#include "compare/mesh_fcl.h"
#include "compare/thread_clock.h"

#include <fcl/fcl.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "core/curve_eval.h"
#include "core/input_error.h"

namespace revdist {

namespace {

// Parameters of one piece's chords, u0 first, each chord within eps / 2 of the
// curve; false (and *us unusable) once more than `cap` chords would be needed.
bool piece_breaks(const Piece& piece, double eps, std::size_t cap, std::vector<double>* us_out) {
  std::vector<double>& us = *us_out;
  const auto [u0, u1] = piece_domain(piece);
  us = {u0};
  if (piece.kind == PieceKind::line) {
    us.push_back(u1);
    return true;
  }
  if (piece.kind == PieceKind::arc) {
    // Sagitta of a sub-arc of angle a: R (1 - cos(a / 2)) <= eps / 2.
    const ArcGeometry g = arc_geometry(piece);
    const double c = 1.0 - 0.5 * eps / g.radius;
    const double max_angle = c <= -1.0 ? M_PI : 2.0 * std::acos(std::max(-1.0, c));
    const double nd = std::max(1.0, std::ceil(std::abs(g.sweep) / max_angle));  // inf when eps is lost in rounding
    if (!(nd <= static_cast<double>(cap))) return false;
    const int n = static_cast<int>(nd);
    for (int i = 1; i <= n; ++i) us.push_back(i == n ? u1 : u0 + (u1 - u0) * i / n);
    return true;
  }
  bool over = false;
  std::function<void(double, double, int)> split = [&](double a, double b, int depth) {
    if (over) return;
    const Vec2 pa = piece_point(piece, a), pb = piece_point(piece, b);
    double dev = 0.0;
    for (int k = 1; k < 16; ++k)
      dev = std::max(dev, point_segment_distance(piece_point(piece, a + (b - a) * k / 16), pa, pb));
    if (dev > 0.5 * eps && depth < 40) {
      split(a, 0.5 * (a + b), depth + 1);
      split(0.5 * (a + b), b, depth + 1);
    } else {
      us.push_back(b);
      over = us.size() > cap;
    }
  };
  split(u0, u1, 0);
  return !over;
}

// The profile points and the sectors of the mesh at eps; false when it would
// have more than max_triangles triangles.
struct MeshPlan {
  std::vector<Vec2> pts;
  int sectors = 0;
  long triangles = 0;
};
bool plan_mesh(const Profile& profile, double eps, long max_triangles, MeshPlan* plan) {
  std::vector<Vec2>& pts = plan->pts;
  // At least 8 sectors, each chord off the axis 1 or 2 triangles a sector.
  const std::size_t cap = static_cast<std::size_t>(max_triangles / 8) + 2;
  std::vector<double> us;
  for (const Piece& piece : profile.pieces) {
    if (!piece_breaks(piece, eps, cap, &us)) return false;
    // Pieces join exactly (case_io makes joins exact): skip the repeated start.
    for (std::size_t k = pts.empty() ? 0 : 1; k < us.size(); ++k) pts.push_back(piece_point(piece, us[k]));
    if (pts.size() > cap) return false;
  }
  double rmax = 0.0;
  for (const Vec2& q : pts) rmax = std::max(rmax, q.x());
  const double c = 1.0 - 0.5 * eps / std::max(rmax, 1e-300);
  const double sd = c <= -1.0 ? 8.0 : std::max(8.0, std::ceil(M_PI / std::acos(std::max(-1.0, c))));
  if (!(sd <= static_cast<double>(max_triangles))) return false;  // inf when eps is lost in rounding
  plan->sectors = static_cast<int>(sd);
  plan->triangles = 0;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const bool a0 = pts[k].x() == 0, b0 = pts[k + 1].x() == 0;
    if (!(a0 && b0)) plan->triangles += (a0 || b0 ? 1 : 2) * static_cast<long>(plan->sectors);
  }
  return plan->triangles <= max_triangles;
}

fcl::Transform3d transform(const Mat3& R, const Vec3& t) {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = R;
  X.translation() = t;
  return X;
}

}  // namespace

long mesh_triangles(const Profile& profile, double eps) {
  MeshPlan plan;
  return plan_mesh(profile, eps, kMaxMeshTriangles, &plan) ? plan.triangles : -1;
}

void require_meshes_within_limit(const std::vector<const Profile*>& profiles, double eps, const std::string& who,
                                 const std::string& hint) {
  const long limit = profiles.size() == 1 ? kMaxMeshTriangles : kMaxMeshTrianglesTogether;
  long total = 0;
  for (const Profile* p : profiles) {
    MeshPlan plan;
    if (!plan_mesh(*p, eps, std::min(kMaxMeshTriangles, limit - total), &plan)) {
      total = -1;
      break;
    }
    total += plan.triangles;
  }
  if (total >= 0) return;
  char e[32];
  std::snprintf(e, sizeof e, "%.3g", eps);
  throw InputError(who + ": " + (profiles.size() == 1 ? "its FCL mesh" : "its FCL meshes") + " at --eps " + e +
                   " would exceed " + std::to_string(limit) + " triangles" +
                   (profiles.size() == 1 ? " (~2.7 GB); " : " together (~4 GB); ") + hint);
}

SolidMesh mesh_solid(const Profile& profile, double eps) {
  SolidMesh m;
  m.eps = eps;
  MeshPlan plan;
  if (!plan_mesh(profile, eps, kMaxMeshTriangles, &plan))
    throw std::length_error("mesh at eps " + std::to_string(eps) + " beyond " + std::to_string(kMaxMeshTriangles) +
                            " triangles");
  const std::vector<Vec2>& pts = plan.pts;
  m.sectors = plan.sectors;
  m.rings = static_cast<int>(pts.size());
  const int nt = m.sectors;
  std::vector<int> ring_start;
  for (const Vec2& q : pts) {
    ring_start.push_back(static_cast<int>(m.vertices.size()));
    if (q.x() == 0) {  // a pole: one vertex on the axis
      m.vertices.emplace_back(0, 0, q.y());
      continue;
    }
    for (int j = 0; j < nt; ++j)
      m.vertices.emplace_back(q.x() * std::cos(2 * M_PI * j / nt), q.x() * std::sin(2 * M_PI * j / nt), q.y());
  }
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const bool a0 = pts[k].x() == 0, b0 = pts[k + 1].x() == 0;
    if (a0 && b0) continue;  // a chord along the axis bounds no surface
    const int sa = ring_start[k], sb = ring_start[k + 1];
    for (int j = 0; j < nt; ++j) {
      const int j1 = (j + 1) % nt;
      if (a0) {
        m.triangles.push_back({sa, sb + j, sb + j1});
      } else if (b0) {
        m.triangles.push_back({sa + j, sb, sa + j1});
      } else {
        // The two rings' chords at one sector form a planar isosceles trapezoid.
        m.triangles.push_back({sa + j, sb + j, sb + j1});
        m.triangles.push_back({sa + j, sb + j1, sa + j1});
      }
    }
  }
  return m;
}

class FclMesh {
 public:
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> bvh;
  long triangles = 0;
};

std::shared_ptr<const FclMesh> make_fcl_mesh(const SolidMesh& mesh) {
  std::vector<fcl::Vector3d> v(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> t;
  t.reserve(mesh.triangles.size());
  for (const auto& tri : mesh.triangles) t.emplace_back(tri[0], tri[1], tri[2]);
  auto m = std::make_shared<FclMesh>();
  m->bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  m->bvh->beginModel();
  m->bvh->addSubModel(v, t);
  m->bvh->endModel();
  m->triangles = static_cast<long>(t.size());
  return m;
}

// FCL 0.7's BVHModel::memUsage adds these same terms but returns BVH_OK (0), so they are summed here.
long fcl_mesh_bytes(const FclMesh& mesh) {
  const auto& m = *mesh.bvh;
  return static_cast<long>(sizeof(fcl::OBBRSSd)) * m.getNumBVs() + static_cast<long>(sizeof(fcl::Triangle)) * m.num_tris +
         static_cast<long>(sizeof(fcl::Vector3d)) * m.num_vertices + static_cast<long>(sizeof(m));
}
long fcl_mesh_triangles(const FclMesh& mesh) { return mesh.triangles; }
long fcl_mesh_bv_nodes(const FclMesh& mesh) { return mesh.bvh->getNumBVs(); }

FclDistanceResult fcl_mesh_distance(const FclMesh& a, const Mat3& R_WA, const Vec3& t_WA, const FclMesh& b,
                                    const Mat3& R_WB, const Vec3& t_WB) {
  fcl::CollisionObjectd oa(a.bvh, transform(R_WA, t_WA)), ob(b.bvh, transform(R_WB, t_WB));
  fcl::DistanceRequestd req;
  req.enable_nearest_points = true;
  fcl::DistanceResultd res;
  FclDistanceResult out;
  const double c0 = thread_cpu_us();
  out.distance = fcl::distance(&oa, &ob, req, res);
  out.cpu_us = thread_cpu_us() - c0;
  // The return value, not res.min_distance (read back garbage with the Debian build,
  // compare/bench_distance.cpp); the witnesses are checked against it by the tests.
  out.distance = std::max(out.distance, 0.0);
  out.witnesses = out.distance > 0;
  if (out.witnesses) {
    out.point_a = res.nearest_points[0];
    out.point_b = res.nearest_points[1];
  }
  return out;
}

}  // namespace revdist
