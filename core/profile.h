// Profiles in the meridian half-plane (r, z) and the cases that hold them
// (SPEC sections 2 and 3). Points are Vec2(r, z).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/motion.h"
#include "core/pose.h"
#include "core/vec.h"

namespace revdist {

enum class PieceKind { line, arc, bezier, bspline };

// One piece of a profile chain, kept in its input form so that lines and arcs
// stay exact and curves keep their control polygon.
//   line:    points = {p0, p1}, degree 1
//   arc:     points = {p0, pm, p1} (p0 to p1 through pm), degree 2
//   bezier:  points = control points, degree = points.size() - 1, weights optional
//   bspline: points, knots (clamped, non-decreasing), degree, weights optional
// Degrees are at most kMaxPieceDegree (the case reader enforces it; the
// evaluator, core/curve_eval.h, refuses a higher one with std::invalid_argument).
constexpr int kMaxPieceDegree = 32;
struct Piece {
  PieceKind kind = PieceKind::line;
  int degree = 1;
  std::vector<Vec2> points;
  std::vector<double> weights;  // empty: all 1 (polynomial)
  std::vector<double> knots;    // bspline only

  Vec2 start() const { return points.front(); }
  Vec2 end() const { return points.back(); }
};

// A chain of pieces, each ending where the next starts (up to a joining tolerance).
struct Profile {
  std::vector<Piece> pieces;
  // true: a closed loop with r > 0 (a ring); false: starts and ends on the axis.
  bool closed_loop = false;
};

// A solid: one keyframe when static; K keyframes (same structure) when deformable.
struct SolidDef {
  std::string name;
  std::vector<Profile> keyframes;
  bool deformable() const { return keyframes.size() > 1; }
};

struct Instance {
  std::string name;
  std::size_t solid = 0;  // index into Case::solids
  Pose pose;
  double time = 0.0;      // keyframe time s in [0, K-1]
  InstanceMotion motion;  // frames of `revdist scene` (core/motion.h); frame 0 is `pose`
};

struct Case {
  std::string file;
  std::vector<SolidDef> solids;
  std::vector<Instance> instances;
  std::vector<std::pair<std::size_t, std::size_t>> queries;  // instance indices
};

}  // namespace revdist
