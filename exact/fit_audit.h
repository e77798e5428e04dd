// Certified error of a biarc fit (paper section 4.1; SPEC section 6, last
// bullet): an interval-arithmetic proof of an upper bound on the two-sided
// Hausdorff distance between an input curve part and the arcs that replace it.
// The theorem and the method are stated in exact/fit_audit.cpp. This header
// includes no CGAL/GMP/MPFR header on purpose (the CLI includes it).
#pragma once
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/arc2.h"
#include "core/profile.h"

namespace revdist {

struct FitAudit {
  bool certified = false;      // false: could not certify (reason says why); certified_error is then +inf
  double certified_error = std::numeric_limits<double>::infinity();
  // A PROVEN upper bound (rounded up) on the two-sided Hausdorff distance.
  double lower_bound = 0.0;    // a proven lower bound (rounded down) on the same distance
  std::string reason;          // why not certified; empty otherwise
  int nodes = 0;               // parameter sub-intervals examined (work done)
};

// Certifies the fit of piece[u0, u1] (parameters as in core/curve_eval.h: arcs
// uniform in angle on the exact circle through their three points, splines by
// their exact knots, weights and control points) by the chain arcs[0..n_arcs)
// (usually the two arcs of a biarc, or one exact arc or segment for an input
// line or arc). Each Arc2 is the set { Arc2::point(s) : 0 <= s <= length }
// computed exactly from its double fields; if the stored tangent is read as
// normalised instead, the bound still holds (the difference is included).
// Consecutive arcs need not join exactly. An arc of length 0 is a point.
//
// target: refinement stops once the bound is <= target (pass the claimed eps)
// or cannot come down further (it is then still a proven upper bound, possibly
// larger than target). Never throws; a failure is data (certified = false).
FitAudit audit_fit(const Piece& piece, double u0, double u1, const Arc2* arcs, int n_arcs, double target);

// One leaf of a biarc tree, as an audit needs it.
struct FitLeaf {
  const Piece* piece = nullptr;
  double u0 = 0.0, u1 = 0.0;
  const Arc2* arcs = nullptr;
  int n_arcs = 0;
  double claimed = 0.0;  // the fitter's eps for this leaf (the audit's target)
};

struct TreeAudit {
  int leaves = 0, certified = 0;
  // Leaves whose proven lower bound exceeds the claimed eps: a fitter bug.
  int violations = 0;
  // Leaves whose certified bound exceeds the claimed eps while the proven lower
  // bound does not: the audit could not confirm the claim (its bound stalls at
  // a point on some degree-32 leaves: certified 1.1e-4, lower 1.04e-5, claim
  // 2.3e-5, sampled 1.04e-5), which is no proof of a fitter bug either.
  int unconfirmed = 0;
  double max_certified_error = 0.0;  // over certified leaves
  double max_lower_bound = 0.0;      // proven lower bound of the worst leaf error
  std::size_t worst_leaf = 0;        // index of the leaf with max_certified_error
  std::size_t first_problem = static_cast<std::size_t>(-1);  // first violation or uncertified leaf
  std::string first_problem_reason;
  long long nodes = 0;
  double time_ms = 0.0;
};

// Audits every leaf; per_leaf (optional) receives each result. tight = false:
// each leaf's target is its claimed eps (cheapest; a certified error just under
// the claim proves the claim but says little more). tight = true: target 0, so
// refinement goes on until the bound is within 5% of the proven lower bound (or
// the node budget ends): the certified error then measures the fit itself.
// progress (optional) is told after each leaf how many are done.
TreeAudit audit_leaves(const std::vector<FitLeaf>& leaves, std::vector<FitAudit>* per_leaf = nullptr,
                       bool tight = false, const std::function<void(std::size_t)>& progress = {});

// The leaves of a biarc tree (fast/biarc_tree.h: BiarcTree) over `profile`.
// A template so that exact/ does not depend on fast/ (STYLE: core <- fast,
// core <- exact); whoever holds both (compare/, cli/) instantiates it. Reads
// only nodes[i].leaf(), nodes[i].fit and fits[f].{arc, arcs, u0, u1, piece, eps}.
template <class BiarcTreeT>
std::vector<FitLeaf> biarc_tree_leaves(const Profile& profile, const BiarcTreeT& tree) {
  std::vector<FitLeaf> out;
  for (const auto& node : tree.nodes) {
    if (!node.leaf() || node.fit < 0) continue;
    const auto& f = tree.fits[static_cast<std::size_t>(node.fit)];
    FitLeaf leaf;
    leaf.piece = &profile.pieces[static_cast<std::size_t>(f.piece)];
    leaf.u0 = f.u0;
    leaf.u1 = f.u1;
    leaf.arcs = f.arc;
    leaf.n_arcs = static_cast<int>(f.arcs);
    leaf.claimed = f.eps;
    out.push_back(leaf);
  }
  return out;
}

}  // namespace revdist
