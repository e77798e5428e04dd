// Biarc tree construction (paper section 4.1, Algorithm 1): spirals, then a
// balanced capsule tree over them, then per spiral a mid-parameter biarc
// subdivision until the lens bound (fast/biarc_fit.h) is below eps.
#include "fast/biarc_tree.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "core/curve_eval.h"
#include "core/profile_check.h"
#include "fast/biarc_fit.h"

namespace revdist {

namespace {

// Deep enough for eps ~ 1e-15 of the profile size (cubic convergence), shallow
// enough to stop a runaway split of a span whose hypotheses cannot hold.
constexpr int kMaxDepth = 40;
// Arcs turning less than this (radians) are fitted by the chord (fit_curve_span).
constexpr double kFlatSweep = 1e-7;

// The longest leaf of an exact line or arc, as a fraction of the profile's
// extent: 1/4 at eps 1e-3 of the extent, halved every two decades of eps
// (1/8 at 1e-5, 1/16 at 1e-7), within [1/64, 1/4]. A long exact leaf costs
// the traversal where it meets small fits (its disk is loose by half its
// length; the query's fit spine bound recovers most of that), a short one
// costs nodes everywhere: measured on the motion probe (M instructions for
// 600 queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6) with 1/16 at every eps
// 88.3 / 76.4 / 147.2 / 121.4, 1/8 86.4 / 75.1 / 149.1 / 120.0, 1/4 88.4 /
// 72.9 / 155.7 / 123.7, 1/32 97.6 / 84.2 / 147.5 / 130.4.
double exact_fraction(double eps, double extent) {
  if (!(extent > 0) || !(eps > 0)) return 1.0 / 16;
  return std::clamp(0.25 * std::pow(1e3 * eps / extent, std::log(2.0) / std::log(100.0)), 1.0 / 64, 0.25);
}

// Builds nodes into `tree`. Node, fit and pending indices are global: those
// below the base counts belong to a shared tree that is never written (a lazy
// tree's own nodes, when a query's view expands them), the rest to `tree`.
struct Builder {
  const Profile& profile;
  double eps;
  double slack;  // rounding allowance added to every proven bound
  double max_exact_length;  // exact lines and arcs are split below this length
  BiarcTree& tree;
  bool lazy = false;  // stop below a proven inner node: mark it pending instead
  std::int32_t base_nodes = 0, base_fits = 0, base_pending = 0;
  BuildStats st{};

  BiarcNode& node_at(std::int32_t i) { return tree.nodes[i - base_nodes]; }

  std::int32_t alloc_pair() {
    const auto i = static_cast<std::int32_t>(tree.nodes.size());
    tree.nodes.resize(tree.nodes.size() + 2);
    return base_nodes + i;
  }

  void set_capsule(std::int32_t node, const Capsule& c) {
    BiarcNode& n = node_at(node);
    n.seg_a = c.a;
    n.seg_b = c.b;
    n.radius = c.radius;
  }

  Capsule capsule_of(std::int32_t node) {
    const BiarcNode& n = node_at(node);
    return Capsule{n.seg_a, n.seg_b, n.radius};
  }

  std::int32_t add_fit(const BiarcFit& f) {
    tree.fits.push_back(f);
    return base_fits + static_cast<std::int32_t>(tree.fits.size() - 1);
  }

  // Records the children of `node`; a shared tree's node is not written (the view records them).
  void link(std::int32_t node, std::int32_t c) {
    if (node >= base_nodes) node_at(node).child = c;
  }

  // Lazy: the node's children are built when a query first asks for them.
  void set_pending(std::int32_t node, const SpiralSpan& s) {
    tree.pending.push_back(s);
    node_at(node).child = -2 - (base_pending + static_cast<std::int32_t>(tree.pending.size() - 1));
  }

  void note_leaf(const BiarcFit& f) {
    ++st.leaves;
    st.max_error = std::max(st.max_error, f.eps);
    st.max_depth = std::max(st.max_depth, static_cast<int>(f.depth));
  }

  // An input line or a (<= 90 degree) part of an input arc: exact Arc2s, split
  // in halves until no longer than max_exact_length. Their error is only
  // rounding either way; the split keeps their bounding disks small, which is
  // what the distance traversal's lower bounds are made of (a long segment's
  // disk is loose by half its length).
  void build_exact(std::int32_t node, const SpiralSpan& s) {
    const Piece& piece = profile.pieces[s.piece];
    double length;
    if (s.kind == SpanKind::line) {
      length = (s.ends.p1 - s.ends.p0).norm();
    } else {
      const ArcGeometry g = arc_geometry(piece);
      length = g.radius * std::abs(g.sweep) * (s.u1 - s.u0);
    }
    const double um = 0.5 * (s.u0 + s.u1);
    if (length > max_exact_length && s.u0 < um && um < s.u1) {
      // The node keeps the whole exact arc as its fit (bounds for the traversal).
      node_at(node).fit = add_fit(exact_fit(s, length));
      set_capsule(node, lens_capsule_of(s.ends));
      if (lazy) set_pending(node, s);
      else expand_exact(node, s);
      return;
    }
    const BiarcFit f = exact_fit(s, length);
    set_capsule(node, lens_capsule_of(s.ends));
    node_at(node).fit = add_fit(f);
    note_leaf(f);
  }

  // The two halves of an exact span (build_exact's split); returns the first child.
  std::int32_t expand_exact(std::int32_t node, const SpiralSpan& s) {
    const Piece& piece = profile.pieces[s.piece];
    const double um = 0.5 * (s.u0 + s.u1);
    SpiralSpan left = s, right = s;
      left.u1 = um;
      left.ends.p1 = piece_tangent(piece, um, -1, &left.ends.t1, &left.ends.k1);
      right.u0 = um;
      right.ends.p0 = left.ends.p1;
      right.ends.t0 = left.ends.t1;
      right.ends.k0 = left.ends.k1;
    const std::int32_t c = alloc_pair();
    link(node, c);
    build_exact(c, left);
    build_exact(c + 1, right);
    return c;
  }

  // The one exact Arc2 of an input line or arc span.
  BiarcFit exact_fit(const SpiralSpan& s, double length) const {
    BiarcFit f;
    f.piece = s.piece;
    f.kind = s.kind;
    f.u0 = s.u0;
    f.u1 = s.u1;
    f.arcs = 1;
    Arc2& a = f.arc[0];
    a.start = s.ends.p0;
    a.tangent = s.ends.t0;
    a.curvature = s.kind == SpanKind::line ? 0.0 : s.ends.k0;
    a.length = length;
    f.arc[1] = Arc2{a.end(), a.end_tangent(), a.curvature, 0.0};
    f.eps = slack;
    return f;
  }

  Capsule lens_capsule_of(const SpanEnds& e) const {
    Capsule c = lens_capsule(e, lens_bound(e));
    c.radius += slack;
    return c;
  }

  void build_curve(std::int32_t node, const Piece& piece, std::int32_t piece_index, double u0, double u1,
                   const SpanEnds& e, int depth) {
    const double um = split_parameter(piece, u0, u1);
    SpanEnds left, right;
    split_span(piece, um, e, &left, &right);
    Capsule cap;
    BiarcFit f = fit_curve_span(piece, piece_index, u0, u1, e, left.p1, slack, &cap, eps);
    f.depth = static_cast<std::uint8_t>(depth);
    node_at(node).fit = add_fit(f);
    const bool proven = f.eps < std::numeric_limits<double>::infinity();

    const bool leaf = (proven && f.eps <= eps) || depth >= kMaxDepth || !(u0 < um && um < u1);
    if (leaf) {
      node_at(node).child = -1;
      if (proven) {
        set_capsule(node, cap);
        if (f.eps > eps) ++st.depth_limited;
      } else {
        // Nothing is proven about this part: a capsule that bounds nothing.
        set_capsule(node, Capsule{e.p0, e.p1, std::numeric_limits<double>::infinity()});
        ++st.unproven;
      }
      note_leaf(f);
      return;
    }
    if (proven && lazy) {
      set_capsule(node, cap);
      SpiralSpan span;
      span.piece = piece_index;
      span.u0 = u0;
      span.u1 = u1;
      span.ends = e;
      set_pending(node, span);
      return;
    }
    // Unproven inner nodes are built eagerly even in a lazy tree: their capsule is their children's union.
    const std::int32_t c = expand_curve(node, piece, piece_index, u0, um, u1, left, right, depth);
    if (proven) {
      set_capsule(node, cap);
    } else {
      set_capsule(node, capsule_union(capsule_of(c), capsule_of(c + 1)));
    }
  }

  // The two halves of a curve span, split at um (ends `left`, `right`: split_span's); returns the first child.
  std::int32_t expand_curve(std::int32_t node, const Piece& piece, std::int32_t piece_index, double u0, double um,
                            double u1, const SpanEnds& left, const SpanEnds& right, int depth) {
    const std::int32_t c = alloc_pair();
    link(node, c);
    build_curve(c, piece, piece_index, u0, um, left, depth + 1);
    build_curve(c + 1, piece, piece_index, um, u1, right, depth + 1);
    return c;
  }

  // Builds the children of pending node `node` (span s, the fit's depth).
  std::int32_t expand(std::int32_t node, const SpiralSpan& s, int depth) {
    if (s.kind == SpanKind::curve) {
      const Piece& piece = profile.pieces[s.piece];
      const double um = split_parameter(piece, s.u0, s.u1);
      SpanEnds left, right;
      split_span(piece, um, s.ends, &left, &right);
      return expand_curve(node, piece, s.piece, s.u0, um, s.u1, left, right, depth);
    }
    return expand_exact(node, s);
  }

  void build_spiral(std::int32_t node, const SpiralSpan& s) {
    if (s.kind == SpanKind::curve && !s.proven) {
      // The split could not prove the spiral hypotheses here (its work bound
      // ran out): the lens proves nothing, whatever the end data say.
      BiarcFit f;
      f.eps = std::numeric_limits<double>::infinity();
      f.u0 = s.u0;
      f.u1 = s.u1;
      f.piece = s.piece;
      f.arcs = 1;
      f.arc[0] = Arc2{s.ends.p0, (s.ends.p1 - s.ends.p0).normalized(), 0.0, (s.ends.p1 - s.ends.p0).norm()};
      f.arc[1] = Arc2{s.ends.p1, f.arc[0].tangent, 0.0, 0.0};
      node_at(node).fit = add_fit(f);
      set_capsule(node, Capsule{s.ends.p0, s.ends.p1, std::numeric_limits<double>::infinity()});
      ++st.unproven;
      note_leaf(f);
      return;
    }
    if (s.kind == SpanKind::curve) {
      build_curve(node, profile.pieces[s.piece], s.piece, s.u0, s.u1, s.ends, 0);
    } else {
      build_exact(node, s);
    }
  }

  // Balanced tree over spirals [lo, hi): capsules only (AABB level of the paper).
  void build_upper(std::int32_t node, std::size_t lo, std::size_t hi) {
    if (hi - lo == 1) {
      build_spiral(node, tree.spirals[lo]);
      return;
    }
    const std::size_t mid = lo + (hi - lo) / 2;
    const std::int32_t c = alloc_pair();
    node_at(node).child = c;
    node_at(node).fit = -1;
    build_upper(c, lo, mid);
    build_upper(c + 1, mid, hi);
    set_capsule(node, capsule_union(capsule_of(c), capsule_of(c + 1)));
  }
};

}  // namespace

double split_parameter(const Piece& piece, double u0, double u1) {
  const double um = 0.5 * (u0 + u1);
  if (piece.kind != PieceKind::bspline) return um;
  const double near = 1e-6 * (u1 - u0);
  const std::vector<double>& t = piece.knots;
  const auto first = std::upper_bound(t.begin(), t.end(), u0);  // the first knot above u0
  if (first != t.end() && *first < u1 && *first - u0 < near) return *first;
  const auto last = std::lower_bound(t.begin(), t.end(), u1);  // after the last knot below u1
  if (last != t.begin() && *(last - 1) > u0 && u1 - *(last - 1) < near) return *(last - 1);
  return um;
}

void split_span(const Piece& piece, double um, const SpanEnds& e, SpanEnds* left, SpanEnds* right) {
  *left = e;
  *right = e;
  left->p1 = piece_tangent(piece, um, +1, &left->t1, &left->k1);
  right->p0 = left->p1;
  right->t0 = left->t1;
  right->k0 = left->k1;
}

BiarcFit fit_curve_span(const Piece& piece, std::int32_t piece_index, double u0, double u1, const SpanEnds& e,
                        const Vec2& mid, double slack, Capsule* capsule, double chord_eps) {
  const LensBound lens = lens_bound(e);
  const Biarc b = fit_curve_biarc(piece, u0, u1, e, mid);
  BiarcFit f;
  f.arc[0] = b.arc[0];
  f.arc[1] = b.arc[1];
  f.eps = lens.hypotheses_ok ? lens.width + slack : std::numeric_limits<double>::infinity();
  // A span so nearly straight that both arcs turn less than kFlatSweep: the
  // chord instead, a cone. The torus of such an arc has a major radius of a
  // million times the arc or more, at which the patch kernel's tests (scaled
  // to the whole circle) accept points off the patch: its bounds stay below
  // the distance and the query cannot converge (stress seed 42,
  // near_inflection #293: arcs of radius 3e4 and length 1e-4). The chord
  // lies in the lens band, whose height over it is at most H =
  // max(|s_A|, |s_B|) (lens_capsule's peak heights), and both curve and
  // chord are graphs over the chord: every point of each is within H of the
  // other. H is below 1e-7 of the chord here, but it shrinks with the square
  // of the span, the biarc's bound with the cube: the tree takes the chord
  // only where it meets the requested bound (chord_eps), so flat curves at
  // the finest eps keep the biarc's leaf counts; the query's refinements take
  // it always (+inf).
  if (lens.hypotheses_ok && std::abs(f.arc[0].curvature * f.arc[0].length) < kFlatSweep &&
      std::abs(f.arc[1].curvature * f.arc[1].length) < kFlatSweep) {
    const Vec2 v = e.p1 - e.p0;
    const double d = v.norm();
    const double h = 0.5 * d * std::max(std::abs(std::tan(0.5 * lens.alpha)), std::abs(std::tan(0.5 * lens.beta)));
    if (d > 0 && h + slack <= chord_eps) {
      f.arc[0] = Arc2{e.p0, v / d, 0.0, d};
      f.arc[1] = Arc2{e.p1, v / d, 0.0, 0.0};
      f.arcs = 1;
      f.eps = h + slack;
    }
  }
  f.u0 = u0;
  f.u1 = u1;
  f.piece = piece_index;
  f.kind = SpanKind::curve;
  *capsule = lens_capsule(e, lens);
  capsule->radius = lens.hypotheses_ok ? capsule->radius + slack : std::numeric_limits<double>::infinity();
  return f;
}

void rebuild_biarc_tree(const Profile& profile, double eps, BiarcTree& tree, BuildStats* stats, bool lazy) {
  tree.nodes.clear();
  tree.fits.clear();
  tree.pending.clear();
  tree.lazy = lazy;
  tree.eps = eps;
  split_into_spirals(profile, tree.spirals);

  // Rounding allowance: end points, tangents and the stored arcs each carry a
  // few ulp of the coordinates; 64 ulp of the largest one covers the dozen
  // operations between the input and a stored arc with room to spare.
  // Exact pieces: at most exact_fraction of the profile's extent per leaf
  // (1/64 to 1/4). The extent of the curve, not of its points (profile_box):
  // an arc given by three points may bulge far past them (a fuzzed case's
  // arc through (0, -2), (2, 1e8) and (0, 2) runs once round a circle of
  // radius 2.5e15; split to 1/16 of its points' extent it made 2.5e9 leaves,
  // 10 GB in 15 s). The rounding allowance's scale too: the largest
  // coordinate of the curve.
  Vec2 lo, hi;
  profile_box(profile, &lo, &hi);
  const double scale = profile.pieces.empty() ? 0.0 : std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  const double extent = profile.pieces.empty() ? 0.0 : (hi - lo).norm();
  Builder b{profile, eps, 64.0 * DBL_EPSILON * scale, extent * exact_fraction(eps, extent), tree};
  b.lazy = lazy;
  tree.exact_length = b.max_exact_length;
  if (!tree.spirals.empty()) {
    tree.nodes.resize(1);
    b.build_upper(0, 0, tree.spirals.size());
  }
  tree.max_error = b.st.max_error;
  tree.slack = b.slack;
  if (stats) {
    *stats = b.st;
    stats->pieces = static_cast<int>(profile.pieces.size());
    stats->spirals = static_cast<int>(tree.spirals.size());
    stats->nodes = static_cast<int>(tree.nodes.size());
    stats->bytes = tree.bytes();
  }
}

BiarcTree build_biarc_tree(const Profile& profile, double eps, BuildStats* stats, bool lazy) {
  BiarcTree tree;
  rebuild_biarc_tree(profile, eps, tree, stats, lazy);
  return tree;
}

BiarcTreeView::BiarcTreeView(const BiarcTree& tree, const Profile& profile)
    : tree_(tree),
      profile_(profile),
      base_nodes_(static_cast<std::int32_t>(tree.nodes.size())),
      base_fits_(static_cast<std::int32_t>(tree.fits.size())),
      base_pending_(static_cast<std::int32_t>(tree.pending.size())) {}

std::int32_t BiarcTreeView::expand(std::int32_t i) {
  const std::int32_t p = -2 - node(i).child;
  if (p < base_pending_) {
    if (expanded_.empty()) expanded_.assign(static_cast<std::size_t>(base_pending_), -1);
    if (expanded_[p] >= 0) return expanded_[p];
  }
  // Copies: the builder appends to ext_ (its pending spans and fits too).
  const SpiralSpan span = p < base_pending_ ? tree_.pending[p] : ext_.pending[p - base_pending_];
  const int depth = fit(node(i).fit).depth;
  Builder b{profile_, tree_.eps, tree_.slack, tree_.exact_length, ext_};
  b.lazy = true;
  b.base_nodes = base_nodes_;
  b.base_fits = base_fits_;
  b.base_pending = base_pending_;
  const std::int32_t c = b.expand(i, span, depth);
  if (p < base_pending_) expanded_[p] = c;
  return c;
}

}  // namespace revdist
