// The biarc tree of a profile (paper section 4.1, Algorithm 1): a binary tree
// over the spirals of the profile whose spiral-level subtrees subdivide each
// spiral at the mid parameter until the proven biarc error is below eps.
//
// Every node carries a capsule in (r, z): a segment and a radius such that the
// node's part of the profile lies within the radius of the segment. Rotated,
// the segment is a truncated cone (or cylinder, or flat annulus) and the
// capsule is its radius-neighbourhood, because a point's distance to a surface
// of revolution is attained in its own meridian half-plane; so
// dist(node A, node B) >= dist(cone A, cone B) - radius A - radius B.
// Nodes at and below the spiral level also carry a biarc with its proven
// two-sided Hausdorff bound eps (fat tori when rotated, tighter than the cone);
// leaves are the nodes whose eps <= the requested eps.
//
// Storage is flat (two arrays, children adjacent, depth first, so leaves come
// in profile order) and rebuilding into an existing tree reuses its capacity:
// a deformable solid rebuilt at a new time allocates nothing once warmed up
// (core/curve_eval's evaluator aside).
//
// Lazy trees (issue 8) stop at every proven inner node at or below the spiral
// level and keep its span instead ("pending"); a query reads the tree through
// a BiarcTreeView, which builds a pending node's children, with the same code
// and so the same numbers as the eager build, when the traversal first splits
// it. Parts of a profile no query reaches are never fitted: a deformable solid
// at a new time costs what its queries touch, not a whole rebuild.
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/arc2.h"
#include "core/profile.h"
#include "fast/biarc_fit.h"
#include "fast/spiral_split.h"

namespace revdist {

struct BiarcNode {
  Vec2 seg_a = Vec2::Zero(), seg_b = Vec2::Zero();  // the best-fit segment (a cone when rotated)
  double radius = 0.0;  // proven: the node's profile part is within `radius` of the segment
  // First child; the second is child + 1. -1 for a leaf; <= -2 for a pending
  // node of a lazy tree (children not built; its span is pending[-2 - child]).
  std::int32_t child = -1;
  std::int32_t fit = -1;    // index into BiarcTree::fits; -1 above the spiral level
  bool leaf() const { return child == -1; }
  bool pending() const { return child < -1; }
};

// The biarc of one node at or below the spiral level, with what an audit needs
// to certify it independently: the source piece and parameter range.
struct BiarcFit {
  Arc2 arc[2];             // G1 chain from C(u0) to C(u1); arc[1] has length 0 when arcs == 1
  double eps = 0.0;        // proven two-sided Hausdorff bound (rounding slack included); +inf if unproven
  double u0 = 0.0, u1 = 0.0;
  std::int32_t piece = 0;
  SpanKind kind = SpanKind::curve;
  std::uint8_t arcs = 2;   // 1: an exact input line or arc (part), 2: a biarc
  std::uint8_t depth = 0;  // below the spiral root

  // The fit's ends: C(u0) and C(u1) as the arcs store them.
  Vec2 start() const { return arc[0].start; }
  Vec2 end() const { return arc[arcs - 1].end(); }
};

struct BiarcTree {
  std::vector<BiarcNode> nodes;  // nodes[0] is the root (empty for an empty profile)
  std::vector<BiarcFit> fits;
  std::vector<SpiralSpan> spirals;  // the spirals the tree was built over, in chain order
  double eps = 0.0;        // requested bound
  double max_error = 0.0;  // max eps over the leaves (claimed, proven by the lens bound)
  double slack = 0.0;      // rounding allowance added to every proven bound (64 ulp of the profile's size)
  double exact_length = 0.0;  // exact lines and arcs are split down to this length
  // Lazy trees: the spans of the pending nodes.
  bool lazy = false;
  std::vector<SpiralSpan> pending;

  // Bytes of the tree proper (nodes and fits); the spiral list is build input.
  std::size_t bytes() const { return nodes.size() * sizeof(BiarcNode) + fits.size() * sizeof(BiarcFit); }
};

struct BuildStats {
  int pieces = 0;
  int spirals = 0;
  int nodes = 0;
  int leaves = 0;
  std::size_t bytes = 0;
  double max_error = 0.0;  // claimed (proven) bound over the leaves
  int max_depth = 0;       // deepest biarc subdivision below a spiral root
  int unproven = 0;        // leaves whose spiral hypotheses failed (eps = inf); 0 expected
  int depth_limited = 0;   // leaves that hit the depth limit before reaching eps
};

// The parameter at which a curve span is halved: its middle, unless a
// B-spline knot lies within 1e-6 of the span of one of its ends. Halving could
// not reach such a knot within the depth limit (knots [0,0,0,0,1e-20,1,1,1,1]:
// the curve travels a finite way within [0, 1e-20], and the leaf [0, 6.9e-13]
// claimed 0.5), so the span is cut there.
double split_parameter(const Piece& piece, double u0, double u1);

// Hermite data of the two halves of a span (ends e) at um = split_parameter,
// the split of Algorithm 1 (also used to refine leaves during a distance query).
void split_span(const Piece& piece, double um, const SpanEnds& e, SpanEnds* left, SpanEnds* right);

// The biarc fit of curve span piece[u0, u1] (end data e, `mid` the curve's
// point at the mid parameter), its proven eps (lens width + slack; +inf when
// the spiral hypotheses fail) and its capsule (radius +inf then). A span so
// flat that both arcs turn less than 1e-7 rad is fitted by its chord instead
// (one straight arc; eps the lens's height over the chord + slack) when that
// eps is at most chord_eps: the patch kernels lose their accuracy on tori a
// million times larger than their arcs.
BiarcFit fit_curve_span(const Piece& piece, std::int32_t piece_index, double u0, double u1, const SpanEnds& e,
                        const Vec2& mid, double slack, Capsule* capsule,
                        double chord_eps = std::numeric_limits<double>::infinity());

// Builds the tree of `profile` with requested error bound eps > 0; lazy: down
// to the spiral level (and below only where a node is unproven), the rest on demand.
BiarcTree build_biarc_tree(const Profile& profile, double eps, BuildStats* stats = nullptr, bool lazy = false);

// The same, into `tree`, reusing its storage (the deformable hot path).
void rebuild_biarc_tree(const Profile& profile, double eps, BiarcTree& tree, BuildStats* stats = nullptr,
                        bool lazy = false);

// One query's read access to a tree: a lazy tree's pending nodes are expanded
// into this view when first split (per query: the shared tree is never
// written, so queries on any number of threads need no lock, and a node two
// queries both reach is built by each). An eager tree is read as it is.
// Indices are global: below the tree's own counts they are the tree's.
class BiarcTreeView {
 public:
  BiarcTreeView(const BiarcTree& tree, const Profile& profile);
  const BiarcNode& node(std::int32_t i) const { return i < base_nodes_ ? tree_.nodes[i] : ext_.nodes[i - base_nodes_]; }
  const BiarcFit& fit(std::int32_t i) const { return i < base_fits_ ? tree_.fits[i] : ext_.fits[i - base_fits_]; }
  // The first child of inner node i (the second is + 1), built now when pending.
  // References from node() and fit() do not survive it.
  std::int32_t children(std::int32_t i) {
    const std::int32_t c = node(i).child;
    return c >= 0 ? c : expand(i);
  }
  long nodes_built() const { return static_cast<long>(ext_.nodes.size()); }

 private:
  std::int32_t expand(std::int32_t i);
  const BiarcTree& tree_;
  const Profile& profile_;
  std::int32_t base_nodes_, base_fits_, base_pending_;
  BiarcTree ext_;                       // nodes, fits and pending spans built by this view
  std::vector<std::int32_t> expanded_;  // per pending node of the tree: its first child here, or -1
};

}  // namespace revdist
