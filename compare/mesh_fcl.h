// The mesh baseline (NOTES.md section 5): inscribed triangle meshes of solids of
// revolution at a chordal error bound, and FCL 0.7 mesh-mesh distance on them.
// Shared by `revdist compare` and `revdist bench`. No FCL header leaks from here.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/profile.h"
#include "core/vec.h"

namespace revdist {

// A closed triangle mesh of the surface of revolution, in the solid's local
// frame. Inscribed: every vertex lies on the true surface (profile points
// rotated), so the mesh is within `eps` of the surface both ways (chordal
// error), and distances between inscribed meshes are biased upward on convex
// parts (NOTES.md section 5).
struct SolidMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  int sectors = 0;  // cuts around the axis: r_max (1 - cos(pi / sectors)) <= eps / 2
  int rings = 0;    // profile samples: every chord within eps / 2 of its curve
  double eps = 0.0;
};

// Meshes the profile at chordal error eps > 0. Lines are one chord each, arcs
// are cut into equal sub-arcs by their closed-form sagitta, curves by recursive
// halving until 15 interior samples of each span lie within eps / 2 of its
// chord (sampling: not a proof, which the report says).
// Throws std::length_error beyond kMaxMeshTriangles (callers check first with
// mesh_triangles, to refuse before any work).
SolidMesh mesh_solid(const Profile& profile, double eps);

// The most triangles one mesh may have: FCL's OBBRSS hierarchy takes ~520 bytes
// a triangle (measured: 834K triangles, 430 MB), so about 2 GB; building one
// of 3.99M triangles peaked at 2.7 GB (the mesh and FCL's copy of it).
constexpr long kMaxMeshTriangles = 4000000;
// The most triangles of the meshes one run holds at once (compare: a case's
// shapes at one eps; bench: the static solids and a deformable one's first
// frame): the paper's five models and Mt at eps 1e-5 hold 3.97M (2.4 GB at
// the run's peak).
constexpr long kMaxMeshTrianglesTogether = 6000000;
// The triangles mesh_solid(profile, eps) would make, -1 beyond kMaxMeshTriangles
// (found without building the mesh; bounded work however small eps is).
long mesh_triangles(const Profile& profile, double eps);
// InputError naming `who` (and ending with `hint`) when the mesh of one
// profile would exceed kMaxMeshTriangles, or the meshes of several, alive
// together, kMaxMeshTrianglesTogether in all: compare and bench refuse before
// any work. (One mesh under the limit each was not enough: two instances of a
// 20000-line ball, 3.99M triangles each, took compare past 4.9 GB.)
void require_meshes_within_limit(const std::vector<const Profile*>& profiles, double eps, const std::string& who,
                                 const std::string& hint);

// An FCL OBBRSS bounding-volume hierarchy of a mesh (opaque: FCL stays in the .cpp).
class FclMesh;
std::shared_ptr<const FclMesh> make_fcl_mesh(const SolidMesh& mesh);
// Bytes of the hierarchy: bounding volumes, triangles, vertices, the model object.
long fcl_mesh_bytes(const FclMesh& mesh);
long fcl_mesh_triangles(const FclMesh& mesh);
// Bounding volumes of the hierarchy (Tables 1-2 of the paper count BVH nodes).
long fcl_mesh_bv_nodes(const FclMesh& mesh);

struct FclDistanceResult {
  // fcl::distance's return value between the two triangle surfaces. 0 when
  // triangles intersect; a positive value when one mesh lies inside the other
  // (FCL measures surfaces, not solids). FCL ignores rel_err / abs_err for
  // mesh-mesh distance, so this is its full-accuracy answer on the meshes.
  double distance = 0.0;
  bool witnesses = false;  // false when distance == 0 (FCL gives no points then)
  Vec3 point_a = Vec3::Zero(), point_b = Vec3::Zero();  // world frame
  double cpu_us = 0.0;  // thread CPU time of the fcl::distance call alone
};

// Distance between mesh a at pose (R_WA, t_WA) and mesh b at (R_WB, t_WB), a
// fresh request and result per call (FCL reuses stale results otherwise).
FclDistanceResult fcl_mesh_distance(const FclMesh& a, const Mat3& R_WA, const Vec3& t_WA, const FclMesh& b,
                                    const Mat3& R_WB, const Vec3& t_WB);

}  // namespace revdist
