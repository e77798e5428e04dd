// Solid-solid distance: Algorithm 2 of the paper with proven bounds.
//
// Parts. A part is a tree node or, below the tree's leaves, a refinement of a
// leaf's fit (half its parameter span, refitted). Every part has a bounding
// disk in (r, z) (from its capsule); rotated, the disk is a solid torus around
// a circle, so two parts are at least circle_distance - radii apart. The
// capsule's segment, rotated, is a cone whose hull (a solid frustum) holds the
// part to within the capsule's radius: a separating direction bounds two parts
// with two support values (fast/cone_hull.h), and the same, exactly, for two
// patches (a revolved arc's support is its circle's or an end's). Parts with
// a fit (leaves and refinements) are compared exactly: the distance between
// their arcs' patches (fast/patch_distance.h) minus both proven eps is a lower
// bound for the true surfaces when the patches are proven apart; the patches'
// closest points mapped onto the input curves give genuine surface points and
// so an upper bound.
//
// Solids, not surfaces (SPEC section 2): once the surfaces are proven apart, a
// point of each surface is tested against the other solid (profile_side); a
// point strictly inside proves an overlap, and is also tried on patches that
// could not be separated.
#include "fast/solid_distance.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <limits>
#include <string>
#include <vector>

#include "core/curve_eval.h"
#include "core/profile_check.h"
#include "fast/biarc_fit.h"
#include "fast/circle_bound.h"
#include "fast/circle_distance.h"
#include "fast/cone_hull.h"
#include "fast/patch.h"
#include "fast/patch_distance.h"
#include "fast/profile_side.h"

namespace revdist {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Boxes the local proof (patches_at_least) may evaluate per patch pair before
// the enumeration takes over.
constexpr int kLocalBudget = 128;
// Boxes for the second try of the local proof, at the cut lowered by the pair's
// own local minimum: the minimum then sits within about tol of the cut, which
// takes smaller boxes. An enumeration costs about as much as 340 boxes (probe:
// 155 K instructions against 460 a box); 512 settles 86 % of the second tries
// (128: 49 %).
constexpr int kRetryBudget = 512;
// Evaluations for each of a leaf pair's two spine bounds (patch_spine_at_least).
constexpr int kSpineBudget = 48;
// Node pairs a query pops before its inner pairs get the tight bound too (the
// paper motion's median query pops 145; see the loop).
constexpr long kTightInner = 256;
// A fit part this many times the other part's disk radius is bounded by its
// own patches against that part's disk circle (fit_spine_bound) when popped.
constexpr double kSpineRatio = 4.0;
// A fit's arc is taken as a sphere zone or a cylinder (Solid::axis_zones,
// zone_bound) when its centre is within this fraction of its radius of the
// axis, or its ends' distances from the axis within this fraction of each
// other (rounding of input given on the axis or parallel to it: the bound
// takes the offset, or the larger distance).
constexpr double kZoneOff = 1e-9;
// A cold first witness starts on fits of this fraction of the solid's
// extent where the leaves are kCoarseLeaves or more times finer
// (coarse_witness in the query).
constexpr double kWitnessCoarse = 1e-3;
constexpr double kCoarseLeaves = 1e3;
// A pair with a tree node above the leaves is bounded by the nodes' own
// fits (node_fits_bound, fine trees only) when their errors are within this
// fraction of the two disks' radii (else the disks bound about as well).
constexpr double kNodeFits = 1e-2;
// Evaluations for a cylinder's axis segment in zone_bound.
constexpr int kZoneBudget = 24;
// A pair of points whose surfaces may cross near them gets the steps across
// (Solid::across, the overlap probe) when they are within this fraction of
// the longer fit's chord of each other. Measured on the motion probe's 3000
// queries at eps 1e-3, 1e-5 and 1e-7, the steps from every first witness
// and every descended pair: of the pairs whose steps proved an overlap, 85 %
// at eps 1e-3, 81 % at 1e-5 and 84 % at 1e-7 are within 0.02, against 15 %,
// 8 % and 6 % of the others (within 0.05: 91, 87 and 89 %, against 25, 15
// and 13 %).
constexpr double kAcrossReach = 0.02;

// The centre key of a pair (PairQueue): its lower bound plus this share of
// both disks' radii (1: the distance of the disks' centre circles). Below 1 a
// big pair comes up a little sooner than a small one at the same centre
// distance: where the first witness sits at a separated contact of solids
// that cross elsewhere, the pairs over the crossing are split sooner instead
// of after every pair near the witness. Measured on the motion probe, least
// of 3 runs, against 1: 30000 queries at eps 1e-5, proven overlaps' p99 52.6
// -> 45.7 us (0.85: 44.6, 0.95: 49.3), median 9.3 / 9.2; 3000 at eps 1e-7,
// p90 62.2 / 63.0 / 63.6 -> 64.1 / 64.1 / 63.9 us (runs of 3, 3 and 5);
// M instructions for 600 queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6 94.07
// / 80.75 / 174.01 / 126.69 -> 94.11 / 80.57 / 177.05 / 126.75, for the
// 200 overlap frames 19.40 -> 18.58. (A share of 0.9 once, before the
// estimated keys of pairs whose closed form is 0 (push_pair), took the
// interlocked rings' threshold query from 14 to 263 node pairs.)
constexpr double kKeyDisks = 0.9;

struct Part {
  std::int32_t node = -1;   // tree node, -1 for a refinement
  bool has_fit = false;     // leaves and refinements: compared by patches
  // Its fit (Solid::fit): the tree's fit of that index (>= 0), refinement
  // k's (-2 - k), none (-1). An index, not a copy: a part is copied at every
  // split, and most never need their fit.
  std::int32_t fit = -1;
  Vec2 disk_c = Vec2::Zero();
  double disk_r = 0.0;
  Vec2 seg_a = Vec2::Zero(), seg_b = Vec2::Zero();  // its capsule: the part is within cap_r of the segment
  double cap_r = 0.0;
  Vec3 world_c = Vec3::Zero();  // the centre of the circle the disk centre sweeps (world)
  std::int32_t child = -1;  // first of the two child parts once split
  int level = 0;            // refinement levels below the tree leaf
};

// One side of the query: the solid, its parts and cached world data.
struct Solid {
  const PosedSolid& s;
  BiarcTreeView tree;  // s.tree; a lazy tree's nodes are built here when first split
  // (Both in the thread's QueryStorage, emptied here: their storage is kept.)
  std::vector<Part>& parts;
  std::deque<BiarcFit>& refined_fits;  // the refinements' fits (a deque: references stay valid)
  Vec3 axis;
  double slack;  // rounding allowance of refitted bounds: the tree builder's
  CircleNormalFrame frame;  // the plane frame of every part's circle (all about the axis)

  Solid(const PosedSolid& ps, std::vector<Part>& part_storage, std::deque<BiarcFit>& fit_storage)
      : s(ps), tree(*ps.tree, *ps.profile), parts(part_storage), refined_fits(fit_storage),
        axis(ps.R.col(2).normalized()), slack(ps.tree->slack), frame(circle_normal_frame(axis)) {
    parts.clear();
    refined_fits.clear();
    parts.push_back(from_node(0, 0));
    place(parts.back());
  }

  // A part's capsule (segment a b, radius r) and the disk that holds it,
  // kept beside it for the closed-form bounds at every push.
  static void set_capsule(Part& p, const Vec2& a, const Vec2& b, double r) {
    p.seg_a = a;
    p.seg_b = b;
    p.cap_r = r;
    p.disk_c = 0.5 * (a + b);
    p.disk_r = 0.5 * (b - a).norm() + r;
  }

  Part from_node(std::int32_t node, int level) const {
    const BiarcNode& n = tree.node(node);
    Part p;
    p.node = node;
    p.level = level;
    set_capsule(p, n.seg_a, n.seg_b, n.radius);
    if (n.fit >= 0) {
      p.has_fit = n.leaf();
      p.fit = n.fit;
    }
    return p;
  }

  // Part p's fit. (A tree fit's reference does not survive a lazy tree's
  // expansion: tree.children.)
  const BiarcFit& fit(const Part& p) const { return p.fit >= 0 ? tree.fit(p.fit) : refined_fits[-2 - p.fit]; }

  // The circle the part's disk centre sweeps, in the world.
  Circle3 disk_circle(const Part& p) const { return {p.world_c, axis, disk_circle_radius(p)}; }
  static double disk_circle_radius(const Part& p) { return std::max(p.disk_c.x(), 0.0); }
  void place(Part& p) const { p.world_c = s.t + p.disk_c.y() * axis; }

  bool can_split(const Part& p, int max_refine) const {
    if (!p.has_fit) return true;
    if (p.level >= max_refine || !(p.disk_r > 0)) return false;
    const BiarcFit& f = fit(p);
    return f.u1 > f.u0;
  }

  // Splits part i (memoised: the children are shared by every pair). The
  // children are built in place (a Part is ~200 bytes, and the first split
  // of a node pair is on the query's path: copies cost 1 % of it).
  std::int32_t split(std::int32_t i, long* refined) {
    return parts[i].child >= 0 ? parts[i].child : make_children(i, refined);
  }
  // Out of line: most splits find the children made (the witness's rounds
  // descend the trees eight times), and with the check inlined alone the
  // motion probe takes 133.9 -> 131.8 M instructions at eps 1e-5, 105.8 ->
  // 104.1 at 1e-3, 270.1 -> 267.6 at 1e-7, 193.3 -> 191.3 at tol 1e-6.
  [[gnu::noinline]] std::int32_t make_children(std::int32_t i, long* refined) {
    const auto k = static_cast<std::int32_t>(parts.size());
    if (!parts[i].has_fit) {
      const std::int32_t tc = tree.children(parts[i].node);
      parts.push_back(from_node(tc, 0));  // (may reallocate: parts[i] is read again below only)
      parts.push_back(from_node(tc + 1, 0));
    } else {
      parts.resize(k + 2);
      refine(parts[i], &parts[k], &parts[k + 1]);
      *refined += 2;
    }
    place(parts[k]);
    place(parts[k + 1]);
    parts[i].child = k;
    return k;
  }

  // Half-span refinements of a fit: a curve is refitted with a biarc under the
  // same lens bound as the tree; an exact line or arc is cut in two.
  void refine(const Part& p, Part* c0, Part* c1) {
    const BiarcFit pf = fit(p);
    const Piece& piece = s.profile->pieces[pf.piece];
    const double u0 = pf.u0, u1 = pf.u1, um = split_parameter(piece, u0, u1);
    SpanEnds e;
    e.p0 = piece_tangent(piece, u0, +1, &e.t0, &e.k0);
    e.p1 = piece_tangent(piece, u1, -1, &e.t1, &e.k1);
    SpanEnds left, right;
    split_span(piece, um, e, &left, &right);
    Part* out[2] = {c0, c1};
    const SpanEnds* ends[2] = {&left, &right};
    const double us[3] = {u0, um, u1};
    for (int h = 0; h < 2; ++h) {
      Part& c = *out[h];
      c.level = p.level + 1;
      c.has_fit = true;
      c.fit = -2 - static_cast<std::int32_t>(refined_fits.size());
      BiarcFit& f = refined_fits.emplace_back(pf);
      f.u0 = us[h];
      f.u1 = us[h + 1];
      Capsule cap;
      if (pf.kind == SpanKind::curve) {
        const Vec2 mid = piece_point(piece, 0.5 * (f.u0 + f.u1));
        f = fit_curve_span(piece, pf.piece, f.u0, f.u1, *ends[h], mid, slack, &cap);
      } else {
        const Arc2& a = pf.arc[0];
        const double half = 0.5 * a.length;
        f.arc[0] = h == 0 ? Arc2{a.start, a.tangent, a.curvature, half}
                          : Arc2{a.point(half), a.tangent_at(half), a.curvature, half};
        f.arc[1] = Arc2{f.arc[0].end(), f.arc[0].end_tangent(), a.curvature, 0.0};
        f.arcs = 1;
        cap = lens_capsule(*ends[h], lens_bound(*ends[h]));
        cap.radius += slack;
      }
      set_capsule(c, cap.a, cap.b, cap.radius);
    }
  }

  // The point of the input curve nearest to patch point x (world) within the
  // fit's span, mapped back to the world at x's azimuth: a genuine surface point.
  Vec3 true_point(const BiarcFit& f, const Vec3& x) const {
    const Vec3 d = s.R.transpose() * (x - s.t);
    const double rho = std::sqrt(d.x() * d.x() + d.y() * d.y());  // (coordinates within 1e100: no overflow)
    const Vec2 best = curve_nearest(f, Vec2(rho, d.z()));
    const Vec3 er = rho > 0 ? Vec3(d.x() / rho, d.y() / rho, 0) : Vec3::UnitX();
    const Vec3 local(std::max(best.x(), 0.0) * er.x(), std::max(best.x(), 0.0) * er.y(), best.y());
    return s.R * local + s.t;
  }

  // The point of the input curve nearest to meridian point q within fit f's
  // span (true_point's), and its curve parameter in *u_best when asked.
  Vec2 curve_nearest(const BiarcFit& f, const Vec2& q, double* u_best = nullptr) const {
    const Piece& piece = s.profile->pieces[f.piece];
    // Newton from the projection onto the fit's chord (the fit's ends, within
    // rounding of the curve's: only the start depends on them). Every point
    // taken is the curve's own, at the iterates, which are clamped to the
    // span: an end nearest to q is reached there.
    const Vec2 c0 = f.start(), chord = f.end() - c0;
    const double l2 = chord.squaredNorm();
    double u = f.u0 + (l2 > 0 ? std::clamp((q - c0).dot(chord) / l2, 0.0, 1.0) : 0.5) * (f.u1 - f.u0);
    Vec2 best;
    double best_d = kInf, best_u = u;
    Vec2 der[3];
    for (int it = 0; it < 12; ++it) {
      piece_derivatives(piece, u, 2, der);
      const Vec2 r = der[0] - q;
      if (it == 0 || r.squaredNorm() < best_d) best = der[0], best_d = r.squaredNorm(), best_u = u;
      const double g = r.dot(der[1]);
      const double h = der[1].squaredNorm() + r.dot(der[2]);
      // Where the squared distance is not convex, downhill to the span's end.
      const double un = h > 0 ? std::clamp(u - g / h, f.u0, f.u1) : g > 0 ? f.u0 : f.u1;
      const double step = std::abs(un - u);
      u = un;
      // Newton's error is about the square of the last step: below 1e-10 of
      // the span it is far below rounding (any u gives a genuine point).
      if (!(step > 1e-10 * (f.u1 - f.u0))) break;
    }
    piece_derivatives(piece, u, 0, der);
    if ((der[0] - q).squaredNorm() < best_d) best = der[0], best_u = u;
    if (u_best) *u_best = best_u;
    return best;
  }

  // The input curve's point nearest to world point x near fit f
  // (true_point's), with what a step on the surface from it needs.
  struct CurvePoint {
    const Piece* piece;
    double u, th, cos_t, sin_t;  // curve parameter, azimuth
    Vec2 c, dc;                  // the curve point (r, z) and its derivative in u
    Vec3 world, normal;          // the surface point, a normal there (unnormalised, either sign)
  };
  CurvePoint curve_point(const BiarcFit& f, const Vec3& x) const {
    const Vec3 d = s.R.transpose() * (x - s.t);
    const double rho = std::sqrt(d.x() * d.x() + d.y() * d.y());
    CurvePoint p;
    p.piece = &s.profile->pieces[f.piece];
    curve_nearest(f, Vec2(rho, d.z()), &p.u);
    Vec2 der[2];
    piece_derivatives(*p.piece, p.u, 1, der);
    p.c = der[0], p.dc = der[1];
    p.cos_t = rho > 0 ? d.x() / rho : 1.0, p.sin_t = rho > 0 ? d.y() / rho : 0.0;
    p.th = std::atan2(p.sin_t, p.cos_t);
    const double r = std::max(p.c.x(), 0.0);
    p.world = s.R * Vec3(r * p.cos_t, r * p.sin_t, p.c.y()) + s.t;
    p.normal = s.R * Vec3(p.dc.y() * p.cos_t, p.dc.y() * p.sin_t, -p.dc.x());
    return p;
  }

  // Genuine surface points near curve point p of this solid, stepped across
  // the tangent plane of the other solid's surface at its curve point q:
  // along the direction on this surface that leaves the plane fastest, `len`
  // then a quarter of it, `steps` lengths, each handed to take(point) until
  // it returns true. Where two surfaces cross, their nearest-point pairs sit
  // on the crossing, inside neither solid, and the step along the profile
  // (along_meridian) runs beside the crossing wherever the crossing runs
  // along the meridian; this step goes across it. Only steps that reach the
  // plane, to first order, are taken: towards it, and both ways from a p on
  // it. Nothing where the surfaces meet at a sine of 1e-3 or less (no
  // direction across).
  template <class Take>
  bool across(const CurvePoint& p, const CurvePoint& q, double len, int steps, Take take) const {
    const Vec3 n = s.R.transpose() * q.normal;
    const double r = std::max(p.c.x(), 0.0);
    // n . x along the curve parameter and the azimuth, over the metric: the
    // step (du, dt) that leaves the plane fastest.
    const double gu = n.dot(Vec3(p.dc.x() * p.cos_t, p.dc.x() * p.sin_t, p.dc.y())),
                 gt = n.dot(Vec3(-r * p.sin_t, r * p.cos_t, 0));
    const double mu = p.dc.squaredNorm(), mt = r * r;
    const double du = mu > 0 ? gu / mu : 0.0, dt = mt > 0 ? gt / mt : 0.0;
    const double rate = std::sqrt(du * du * mu + dt * dt * mt);  // |n| times the sine of the surfaces' angle
    const double nn = q.normal.norm();
    if (!(rate > 1e-3 * nn)) return false;
    const double sine = rate / nn;
    const double s0 = q.normal.dot(p.world - q.world) / nn;  // p's signed distance from the plane
    const auto [lo, hi] = piece_domain(*p.piece);
    double l = len;
    for (int k = 0; k < steps; ++k, l *= 0.25)
      for (double side : {-1.0, 1.0}) {
        // (A step of length l along side * (du, dt) moves side * l * sine off the plane.)
        if (std::abs(s0) > l * sine) return false;  // (and every shorter step)
        const bool on_plane = std::abs(s0) <= 1e-3 * l * sine;
        if (!on_plane && (s0 > 0) == (side > 0)) continue;
        const double uk = std::clamp(p.u + side * l / rate * du, lo, hi), tk = p.th + side * l / rate * dt;
        const Vec2 c = piece_point(*p.piece, uk);
        const double cr = std::max(c.x(), 0.0);
        if (take(Vec3(s.R * Vec3(cr * std::cos(tk), cr * std::sin(tk), c.y()) + s.t))) return true;
      }
    return false;
  }

  // Genuine surface points on world point x's meridian, from the input curve
  // at fit f's span ends and at 1, 2, 4 ... (`steps` of them) span lengths
  // beyond each end (within the piece), handed to take(point) in that order
  // until it returns true. Where two solids cross at a sharp edge, the
  // nearest-point probes sit on the crossing and prove nothing; a step along
  // the profile reaches the part of the surface that is inside the other.
  template <class Take>
  bool along_meridian(const BiarcFit& f, const Vec3& x, int steps, Take take) const {
    const Vec3 d = s.R.transpose() * (x - s.t);
    const double rho = std::sqrt(d.x() * d.x() + d.y() * d.y());  // (coordinates within 1e100: no overflow)
    const Vec3 er = rho > 0 ? Vec3(d.x() / rho, d.y() / rho, 0) : Vec3::UnitX();
    const Piece& piece = s.profile->pieces[f.piece];
    const auto [lo, hi] = piece_domain(piece);
    const double span = f.u1 - f.u0;
    auto at = [&](double u) {
      const Vec2 c = piece_point(piece, std::clamp(u, lo, hi));
      return take(Vec3(s.R * Vec3(std::max(c.x(), 0.0) * er.x(), std::max(c.x(), 0.0) * er.y(), c.y()) + s.t));
    };
    if (at(f.u0) || at(f.u1)) return true;
    double step = span;
    for (int k = 0; k < steps; ++k, step *= 2) {
      if (f.u0 > lo && at(f.u0 - step)) return true;
      if (f.u1 < hi && at(f.u1 + step)) return true;
    }
    return false;
  }

  // World point x in this solid's meridian half-plane: (distance to the axis, height).
  Vec2 meridian(const Vec3& x) const {
    const Vec3 d = s.R.transpose() * (x - s.t);
    return Vec2(std::sqrt(d.x() * d.x() + d.y() * d.y()), d.z());
  }

  // The fit near world point x: a greedy descent of the disks towards x's
  // meridian point, or the leaf it found last when x's meridian point is in
  // that leaf's disk (the witness's rounds mostly stay on one fit: motion
  // probe, M instructions for 600 queries at eps 1e-5 / 1e-3 / 1e-7 / tol
  // 1e-6, 100.4 / 81.3 / 198.8 / 148.0 -> 99.9 / 80.8 / 198.7 / 147.6;
  // first witnesses within tol of the answer 1764 -> 1758 of 2811).
  // (nearest_fit and closest_fit with a `coarse` error above 0 stop at the
  // first node whose own fit is within it: the first witness's coarse
  // rounds, first_witness; each keeps its last find apart.)
  std::int32_t last_leaf = -1, last_coarse = -1;
  // Whether part i ends a descent for a fit of error `coarse` (0: a leaf).
  bool ends(std::int32_t i, double coarse) const {
    return parts[i].has_fit || (coarse > 0 && parts[i].fit >= 0 && fit(parts[i]).eps <= coarse);
  }
  BiarcFit nearest_fit(const Vec3& x, double coarse = 0.0) {
    const Vec2 q = meridian(x);
    std::int32_t& last = coarse > 0 ? last_coarse : last_leaf;
    if (last >= 0 && (q - parts[last].disk_c).norm() <= parts[last].disk_r) return fit(parts[last]);
    std::int32_t i = 0;
    long refined = 0;  // tree nodes only: parts with a fit end the descent
    while (!ends(i, coarse)) {
      const std::int32_t c = split(i, &refined);
      const Part &c0 = parts[c], &c1 = parts[c + 1];
      i = (q - c0.disk_c).norm() - c0.disk_r <= (q - c1.disk_c).norm() - c1.disk_r ? c : c + 1;
    }
    last = i;
    return fit(parts[i]);
  }

  // The fit nearest world point x, by a branch-and-bound search of the
  // parts' capsules (capsule_lb) from the last fit found, against the fits'
  // arcs in the meridian half-plane (a point's distance to a surface of
  // revolution is its meridian point's to the profile). Where disks overlap (an exact line's
  // long leaf beside a curve's short fits) nearest_fit's greedy descent, and
  // its shortcut to the last leaf, can return a fit that is not the nearest.
  BiarcFit closest_fit(const Vec3& x, double coarse = 0.0) {
    const Vec2 q = meridian(x);
    long refined = 0;  // tree nodes only, as in nearest_fit
    std::int32_t& last = coarse > 0 ? last_coarse : last_leaf;
    std::int32_t best = last;
    double best_d = best >= 0 ? fit_distance(fit(parts[best]), q) : kInf;
    struct Item {
      std::int32_t i;
      double lb;
    };
    constexpr int kStack = 128;  // (a deeper tree only loses the search's farther branches)
    Item stack[kStack];
    int n = 0;
    stack[n++] = {0, (q - parts[0].disk_c).norm() - parts[0].disk_r};
    while (n > 0) {
      const Item it = stack[--n];
      if (it.lb >= best_d || it.i == best) continue;
      if (ends(it.i, coarse)) {
        if (const double d = fit_distance(fit(parts[it.i]), q); d < best_d) best_d = d, best = it.i;
        continue;
      }
      const std::int32_t c = split(it.i, &refined);
      Item near{c, capsule_lb(parts[c], q)};
      Item far{c + 1, capsule_lb(parts[c + 1], q)};
      if (far.lb < near.lb) std::swap(near, far);
      if (far.lb < best_d && n + 2 <= kStack) stack[n++] = far;  // popped after near's subtree
      if (near.lb < best_d) stack[n++] = near;
    }
    last = best;
    return fit(parts[best]);
  }
  // A lower bound on the distance from meridian point q to part p: to its
  // capsule (closer than its disk's for a long thin part; closest_fit: M
  // instructions for the motion probe's 600 queries at eps 1e-7 142.15 ->
  // 140.83, the others within 0.2 %).
  static double capsule_lb(const Part& p, const Vec2& q) { return point_segment_distance(q, p.seg_a, p.seg_b) - p.cap_r; }
  // The distance from meridian point q to fit f's arcs.
  static double fit_distance(const BiarcFit& f, const Vec2& q) {
    double d = f.arc[0].distance(q);
    if (f.arcs == 2) d = std::min(d, f.arc[1].distance(q));
    return d;
  }

  // Fit f as axis zones: each arc of it within a radius of a piece of the
  // solid's axis, tightly. A sphere zone (an arc about a centre on the axis:
  // the pawn's head, the lightmil's bulb) is within its radius, plus the
  // centre's offset from the axis, of the centre; a cylinder (a segment at
  // one distance r from the axis: the table's column, the bottle's body) is
  // within r of the axis between its end heights. Gives, per arc of some
  // length, the axis piece in the world (a0 == a1 for a sphere) and the
  // radius; false when an arc is neither (within kZoneOff of its size).
  struct Zone {
    Vec3 a0, a1;
    double radius;
  };
  bool axis_zones(const BiarcFit& f, Zone* zones, int* n) const {
    *n = 0;
    for (int k = 0; k < f.arcs; ++k) {
      const Arc2& a = f.arc[k];
      if (!(a.length > 0)) continue;
      if (a.straight()) {
        const Vec2 e = a.end();
        const double r = std::max(a.start.x(), e.x());
        if (!(std::abs(e.x() - a.start.x()) <= kZoneOff * r)) return false;
        zones[(*n)++] = {s.R * Vec3(0, 0, a.start.y()) + s.t, s.R * Vec3(0, 0, e.y()) + s.t, r};
        continue;
      }
      const Vec2 c = a.center();
      const double rho = 1.0 / std::abs(a.curvature), off = std::abs(c.x());
      if (!(off <= kZoneOff * rho)) return false;
      const Vec3 centre = s.R * Vec3(0, 0, c.y()) + s.t;
      zones[(*n)++] = {centre, centre, rho + off};
    }
    return *n > 0;
  }
  // A lower bound on the distance from world point x to part p's true
  // curve, revolved: its fit's arcs less the fit's eps, or its capsule.
  double part_distance_from(const Part& p, const Vec3& x) {
    const Vec2 q = meridian(x);
    if (!p.has_fit) return capsule_lb(p, q);
    const BiarcFit& f = fit(p);
    return fit_distance(f, q) - f.eps;
  }

  // The patches of the fit nearest_patch saw last: the witness's rounds
  // come back to the same fit, and a patch costs a sine and cosine.
  // (Measured on the motion probe at eps 1e-5: 134.9 -> 133.9 M
  // instructions. The leaf pairs' patches through it too: 134.2.)
  mutable struct {
    std::int32_t piece = -1;
    double u0 = 0, u1 = 0;
    Patch p[2];
  } last_;
  const Patch* fit_patches(const BiarcFit& f) const {
    if (!(last_.piece == f.piece && last_.u0 == f.u0 && last_.u1 == f.u1)) {
      last_.piece = f.piece, last_.u0 = f.u0, last_.u1 = f.u1;
      for (int k = 0; k < f.arcs; ++k) last_.p[k] = make_patch(f.arc[k], s.R, s.t);
    }
    return last_.p;
  }

  // The patch of fit f's arc nearest world point x (arcs of no length only
  // when the fit has no other; of two arcs, the one on x's side of their
  // junction's normal), and in *y, when given, that patch's point nearest x:
  // within f.eps of the surface, not a genuine surface point (true_point
  // maps it to one), and a tenth of true_point's cost. A candidate maker for
  // the witness and the overlap probes: nothing proven rests on it.
  Patch nearest_patch(const BiarcFit& f, const Vec3& x, Vec3* y = nullptr) const {
    Patch best;
    Vec3 best_y;
    double best_d = kInf;
    const Patch* ps = fit_patches(f);
    // Of a biarc's two arcs, the one on x's side of the normal line at
    // their junction (the line that parts their nearest points near the
    // curve; a point it misplaces only makes a worse candidate). Measured on
    // the motion probe, M instructions for 600 queries at eps 1e-5 / 1e-3 /
    // 1e-7 / tol 1e-6: both arcs 110.6 / 92.2 / 230.2 / 171.9, one 109.6 /
    // 91.3 / 229.2 / 170.9.
    int only = -1;
    if (f.arcs == 2 && f.arc[0].length > 0 && f.arc[1].length > 0)
      only = (meridian(x) - f.arc[1].start).dot(f.arc[1].tangent) < 0 ? 0 : 1;
    for (int k = 0; k < f.arcs; ++k) {
      if (f.arc[k].length <= 0 || (only >= 0 && k != only)) continue;
      const Patch& p = ps[k];
      Vec3 yk;
      if (const double d = patch_nearest(p, x, &yk); d < best_d) best_d = d, best = p, best_y = yk;
    }
    if (best_d == kInf) {
      best = make_patch(f.arc[0], s.R, s.t);
      patch_nearest(best, x, &best_y);
    }
    if (y) *y = best_y;
    return best;
  }

  // A few points of the surface (k = 0..kSurfacePoints-1): the profile's start
  // and end, the middles of its first and last pieces, at azimuth 0.
  static constexpr int kSurfacePoints = 4;
  Vec3 surface_point(int k) const {
    const std::vector<Piece>& pieces = s.profile->pieces;
    Vec2 p;
    if (k == 0) p = pieces.front().start();
    else if (k == 1) p = pieces.back().end();
    else {
      const Piece& piece = k == 2 ? pieces.front() : pieces.back();
      const auto [u0, u1] = piece_domain(piece);
      p = piece_point(piece, 0.5 * (u0 + u1));
    }
    return s.R * Vec3(p.x(), 0, p.y()) + s.t;
  }

  // A point proven strictly inside this solid (world), if one is found: off
  // the middle of a leaf arc, to either side, by a small fraction of the
  // profile's size, checked against the true profile. Solids that share their
  // surfaces (identical, or stacked flush) are proven to overlap with it.
  bool interior_point(Vec3* out) {
    const BiarcNode& root = tree.node(0);
    // The scale of the profile: the root capsule holds it.
    const double size = std::max(root.seg_a.norm(), root.seg_b.norm()) + (std::isfinite(root.radius) ? root.radius : 0.0);
    // The first leaf in profile order (depth first, left child first).
    std::vector<std::int32_t> stack{0};
    while (!stack.empty()) {
      const std::int32_t i = stack.back();
      stack.pop_back();
      const BiarcNode n = tree.node(i);
      if (!n.leaf()) {
        const std::int32_t c = tree.children(i);
        stack.push_back(c + 1);
        stack.push_back(c);
        continue;
      }
      if (n.fit < 0) continue;
      const Arc2 a = tree.fit(n.fit).arc[0];
      if (a.length <= 0) continue;
      const Vec2 m = a.point(0.5 * a.length);
      const Vec2 t = a.tangent_at(0.5 * a.length);
      for (double side : {1.0, -1.0}) {
        const Vec2 q = m + side * 1e-3 * size * Vec2(-t.y(), t.x());
        if (q.x() < 0 || profile_side(tree, q, 1e-9 * size) != Side::inside) continue;
        *out = s.R * Vec3(q.x(), 0, q.y()) + s.t;
        return true;
      }
      return false;  // one try: the first leaf's neighbourhood
    }
    return false;
  }

  // Side of world point x for this solid (true profile; unknown within margin).
  // A point outside the root's disk is outside: the meridian section is
  // bounded by the profile (and the axis between its ends), all within that
  // convex disk; only points inside it pay for the scan over the leaves.
  Side side_of(const Vec3& x, double margin) {
    const Vec2 q = meridian(x);
    if ((q - parts[0].disk_c).norm() > parts[0].disk_r + margin) return Side::outside;
    return profile_side(tree, q, margin);
  }
};

// The neighbour memo's key (solid_distance): a side, an end of a fit, the
// other fit by its span, and the neighbour fit's piece and end parameter.
struct NeighbourKey {
  bool mine_is_a;
  int dir, other_piece, piece;
  double other_u0, other_u1, u;
  bool operator==(const NeighbourKey& k) const {
    return mine_is_a == k.mine_is_a && dir == k.dir && other_piece == k.other_piece && piece == k.piece &&
           other_u0 == k.other_u0 && other_u1 == k.other_u1 && u == k.u;
  }
};
struct NeighbourHash {
  // The bit pattern of x (x + 0.0 makes -0.0 and 0.0, which compare equal,
  // one pattern): cheaper than std::hash<double>, which is a byte-wise hash.
  static std::uint64_t bits(double x) {
    x += 0.0;
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  }
  std::size_t operator()(const NeighbourKey& k) const {
    std::uint64_t h = bits(k.u);
    for (std::uint64_t v : {bits(k.other_u0), bits(k.other_u1), static_cast<std::uint64_t>(k.other_piece),
                            static_cast<std::uint64_t>(k.piece), static_cast<std::uint64_t>(k.dir * 2 + k.mine_is_a)})
      h = (h ^ v) * 0x9e3779b97f4a7c15ull;
    // The table takes the low bits, and a product's low bits depend only on
    // its factors' low bits, which are 0 in the doubles of dyadic span ends
    // (0.5, 0.375, ...): the finaliser of MurmurHash3 brings the high bits down.
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    return static_cast<std::size_t>(h);
  }
};
// A flat hash table from neighbour keys to indices (the first insert of a key
// wins), open addressing with linear probing. The slots hold 32-bit positions
// in the list of entries (0: empty), so the table is small to clear and to
// grow: slots of whole entries (64 bytes) cost 3 % of the query's
// instructions at eps 1e-7 in value-initialisation and rehashing alone.
class NeighbourTable {
 public:
  NeighbourTable() : slots_(256, 0) { entries_.reserve(64); }
  void emplace(const NeighbourKey& k, std::size_t v) {
    std::uint32_t& s = slots_[index(k)];
    if (s != 0) return;
    entries_.push_back({k, v});
    s = static_cast<std::uint32_t>(entries_.size());
    if (4 * entries_.size() > 3 * slots_.size()) grow();
  }
  // Empty again (a table grown by a long query shrinks back).
  void clear() {
    if (slots_.size() > 256) slots_.assign(256, 0);
    else std::fill(slots_.begin(), slots_.end(), 0);
    entries_.clear();
  }
  // The index stored for k, or nullptr.
  const std::size_t* find(const NeighbourKey& k) const {
    const std::uint32_t s = slots_[index(k)];
    return s != 0 ? &entries_[s - 1].value : nullptr;
  }

 private:
  struct Item {
    NeighbourKey key;
    std::size_t value;
  };
  // The slot holding k, or the empty one where it belongs.
  std::size_t index(const NeighbourKey& k) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = NeighbourHash()(k) & mask;
    while (slots_[i] != 0 && !(entries_[slots_[i] - 1].key == k)) i = (i + 1) & mask;
    return i;
  }
  void grow() {
    slots_.assign(slots_.size() * 2, 0);
    for (std::size_t e = 0; e < entries_.size(); ++e) slots_[index(entries_[e].key)] = static_cast<std::uint32_t>(e + 1);
  }
  std::vector<std::uint32_t> slots_;
  std::vector<Item> entries_;
};

// (16 bytes, not 24: the heap moves entries on every push and pop; the
// motion probe takes 131.8 -> 130.9 M instructions at eps 1e-5. A 4-ary
// heap of them instead of std::priority_queue's binary one: 133.8. B's part
// index in 31 bits: 2^30 parts of ~200 bytes would not fit in memory.)
struct Entry {
  double lb;
  std::int32_t a;
  std::int32_t b : 31;
  std::uint32_t tight : 1;  // lb is the tight bound (pair_bound), not only the cheap one
  bool operator<(const Entry& o) const { return lb > o.lb; }  // min-heap
};
static_assert(sizeof(Entry) == 16);

// A min-heap of entries (the least lb on top) in a vector it does not own.
class EntryHeap {
 public:
  explicit EntryHeap(std::vector<Entry>& v) : v_(v) { v_.clear(); }
  bool empty() const { return v_.empty(); }
  const Entry& top() const { return v_.front(); }
  void push(const Entry& e) {
    v_.push_back(e);
    std::push_heap(v_.begin(), v_.end());
  }
  void pop() {
    std::pop_heap(v_.begin(), v_.end());
    v_.pop_back();
  }

 private:
  std::vector<Entry>& v_;
};

// The query's queue of node pairs. Pairs whose lower bound is above 0 are
// taken least bound first (Algorithm 2's order). A bound at or below 0 (the
// pairs' bounding tori meet) tells nothing of where the contact is, and
// every such pair is taken before any other: those are taken closest centre
// circles first (`centre`: the bound plus kKeyDisks of both disk radii), which
// reaches the leaf pairs at the contact first, and between overlapping solids
// a crossing pair. A pair taken so reports -inf as its bound: the queue's stop
// test (the least bound left reaches the cut) stays exact, and once the cut
// is at most 0 (an upper bound within tol of touching) the loop retires such
// a pair when its own bound reaches the cut. (Until 2026-11 the queue went
// back to the bound order there: where a first witness near a crossing
// comes within tol of touching and its probes fail, the bound order takes
// the pairs of most overlap first, not those at the crossing. The bottles of
// solid_overlap_crossing_key_bottles.json, whose first witness now lands
// 4.6e-7 from the crossing: 121 node pairs before the overlap is proven, 12
// in the centre order. Motion probe, M instructions for 600 queries at eps
// 1e-5 / 1e-3 / 1e-7 / tol 1e-6: 86.69 / 70.67 / 142.73 / 119.30 -> 86.84 /
// 70.87 / 142.92 / 119.43; 30000 queries, least of 3, the overlap frames'
// p99 at eps 1e-5 85.6 -> 84.6 us.)
class PairQueue {
 public:
  PairQueue(std::vector<Entry>& by_bound, std::vector<Entry>& by_centre) : bound_(by_bound), centre_(by_centre) {}
  bool empty() const { return bound_.empty() && centre_.empty(); }
  // The next pair; its lb is -inf when it is taken by its centre key.
  Entry top() const {
    if (centre_.empty()) return bound_.top();
    Entry e = centre_.top();
    e.lb = -std::numeric_limits<double>::infinity();
    return e;
  }
  void pop() {
    if (!centre_.empty()) centre_.pop();
    else bound_.pop();
  }
  void push(const Entry& e, double centre) {
    if (e.lb <= 0) centre_.push({centre, e.a, e.b, e.tight});
    else bound_.push(e);
  }
  // Whether a pair of bound lb and centre key `centre`, pushed now, would be
  // the next one taken.
  bool would_be_next(double lb, double centre) const {
    if (lb <= 0) return centre_.empty() || centre <= centre_.top().lb;
    return centre_.empty() && (bound_.empty() || lb <= bound_.top().lb);
  }
  // The least bound of the pairs left (-inf while some are taken by their centre key).
  double least() const {
    return !centre_.empty() ? -std::numeric_limits<double>::infinity()
           : bound_.empty() ? std::numeric_limits<double>::infinity() : bound_.top().lb;
  }

 private:
  EntryHeap bound_, centre_;
};

// A lower bound on the distance between the fits of a pair compared (before
// the eps are taken off), the fits by their parts of A and B.
struct FitBound {
  std::int32_t a, b;
  double lb;
};

// A query's containers, one set per thread, kept from query to query: a
// query then allocates nothing once the storage has grown (14 allocations a
// query on the motion probe before). Storage that a long query grew past
// kKeep elements is given back at the next one.
struct QueryStorage {
  std::vector<Part> parts[2];
  std::deque<BiarcFit> fits[2];
  std::vector<Entry> heap, heap_centre;
  std::vector<FitBound> fit_bounds;
  NeighbourTable neighbours;
  static constexpr std::size_t kKeep = 1 << 14;
  QueryStorage& ready() {
    for (auto* v : {&parts[0], &parts[1]})
      if (v->capacity() > kKeep) std::vector<Part>().swap(*v);
    if (heap.capacity() > kKeep) std::vector<Entry>().swap(heap);
    if (heap_centre.capacity() > kKeep) std::vector<Entry>().swap(heap_centre);
    if (fit_bounds.capacity() > kKeep) std::vector<FitBound>().swap(fit_bounds);
    for (auto* f : {&fits[0], &fits[1]})
      if (f->size() > kKeep) std::deque<BiarcFit>().swap(*f);
    fit_bounds.clear();
    neighbours.clear();
    return *this;
  }
};

// The cheap lower bound between two parts, in closed form (no iteration):
// their bounding tori (disks rotated) are at least the closed-form circle
// bound of their centre circles minus the disk radii apart. Used when a pair
// is queued; the tight bound is computed only if the pair is popped.
// `axes` holds the two solids' axes (every part's circle is about its solid's).
double cheap_bound(const CircleBoundAxes& axes, const Part& pa, const Part& pb) {
  return axes(pa.world_c, Solid::disk_circle_radius(pa), pb.world_c, Solid::disk_circle_radius(pb)) - pa.disk_r -
         pb.disk_r;
}

// The tight lower bound between two parts with fits: their bounding tori by
// the exact circle distance of the disks' centre circles, an iterative solve
// (~2000 instructions). Only pairs of fits pay for it, in front of their
// kernels: a pair with a tree node is split instead, its children queued with
// cheap bounds, which costs less than the solve (measured on the motion
// probe: 955 M instructions against 1021 M, 145 node pairs against 108, the
// same leaf pairs). (Bounds from the fits' patches at inner nodes cut node
// pairs by a fifth but cost more than they save: 25% more instructions.)
double pair_bound(const Solid& A, const Part& pa, const Solid& B, const Part& pb) {
  return circle3_circle3_distance_value(A.disk_circle(pa), A.frame, B.disk_circle(pb), B.frame) - pa.disk_r - pb.disk_r;
}

// A lower bound on the least of dist over the segment p0 p1, where dist is a
// point's distance from a set (1-Lipschitz), proven at least `need`, or -inf
// when a point of the segment is closer than that or the proof takes more
// than `budget` evaluations: the segment cut in halves until the chord lemma
// (chord_bound, fast/patch_distance.h) clears each piece. p0 == p1: one
// evaluation.
template <class Dist>
double segment_at_least(const Vec3& p0, const Vec3& p1, double need, int budget, Dist dist) {
  struct End {
    Vec3 y;
    double d;
  };
  const End a{p0, dist(p0)};
  if (!(a.d >= need)) return -kInf;
  if (p0 == p1) return a.d;
  const End b{p1, dist(p1)};
  if (!(b.d >= need)) return -kInf;
  constexpr int kOpen = 48;
  std::pair<End, End> open[kOpen];
  int n = 0, evals = 2;
  open[n++] = {a, b};
  double least = kInf;
  while (n > 0) {
    const auto [u, v] = open[--n];
    if (const double bound = chord_bound(u.d, v.d, (v.y - u.y).squaredNorm()); bound >= need) {
      least = std::min(least, bound);
      continue;
    }
    if (evals >= budget || n + 2 > kOpen) return -kInf;
    const Vec3 mid = 0.5 * (u.y + v.y);
    const End m{mid, dist(mid)};
    ++evals;
    if (!(m.d >= need)) return -kInf;
    open[n++] = {u, m};
    open[n++] = {m, v};
  }
  return least;
}

// Where a cold query's first witness starts, on leaf parts a of A and b of
// B: a point of b's centre circle from alternating projection between the
// two centre circles, in closed form, from B's point nearest A's centre
// (three projections onto B's circle; a start, not the circles' closest pair:
// their solve cost 2.3 % of the median query; two, four or five projections
// did worse).
Vec3 leaf_start(const Solid& A, const Part& a, const Solid& B, const Part& b) {
  const Circle3 ca = A.disk_circle(a);
  Vec3 y;
  circle3_circle3_upper_bound(B.disk_circle(b), ca, ca.center, 3, &y);
  return y;
}

// The query (Algorithm 2), from a warm start when one is given.
SolidDistanceResult query(const PosedSolid& pa, const PosedSolid& pb, const DistanceOptions& opt, const WarmStart* warm) {
  SolidDistanceResult res;
  if (!pa.tree || !pb.tree || pa.tree->nodes.empty() || pb.tree->nodes.empty()) {
    res.reason = "empty profile";
    return res;
  }
  thread_local QueryStorage storage;
  QueryStorage& mem = storage.ready();
  Solid A(pa, mem.parts[0], mem.fits[0]), B(pb, mem.parts[1], mem.fits[1]);
  DistanceStats& st = res.stats;
  // Rounding of world coordinates: a few ulps of the largest one involved.
  // (A root disk is unbounded where a fit is unproven, a near-cusp the lens
  // bound cannot hold: then the profile's box. An infinite allowance made
  // every upper bound infinite, and the answer no finite bracket.)
  auto extent = [](const Solid& S) {
    const Part& root = S.parts[0];
    if (std::isfinite(root.disk_r)) return root.disk_c.norm() + root.disk_r;
    Vec2 lo, hi;
    profile_box(*S.s.profile, &lo, &hi);
    return std::max(lo.norm(), hi.norm());
  };
  // The error of the fits a cold first witness starts on (first_witness): a
  // fraction kWitnessCoarse of the solid's extent where the leaves are at
  // least kCoarseLeaves times finer than that, else 0 (the leaves). A walk
  // across fits crosses one fit a step, and at eps 1e-7 a conformal contact
  // or an edge spans dozens of leaves: measured on the motion probe's 30000
  // queries at eps 1e-7, least of 3 runs, the first witness took 28 % of the
  // instructions of the queries between the p85 and the p95, and started
  // from each query's own answer (--perfect-warm) the p90 was 26.8 us
  // against 45.5. From fits of 1e-3 of the extent: p90 45.5 -> 37.3 us,
  // median 11.5 -> 11.7, mean 22.7 -> 21.2; 3e-3, 3e-4 and 1e-2: p90 37.0,
  // 37.1 and 37.8. At eps 1e-6: p90 31.3 -> 28.2, median 9.8 -> 10.6. At
  // eps 1e-5 (leaves about 150 times finer) it would cost more than it
  // saves: median 8.4 -> 9.4, p90 22.5 -> 21.9, 77.1 -> 79.3 M instructions
  // for the probe's 600 queries.
  auto coarse_witness = [&](const Solid& S) {
    const double coarse = kWitnessCoarse * extent(S);
    return S.s.tree->eps * kCoarseLeaves <= coarse ? coarse : 0.0;
  };
  const double coord = std::max({pa.t.cwiseAbs().maxCoeff(), pb.t.cwiseAbs().maxCoeff(), extent(A), extent(B)});
  const double round = 256 * DBL_EPSILON * coord;

  auto proven_overlap = [&](const Vec3& p) {
    res.overlap = true;
    res.converged = true;
    res.decided = std::isfinite(opt.threshold);  // distance 0 settles any threshold
    res.lower = res.upper = res.distance = 0.0;
    res.point_a = res.point_b = p;
    st.nodes_built = A.tree.nodes_built() + B.tree.nodes_built();
    return res;
  };

  // Overlap probes: a genuine point of one solid's surface strictly inside
  // the other (kept in `shared`) proves that they overlap.
  Vec3 shared = Vec3::Zero();
  auto in_b = [&](const Vec3& t) { return B.side_of(t, round) == Side::inside ? (shared = t, true) : false; };
  auto in_a = [&](const Vec3& t) { return A.side_of(t, round) == Side::inside ? (shared = t, true) : false; };

  double ub = kInf;
  // The steps across each surface's tangent plane (Solid::across) from a
  // point pair whose surfaces may cross near it, x near fit fa of A and y
  // near fb of B: 5 lengths from the longer fit's chord down to 1/256 of it.
  // Pairs more than `reach` times that chord apart are left alone (reach 0:
  // no limit). True when a step proves an overlap (the point in `shared`).
  auto probe_across = [&](const BiarcFit& fa, const Vec3& x, const BiarcFit& fb, const Vec3& y, double reach) {
    const double len = std::max((fa.end() - fa.start()).norm(), (fb.end() - fb.start()).norm());
    if (reach > 0 && !((x - y).norm() <= reach * len)) return false;
    const Solid::CurvePoint p = A.curve_point(fa, x), q = B.curve_point(fb, y);
    return A.across(p, q, len, 5, in_b) || B.across(q, p, len, 5, in_a);
  };
  // The witness's overlap probe: its points, then the input curve along their
  // meridians from the spans of fits fa and fb (alternating projection stops
  // near a crossing, where no point is inside; a step along the profile goes
  // in), then the steps across. True when it proves an overlap (the point in
  // `shared`).
  auto probe_witness = [&](const BiarcFit& fa, const BiarcFit& fb) {
    const Vec3 wa = res.point_a, wb = res.point_b;
    return in_b(wa) || in_a(wb) || A.along_meridian(fa, wa, 3, in_b) || B.along_meridian(fb, wb, 3, in_a) ||
           probe_across(fa, wa, fb, wb, 0.0);
  };
  // The queue stops below cut(): the bracket then meets tol or rel_tol.
  const double rel = std::max(opt.rel_tol, 0.0);
  double tol = opt.tol;  // (relaxed below when doubles cannot resolve it)
  // Stop when lower >= ub - tol or lower >= ub / (1 + rel_tol): either tolerance met.
  // (Kept in cut_v, set again wherever ub or tol changes: it is read at every
  // pair. A stale value could only be above the true cut, which prunes less.)
  double cut_v;
  auto set_cut = [&] { cut_v = rel > 0 ? std::min(ub - tol, ub / (1.0 + rel)) : ub - tol; };
  set_cut();
  auto cut = [&] { return cut_v; };
  const bool threshold = std::isfinite(opt.threshold);
  // Upper bounds are rounded outward: the rounded norm of two rounded witness
  // points, each a few ulps of the coordinates from the true surface point it
  // stands for.
  const double up_round = 32 * DBL_EPSILON * coord;
  auto offer = [&](const Vec3& x, const Vec3& y) {
    const double d = (x - y).norm() + up_round;
    if (d < ub) {
      ub = d;
      set_cut();
      res.point_a = x;
      res.point_b = y;
    }
  };

  // The previous pose's answer (frame coherence), its points checked against
  // the solids: within `round` of its solid (not outside), the pair bounds
  // the distance from above by their distance plus those margins; after an
  // overlap, the shared point of one solid still inside the other proves it.
  if (warm && warm->valid) {
    const Vec3 x = pa.R * warm->a_local + pa.t, y = pb.R * warm->b_local + pb.t;
    const bool x_in = A.side_of(x, round) != Side::outside, y_in = B.side_of(y, round) != Side::outside;
    if (warm->overlap) {
      if ((x_in && in_b(x)) || (y_in && in_a(y))) return proven_overlap(shared);
    }
    if (x_in && y_in) {
      ub = (x - y).norm() + up_round + 2 * round;
      set_cut();
      res.point_a = x;
      res.point_b = y;
    }
  }

  const CircleBoundAxes axes(A.axis, B.axis);

  // Containment: a surface point of one solid strictly inside the other.
  bool containment_unknown = false;
  // Once the surfaces are apart every point of one decides, so a point within
  // rounding of the other's boundary (a sharp pole 1e-6 from it) gives way to
  // the next of a few (it left the bracket at [0, 1e-6] before).
  {
    auto side_of_surface = [&](Solid& X, Solid& Y, Vec3* at) {
      Side side = Side::unknown;
      for (int k = 0; k < Solid::kSurfacePoints && side == Side::unknown; ++k) {
        *at = X.surface_point(k);
        side = Y.side_of(*at, round);
      }
      return side;
    };
    Vec3 x, y;
    const Side sa = side_of_surface(A, B, &x);
    if (sa == Side::inside) return proven_overlap(x);
    const Side sb = side_of_surface(B, A, &y);
    if (sb == Side::inside) return proven_overlap(y);
    containment_unknown = sa == Side::unknown || sb == Side::unknown;
    // Coincident surfaces leave those points undecided: an interior point of
    // one solid inside the other still proves the overlap.
    Vec3 p;
    if (containment_unknown && A.interior_point(&p) && in_b(p)) return proven_overlap(shared);
    if (containment_unknown && B.interior_point(&p) && in_a(p)) return proven_overlap(shared);
  }

  // The first witness pair: a few rounds of alternating projection onto the
  // surfaces, from `start`. True when it proves an overlap (the point in
  // `shared`). A warm start's pair starts it before the traversal (the
  // previous frame's contact is near this one's: on the motion probe's
  // sequences, 158.8 -> 146.5 M instructions at eps 1e-5, 6-9 % less at
  // 1e-3, 1e-7 and tol 1e-6, than from the root circles; proven overlaps 37
  // against the cold queries' 38 at 1e-3, where one bracket [0, u <= tol]
  // goes without the proof, and 197 against 196 on 3000 queries at 1e-5).
  // A cold query's starts at the first leaf pair the traversal takes (the
  // loop below: in the centre order, the leaves nearest the contact; those
  // pops are the traversal's own), from leaf_start. Measured on the motion
  // probe's 3000 queries at eps 1e-5: first witnesses within tol of the
  // answer 1271 of 2811 from the root disks' circles, the rest a median 0.5
  // away (another contact), 1764 from a greedy dive by the centre key; from
  // the first leaf pair, against that dive, M instructions for 600 queries at
  // eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6 96.8 / 76.9 / 198.6 / 145.5 -> 93.3 /
  // 75.5 / 194.8 / 141.1, median / p90 us 12.65 / 39.9 -> 12.2 / 37.0. A
  // threshold query answered "closer" needs only one pair below the
  // threshold, and the best-first loop below, which would first tighten
  // every bound under the threshold, then stops at once; any other query
  // has an upper bound near the distance, so the local proofs of the first
  // leaf pairs can pass (measured: 5 % fewer instructions on the motion probe).
  // The rounds project onto the fits' patches; only the last pair is mapped
  // to the input curves (true_point, ten times a patch projection's cost).
  bool have_witness = false;
  const double coarse_a = coarse_witness(A), coarse_b = coarse_witness(B);
  const bool fine_trees = coarse_a > 0 && coarse_b > 0;
  auto first_witness = [&](const Vec3& start) {
    have_witness = true;
    Vec3 y = start, x = y;
    BiarcFit fx, fy;
    Patch px, py;  // the patches the pair is on
    // Where the leaves are far finer than kWitnessCoarse of the extent (eps
    // at most 1e-3 of it), the rounds, the descent and the walk run first on
    // the tree's own fits of that error (coarse: nodes above the leaves),
    // then once more from the fine fits nearest the pair they reach
    // (coarse_witness).
    // Between nearly parallel sides each round moves the pair only a little
    // way along them: the point projected onto A is pushed on by 0.7 of B's
    // last move (any point may be projected; the pair stays genuine). Eight
    // rounds, fewer once the pair moves by under 1 % of its distance.
    // Measured on the motion probe at eps 1e-5 (M instructions, node pairs a
    // query): three plain rounds 182.0 / 94.7, eight 178.7 / 88.8, these
    // 168.8 / 84.4 (pushes of 0.5 to 0.85 and 8 to 14 rounds: 169.5-172.4;
    // a push of 2 overshoots: 198.5).
    Vec3 ys = y;
    for (int i = 0; i < 8; ++i) {
      const Vec3 x0 = x, y0 = y;
      fx = A.nearest_fit(ys, coarse_a);
      px = A.nearest_patch(fx, ys, &x);
      fy = B.nearest_fit(x, coarse_b);
      py = B.nearest_patch(fy, x, &y);
      if (i > 0 && (x - x0).norm() + (y - y0).norm() <= 1e-2 * (x - y).norm()) break;
      ys = i > 0 ? Vec3(y + 0.7 * (y - y0)) : y;
    }
    // The rounds converge linearly, and stop at a 1 % move: the pair is
    // then still far from its local minimum by much more than tol. Newton
    // steps on the two patches the pair ends on (patch_pair_descent) pin it
    // down; with the upper bound and the hulls' direction exact, the bounds
    // retire more pairs before any kernel runs. Measured on the motion probe
    // (M instructions, 600 queries): eps 1e-3 123.3 -> 114.6, 1e-5 168.8 ->
    // 155.6, 1e-7 369.2 -> 349.9, tol 1e-6 212.2 -> 207.4 (a second round
    // of fits and Newton steps: 158.2 at 1e-5). A witness exact from the
    // start (the same query's answer as a warm start) halves the median time:
    // the rest of the gap is pairs whose rounds end at another local minimum.
    {
      Vec3 xs, ys2;
      patch_pair_descent(px, py, x, 1e-3 * opt.tol, &xs, &ys2);
      if (xs.allFinite() && ys2.allFinite()) x = xs, y = ys2;
    }
    // A descent that ends at an end of its patch (P's profile fraction
    // clamped to 0 or 1, or Q's nearest point at one of Q's end circles) has
    // stopped at the patch's boundary, not at a minimum: the fit and patch
    // nearest the pair are taken again on each side that ended there, and a
    // descent on the new pair, up to 24 times while the pair gets closer
    // (at eps 1e-7 fits are short, and a pair sliding along a conformal
    // contact or an edge crosses a fit at each step). (End points are met
    // to the rounding of the coordinates, well within `round`; far from the
    // origin a patch shorter than that is all ends, which only costs the
    // steps.) Measured on the motion probe, M
    // instructions for 600 queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6:
    // 117.7 / 95.5 / 242.8 / 177.1 -> 113.3 / 93.9 / 231.4 / 176.4 (local
    // boxes 45.8 -> 43.7 a query); first witnesses within tol of the answer,
    // of 2800 queries at eps 1e-5: 865 -> 1270. (In a trial build, from
    // 119.0 at 1e-5: two steps 115.0, and 235.4 at 1e-7 against 233.5;
    // six 115.0; the fit's ends only, not the junction of its arcs, 117.2;
    // from 4 rounds instead of 8, 123.0; the nearest fits by a
    // branch-and-bound search instead of the greedy descent, 116.2. Later,
    // from 87.4 / 73.8 / 147.3 / 120.9: 8 steps 87.1 / 73.8 / 145.2 / 120.6,
    // 24 steps 87.2 / 73.8 / 144.3 / 120.7, 64 the same; 30000 queries at
    // 1e-7, least of 3, p90 57.9 -> 55.4 us. Taking, at a spiral's end
    // inside a piece, the fit across it (the greedy nearest fit from the
    // other point comes back to the same fit there): first witnesses within
    // tol of the answer 18481 -> 19317 of 30000, but 145.97 M at 1e-7 and
    // 1-2 % more at the other eps.)
    // The steps take the nearest fits by closest_fit's search, not by
    // nearest_fit's greedy descent, which near a long exact leaf returns the
    // leaf whose disk holds the point (and at a spiral's end inside a piece
    // the same fit again). Measured on the motion probe: first witnesses
    // more than 1e-4 above the answer, of 30000 queries at eps 1e-7, 9159 ->
    // 2754 (1e-5: 9553; 1e-3: 10073 before); M instructions for 600 queries
    // at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6 86.88 / 73.59 / 143.39 / 120.30
    // -> 86.36 / 70.53 / 142.15 / 118.91; 30000 queries, least of 3, p90 at
    // eps 1e-3 / 1e-5 / 1e-7 22.7 / 28.3 / 54.3 -> 20.8 / 27.2 / 53.7 us,
    // proven overlaps' p90 at 1e-3 15.0 -> 12.0. (The search in the rounds
    // too: 91.81 / 75.95 / 148.29 / 124.05; in their first only: 86.65 /
    // 71.33 / 142.94 / 119.33.)
    auto walk = [&](double ca, double cb) {
      auto at_end = [&](const Patch& p, const Vec3& w) {
        const Vec2 q = patch_local(p, w);
        return (q - p.p0).norm() <= round || (q - p.p1).norm() <= round;
      };
      auto same = [](const Patch& a, const Patch& b) { return a.p0 == b.p0 && a.p1 == b.p1; };
      for (int step = 0; step < 24; ++step) {
        const bool end_x = at_end(px, x), end_y = at_end(py, y);
        if (!end_x && !end_y) break;
        BiarcFit nfx = fx, nfy = fy;
        Patch npx = px, npy = py;
        Vec3 nx = x;  // the descent's start on A's side
        if (end_x) nfx = A.closest_fit(y, ca), npx = A.nearest_patch(nfx, y, &nx);
        if (end_y) nfy = B.closest_fit(nx, cb), npy = B.nearest_patch(nfy, nx);
        if (same(npx, px) && same(npy, py)) break;
        Vec3 xs, ys2;
        const double d = patch_pair_descent(npx, npy, nx, 1e-3 * opt.tol, &xs, &ys2);
        if (!(xs.allFinite() && ys2.allFinite() && d < (x - y).norm())) break;
        fx = nfx, fy = nfy, px = npx, py = npy, x = xs, y = ys2;
      }
    };
    walk(coarse_a, coarse_b);
    if (coarse_a > 0 || coarse_b > 0) {  // the leaves nearest the coarse pair, a descent on them and the walk
      Vec3 x2 = x, y2 = y;
      fx = A.closest_fit(x), px = A.nearest_patch(fx, x, &x2);
      fy = B.closest_fit(y), py = B.nearest_patch(fy, y, &y2);
      Vec3 xs, ys2;
      patch_pair_descent(px, py, x2, 1e-3 * opt.tol, &xs, &ys2);
      if (xs.allFinite() && ys2.allFinite()) x = xs, y = ys2;
      else x = x2, y = y2;
      walk(0.0, 0.0);
    }
    const Vec3 tx = A.true_point(fx, x), ty = B.true_point(fy, y);
    offer(tx, ty);
    // Alternating projection between crossing surfaces converges to their
    // crossing: a first witness within its fits' errors and tol of each
    // other gets the overlap probe now, before any traversal, instead of
    // when a leaf pair's patches are found to cross. Measured on the motion
    // probe, M instructions for the 198 proven overlaps of 3000 queries at
    // eps 1e-5 and 1e-3: 44.8 / 33.3 -> 35.0 / 24.2; for the 600 queries at
    // eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6: 112.5 / 93.0 / 230.1 / 172.8 ->
    // 110.5 / 92.1 / 230.0 / 171.7. (Within 3 and 10 times that: 33.4 and
    // 31.9 on the overlaps, but 93.9 and 98.0 for the 600 at eps 1e-3, where
    // it takes in most near contacts; the points alone, without the
    // meridians: 38.8 on the overlaps.) Where the rounds slow down near a
    // crossing (surfaces at a small angle) the pair stops short of it: a
    // pair farther apart than that but within kAcrossReach of the fits'
    // chord gets the steps across (most pairs at a separated minimum have
    // parallel normals, and take no step).
    if (ub <= fx.eps + fy.eps + opt.tol) return probe_witness(fx, fy);
    return probe_across(fx, tx, fy, ty, kAcrossReach);
  };
  if (ub < kInf && first_witness(res.point_b)) return proven_overlap(shared);  // (only a warm start sets ub here)

  // (The centre order, against the bound order for all pairs: on the motion
  // probe's 3000 queries, least of 3 runs, median / p90 / mean us at eps 1e-5
  // 14.2 / 43.2 / 22.2 -> 12.6 / 39.8 / 20.9, at 1e-3 11.4 / 35.1 / 17.7 ->
  // 10.4 / 33.2 / 17.0, at 1e-7 18.9 / 97.0 / 44.9 -> 16.9 / 90.3 / 43.0, tol
  // 1e-6 22.1 / 60.7 / 31.9 -> 20.0 / 57.9 / 30.8; instructions 478.2 ->
  // 476.0 M at eps 1e-5, the 189 proven overlaps' 29.0 -> 26.6 M, their p95
  // 57.9 -> 50.4 us but their two slowest 73 and 116 -> 94 and 96.)
  PairQueue heap(mem.heap, mem.heap_centre);
  // The hull bounds along the witness's direction (res.point_a - res.point_b),
  // prepared once for each witness: most pops of a query see the same one.
  RevolvedHullDirection witness_dir(pa.t, A.axis, pb.t, B.axis, Vec3::Zero());
  auto witness_hull = [&]() -> const RevolvedHullDirection& {
    const Vec3 u = res.point_a - res.point_b;
    if (u != witness_dir.dir()) witness_dir = RevolvedHullDirection(pa.t, A.axis, pb.t, B.axis, u);
    return witness_dir;
  };
  // A lower bound on the distance between fit part f of F and part x of X
  // (its eps and rounding taken off), -inf when the proof at the cut fails:
  // f's patches against x's disk circle (patch_circle_at_least).
  auto fit_spine_bound = [&](const Solid& F, const Part& f, const Solid& X, const Part& x) {
    const BiarcFit& fit = F.fit(f);
    const double need = cut() + fit.eps + round;
    const Circle3 spine = X.disk_circle(x);
    const Vec3& hint = &X == &B ? res.point_b : res.point_a;
    const Patch* W = F.fit_patches(fit);  // (a big fit meets many small parts in a row: made once)
    double least = kInf;
    for (int i = 0; i < fit.arcs; ++i) {
      if (fit.arc[i].length <= 0) continue;
      double lower = 0.0;
      int evals = 0;
      const bool ok = patch_circle_at_least(W[i], spine, x.disk_r, need, round, kSpineBudget, &lower, &evals,
                                            have_witness ? &hint : nullptr);
      st.spine_evals += evals;
      if (!ok) return -kInf;
      least = std::min(least, lower);
    }
    return least - fit.eps - round;
  };
  // Whether patches P of A and Q of B are at least c apart by the spine
  // bounds, either way (patch_spine_at_least; *bound then bounds it).
  auto spines_at_least = [&](const Patch& P, const Patch& Q, double c, double* bound) {
    int evals = 0, more = 0;
    const bool ok = patch_spine_at_least(P, Q, c, round, kSpineBudget, bound, &evals, &res.point_b) ||
                    patch_spine_at_least(Q, P, c, round, kSpineBudget, bound, &more, &res.point_a);
    st.spine_evals += evals + more;
    return ok;
  };
  // A lower bound on the distance between parts qa of A and qb of B from
  // either's fit when its arcs are axis zones (Solid::axis_zones): a point
  // of a zone is within its radius of the zone's piece of axis, so at least
  // that piece's distance from the other part less the radius away from it;
  // -inf when neither fit is such, or when a cylinder's segment cannot be
  // shown at least `need` from the other part (its points' distances, and
  // between two points the chord lemma of the spine bounds: the other part
  // avoids both points' balls). A sphere zone is one evaluation.
  auto zone_bound = [&](const Part& qa, const Part& qb) {
    double best = -kInf;
    for (int side = 0; side < 2; ++side) {
      Solid& F = side == 0 ? A : B;
      Solid& X = side == 0 ? B : A;
      const Part& f = side == 0 ? qa : qb;
      const Part& x = side == 0 ? qb : qa;
      if (!f.has_fit) continue;
      const BiarcFit& fit = F.fit(f);
      Solid::Zone zones[2];
      int n = 0;
      if (!F.axis_zones(fit, zones, &n)) continue;
      double least = kInf;
      for (int k = 0; k < n && least > -kInf; ++k) {
        const Solid::Zone& z = zones[k];
        const double need = cut() + z.radius + fit.eps + round;
        least = std::min(least, segment_at_least(z.a0, z.a1, need, kZoneBudget,
                                                 [&](const Vec3& y) { return X.part_distance_from(x, y); }) -
                                    z.radius);
      }
      best = std::max(best, least - fit.eps - round);
    }
    return best;
  };
  // A lower bound on the distance between parts ha of A and hb of B from
  // their own fits (a tree node at or below the spiral level has one, of a
  // proven error: BiarcTree), -inf when it is not proven at the cut: each
  // arc pair of the two fits by the hulls along the witness's direction or a
  // spine bound (patch_spine_at_least, both ways), less both fits' errors.
  // Only for pairs with a node above the leaves (leaf pairs go to the
  // kernels) whose fits are within kNodeFits of their disks' radii. A node's
  // fit proves a whole block of leaf pairs at once where the leaves are far
  // finer than the contact needs: at eps 1e-7 a pawn's body 0.0219 from a
  // bottle's shoulder, their distance varying slowly along both curves
  // (motion probe frame 5867), took 122 leaf pairs and 517 node pairs, 1 ms;
  // bounded by the nodes' fits, 57 node pairs and no leaf pair, 0.12 ms.
  // Measured on the motion probe, 30000 queries, least of 3: p90 at eps 1e-7
  // 37.5 -> 33.3 us, at 1e-6 28.2 -> 27.5; with the nodes' fits at every eps
  // the p90 at 1e-3 went 18.8 -> 20.0 (the nodes' fits there are about as
  // coarse as the tolerance, and most proofs fail), M instructions for 600
  // queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6 77.14 / 64.22 / 118.76 /
  // 110.50 -> 80.27 / 66.59 / 116.12 / 114.39; also only after a query's
  // first 64 pops: 78.37 / 64.66 / 119.17 / 112.00; only where the fits'
  // errors are under half the tol: 119.90 at 1e-7. So it runs where the
  // first witness starts coarse (fine_trees: the leaves 1000 times finer
  // than 1e-3 of the extent).
  auto node_fits_bound = [&](const Part& ha, const Part& hb) {
    if (ha.fit < 0 || hb.fit < 0 || (ha.has_fit && hb.has_fit) || !have_witness) return -kInf;
    const BiarcFit fa = A.fit(ha), fb = B.fit(hb);
    if (!(fa.eps + fb.eps <= kNodeFits * (ha.disk_r + hb.disk_r))) return -kInf;
    const double need = cut() + fa.eps + fb.eps + round;
    // (Patches made as the loop reaches them, not by Solid::fit_patches: that
    // one-fit cache holds the leaf a run of pairs shares, fit_spine_bound's,
    // and the witness's; and most calls end at their first arc pair.)
    double least = kInf;
    for (int i = 0; i < fa.arcs; ++i) {
      if (fa.arc[i].length <= 0) continue;
      const Patch P = make_patch(fa.arc[i], pa.R, pa.t);
      for (int j = 0; j < fb.arcs; ++j) {
        if (fb.arc[j].length <= 0) continue;
        const Patch Q = make_patch(fb.arc[j], pb.R, pb.t);
        double lower = witness_hull().patches(P, Q);
        if (!(lower >= need) && !spines_at_least(P, Q, need, &lower)) return -kInf;
        least = std::min(least, lower);
      }
    }
    return least - fa.eps - fb.eps - round;
  };
  heap.push({cheap_bound(axes, A.parts[0], B.parts[0]) - round, 0, 0, false}, 0.0);
  double settled_lb = kInf;  // min lower bound over pairs retired without a split
  // Lower bounds on the distance between the fits of the pairs compared so
  // far (before the eps are taken off), each fit named by its span (the same
  // in a lazy tree as in an eager one): a fit's end circle is part of the fit
  // of the adjacent span too, so a neighbour pair's bound also bounds that
  // circle's sub-problems against the same other fit.
  std::vector<FitBound>& fit_bounds = mem.fit_bounds;
  // The first pair compared for each (side, end, other fit, neighbour's
  // piece and end parameter): a lookup per leaf pair instead of a scan of all
  // earlier ones (which made long queries quadratic in their leaf pairs).
  NeighbourTable& neighbours = mem.neighbours;
  bool tried_witness = false;  // the witness's overlap probe (once a query)
  auto witness_probe = [&](const BiarcFit& fa, const BiarcFit& fb) {
    tried_witness = true;
    return probe_witness(fa, fb);
  };
  // The deep points of patches P (of fit fa) and Q (of fb) that may cross:
  // each patch's points deepest on either side of the other's whole surface
  // (patch_deep_point), descended from the witness, mapped to the input
  // curve and tested. Measured on the motion probe's 3000 queries at eps
  // 1e-5, in front of the enumeration: the 196 overlapping queries 65.3 ->
  // 49.4 M instructions (the slowest, 1.15 M -> 0.24 M), their p99 time
  // 269 -> 222 us.
  auto deep_probe = [&](const Patch& P, const Patch& Q, const BiarcFit& fa, const BiarcFit& fb) {
    const double resolution = 1e-3 * opt.tol;
    for (double side : {-1.0, 1.0})
      if (in_b(A.true_point(fa, patch_deep_point(P, Q, res.point_a, side, resolution))) ||
          in_a(B.true_point(fb, patch_deep_point(Q, P, res.point_b, side, resolution))))
        return true;
    return false;
  };
  auto remember = [&](std::int32_t ia, std::int32_t ib, double lb) {
    const BiarcFit &fa = A.fit(A.parts[ia]), &fb = B.fit(B.parts[ib]);
    // As A's neighbour `fa` of a later fit of A against fb: it precedes that
    // fit (dir 0) when fa.u1 is its start, follows it (dir 1) when fa.u0 is its end.
    for (int dir = 0; dir < 2; ++dir) {
      neighbours.emplace(NeighbourKey{true, dir, fb.piece, fa.piece, fb.u0, fb.u1, dir == 0 ? fa.u1 : fa.u0},
                         fit_bounds.size());
      neighbours.emplace(NeighbourKey{false, dir, fa.piece, fb.piece, fa.u0, fa.u1, dir == 0 ? fb.u1 : fb.u0},
                         fit_bounds.size());
    }
    fit_bounds.push_back({ia, ib, lb});
  };
  // The bound of the pair (neighbour of `mine` at its start (dir 0) or end,
  // `other`), less the rounding gap between the shared end points; -inf if
  // that pair has not been compared. mine_is_a: which side `mine` is on.
  auto neighbour_bound = [&](const BiarcFit& mine, int dir, const BiarcFit& other, bool mine_is_a) {
    const std::size_t* it = neighbours.find(
        NeighbourKey{mine_is_a, dir, other.piece, mine.piece, other.u0, other.u1, dir == 0 ? mine.u0 : mine.u1});
    if (!it) return -kInf;
    const FitBound& f = fit_bounds[*it];
    const BiarcFit& n = mine_is_a ? A.fit(A.parts[f.a]) : B.fit(B.parts[f.b]);
    const double gap = dir == 0 ? (n.end() - mine.start()).norm() : (n.start() - mine.end()).norm();
    return f.lb - gap;
  };
  bool unresolved = false;
  long local_failed = 0;  // local proofs that did not settle their pair

  // Pairs are queued with their cheap bound; the tight one (pairs of fits
  // only) is computed when a pair reaches the top of the queue, so pairs that
  // a later upper bound retires never pay for it. Every lower bound carries the same rounding
  // allowance (`round`).
  auto push_pair = [&](std::int32_t ia, std::int32_t ib) {
    const Part &qa = A.parts[ia], &qb = B.parts[ib];
    const double cheap = cheap_bound(axes, qa, qb);
    const double lb = cheap - round;
    if (lb >= cut()) {
      settled_lb = std::min(settled_lb, lb);
      return;
    }
    // The centre key: the closed-form bound of the disks' centre circles (less
    // 1 - kKeyDisks of both radii).
    // Where that is 0 (circles about axes far from parallel, each past the
    // other's plane, cylinder and sphere: around crossing surfaces, pairs at
    // the crossing and pairs a tube's width off it alike) the pairs would
    // be taken in no order, each paying for its tight bound before the
    // pair at the crossing is found: an estimate of the circles' distance
    // from above orders them (three rounds of alternating projection, a
    // point of each circle). Measured on the motion probe's 30000 queries,
    // least of 3 runs, at eps 1e-5: proven overlaps' p99 57.6 -> 50.4 us,
    // median 9.2 / 9.1 (cup-bottle frame 12432: 200 node pairs and 153
    // tight bounds before its crossing pair); M instructions for 600
    // queries at eps 1e-5 / 1e-7 +0.7 %, for the 200 overlap frames -2.6 %
    // (two rounds: p99 52.6).
    double centre = cheap + qa.disk_r + qb.disk_r;
    if (centre <= 0)
      centre = axes.upper(qa.world_c, Solid::disk_circle_radius(qa), qb.world_c, Solid::disk_circle_radius(qb), 3);
    heap.push({lb, ia, ib, false}, centre - (1 - kKeyDisks) * (qa.disk_r + qb.disk_r));
  };
  // Replaces pair e by the pairs of one side's children.
  auto split_pair = [&](const Entry& e, bool split_a) {
    if (split_a) {
      const std::int32_t c = A.split(e.a, &st.refined);
      push_pair(c, e.b);
      push_pair(c + 1, e.b);
    } else {
      const std::int32_t c = B.split(e.b, &st.refined);
      push_pair(e.a, c);
      push_pair(e.a, c + 1);
    }
  };

  while (!heap.empty()) {
    const Entry e = heap.top();
    // A cold query's first witness, at the first leaf pair (the pair is
    // taken again with the upper bound it gives).
    if (!have_witness && A.parts[e.a].has_fit && B.parts[e.b].has_fit) {
      if (first_witness(leaf_start(A, A.parts[e.a], B, B.parts[e.b]))) return proven_overlap(shared);
      continue;
    }
    if (e.lb >= cut()) break;  // every remaining pair is at least e.lb away
    if (threshold && (ub <= opt.threshold || std::min(e.lb, settled_lb) > opt.threshold)) {
      res.decided = true;
      break;
    }
    heap.pop();
    if (e.lb == -kInf && cut() <= 0) {  // taken by its centre key: its own bound (PairQueue)
      const double lb = cheap_bound(axes, A.parts[e.a], B.parts[e.b]) - round;
      if (lb >= cut()) {
        settled_lb = std::min(settled_lb, lb);
        continue;
      }
    }
    // Inner pairs too once the query has popped kTightInner pairs: where the
    // closed-form bound of inner pairs is loose (circles about perpendicular
    // axes: two linked rings of a scene popped 4187 node pairs for 92 leaf
    // pairs) the circles' distance prunes them; most queries never get there.
    // The hulls of the two parts' capsule segments, revolved (less the
    // capsules' radii), along the witness's direction: two support values
    // before any split or circle solve. It only retires pairs; as an ordering
    // key it is worse (its value depends on the direction: probe 251 -> 267 M
    // instructions at eps 1e-5), and at push time, on every pair, it costs
    // more than it saves (315 M). Measured at eps 1e-5: node pairs 138 -> 95
    // a query, tight bounds 45 -> 18, 281 -> 251 M instructions. A pair
    // popped again after its tight bound is tried again: the witness and the
    // cut have often moved since (leaf pairs 7.5 -> 5.5 a query; M
    // instructions at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6: 122.3 / 97.4 / 261.5
    // / 181.9 -> 119.5 / 96.6 / 247.9 / 179.1).
    if (have_witness) {  // (its direction)
      const Part &ha = A.parts[e.a], &hb = B.parts[e.b];
      const double lb = witness_hull()(ha.seg_a, ha.seg_b, hb.seg_a, hb.seg_b) - ha.cap_r - hb.cap_r - round;
      if (lb >= cut()) {
        ++st.hull_parts;
        settled_lb = std::min(settled_lb, std::max(e.lb, lb));
        continue;
      }
    }
    // A fit whose arcs are sphere zones or cylinders (axis_zones: the pawn's
    // head, the table's column) is at least as far from the other part as
    // their pieces of axis less their radii (zone_bound): exact up to the
    // fits' eps where the other part is a fit, where the other bounds of a
    // pair with a long exact leaf are loose by a disk's radius.
    if (cut() < kInf) {
      if (const double lb = zone_bound(A.parts[e.a], B.parts[e.b]); lb >= cut()) {
        ++st.zone_parts;
        settled_lb = std::min(settled_lb, lb);
        continue;
      }
    }
    // Fine trees (fine_trees): a pair of tree nodes whose own fits are within
    // 1 % of their disks' radii is bounded by those fits' patches (node_fits_bound).
    if (fine_trees && cut() < kInf) {
      if (const double lb = node_fits_bound(A.parts[e.a], B.parts[e.b]); lb >= cut()) {
        ++st.node_fit_parts;
        settled_lb = std::min(settled_lb, lb);
        continue;
      }
    }
    // A fit beside a part kSpineRatio or more times smaller (an exact line or
    // arc, cut only to a fraction of the profile's extent, exact_fraction in
    // fast/biarc_tree.cpp, beside the small fits of a curve at a small eps;
    // pawn-pawn bench frame 248 at 1e-7: 349 leaf pairs, 1.4 ms, most of them
    // small fits of one pawn's body against the other's neck and collar
    // lines, settled far above the cut): the fit's disk is loose by about
    // half the fit's length, so every part of the other side within that of
    // it would reach the leaf kernels. The fit's own patches against the
    // small part's disk circle (patch_circle_at_least) bound the pair within
    // the part's disk. Measured on the motion probe, M instructions for 600
    // queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6: 92.46 / 78.12 / 172.55 /
    // 125.24 -> 88.43 / 76.49 / 147.48 / 121.49 (ratio 2 or 3 the same, 8:
    // 91.6 at 1e-5; for inner parts only, 91.4 at 1e-5 but 144.1 at 1e-7;
    // the small leaf's own patches' spines instead of its disk: 93.3 / 159.6).
    if (!e.tight && cut() < kInf) {
      const Part &ha = A.parts[e.a], &hb = B.parts[e.b];
      const bool a_big = ha.has_fit && ha.disk_r >= kSpineRatio * hb.disk_r;
      if (a_big || (hb.has_fit && hb.disk_r >= kSpineRatio * ha.disk_r)) {
        ++st.spine_parts;
        const double lb = a_big ? fit_spine_bound(A, ha, B, hb) : fit_spine_bound(B, hb, A, ha);
        if (lb >= cut()) {
          settled_lb = std::min(settled_lb, lb);
          continue;
        }
      }
    }
    if (!e.tight && ((A.parts[e.a].has_fit && B.parts[e.b].has_fit) || st.node_pairs > kTightInner)) {
      ++st.bounds;
      const double lb = std::max(e.lb, pair_bound(A, A.parts[e.a], B, B.parts[e.b]) - round);
      if (lb >= cut()) {
        settled_lb = std::min(settled_lb, lb);
        continue;
      }
      // Back into the queue with the tight bound, unless it would be taken
      // next anyway. (A centre-ordered pair was always put back, its key
      // compared with the -inf that the queue's top reports there: M
      // instructions for the motion probe's 600 queries at eps 1e-5 / 1e-3 /
      // 1e-7 / tol 1e-6 92.81 / 79.05 / 178.33 / 123.36 -> 92.56 / 78.81 /
      // 177.96 / 123.01.)
      const double centre = lb + kKeyDisks * (A.parts[e.a].disk_r + B.parts[e.b].disk_r);
      if (!heap.would_be_next(lb, centre)) {
        heap.push({lb, e.a, e.b, true}, centre);
        continue;
      }
    }
    // A tol below twice the rounding allowances (a bracket that doubles cannot
    // resolve this far from the origin) is relaxed to that once the query has
    // compared 500 leaf pairs: coins or balls 1e6 from the origin at tol 1e-12
    // otherwise refined every pair near the contact until the 25,000 leaf
    // pairs of the work budget ran out (about 0.1 s), and answered a bracket
    // as wide as the gap (4.8e-4 for the balls); now 1-2 ms and a bracket
    // within the allowances. converged still answers to the tol asked for,
    // and the reason below says why it was not met. (Queries that can reach
    // their tol do so long before: the far_from_origin stress families at
    // eps 1e-7, seeds 70-72 and 76, converge as before.)
    if (st.leaf_pairs >= 500 && tol < 2 * (round + up_round)) tol = 2 * (round + up_round), set_cut();
    const bool out_of_kernels = st.patch_pairs >= opt.max_patch_pairs;
    const bool out_of_leaves = st.leaf_pairs >= opt.max_leaf_pairs;
    if (++st.node_pairs > opt.max_node_pairs || out_of_kernels || out_of_leaves) {
      res.reason = out_of_kernels  ? "work budget exhausted: " + std::to_string(st.patch_pairs) + " patch-pair kernels (max_patch_pairs)"
                   : out_of_leaves ? "work budget exhausted: " + std::to_string(st.leaf_pairs) + " leaf pairs (max_leaf_pairs)"
                                   : "work budget exhausted: " + std::to_string(opt.max_node_pairs) + " node pairs (max_node_pairs)";
      settled_lb = std::min(settled_lb, e.lb);
      unresolved = true;
      break;
    }
    const Part& qa = A.parts[e.a];
    const Part& qb = B.parts[e.b];
    if (!(qa.has_fit && qb.has_fit)) {
      // Descend: split the part without a fit, or the bigger one; both
      // tree nodes at once when neither is twice the other's size (the pair
      // of one side's child and the other's node would mostly be popped and
      // split in turn: measured on the motion probe, node pairs a query
      // 81.2 -> 52.8 at eps 1e-5, M instructions for 600 queries at eps 1e-5
      // / 1e-3 / 1e-7 / tol 1e-6 130.9 / 103.6 / 266.3 / 190.4 -> 124.1 /
      // 98.7 / 264.5 / 183.5; with a ratio of 0.2 or 0.9 instead of 0.5:
      // 124.7 and 128.2 at eps 1e-5).
      if (!qa.has_fit && !qb.has_fit && std::min(qa.disk_r, qb.disk_r) >= 0.5 * std::max(qa.disk_r, qb.disk_r)) {
        const std::int32_t ca = A.split(e.a, &st.refined), cb = B.split(e.b, &st.refined);
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) push_pair(ca + i, cb + j);
        continue;
      }
      split_pair(e, !qa.has_fit && (qb.has_fit || qa.disk_r >= qb.disk_r));
      continue;
    }

    // Two fits: their patches, exactly.
    ++st.leaf_pairs;
    double lb_pair = kInf;
    bool all_separated = true;
    const BiarcFit fa = A.fit(qa), fb = B.fit(qb);
    // The cut for the fits' patches: their distance must reach it for the
    // pair's bound, less the fit errors and rounding, to reach cut().
    auto fits_cut = [&] { return cut() + fa.eps + fb.eps + round; };
    const double kernel_cut = fits_cut();
    // End circles of either fit that the pair of the adjacent span's fit with
    // the same other fit already puts at kernel_cut or more (less the end
    // points' rounding gap): their sub-problems are skipped, their bound kept.
    unsigned covered = 0;  // bit 0/1: A's start/end circle, 2/3: B's
    double covered_lb = kInf;
    for (int dir = 0; dir < 2; ++dir) {
      const double la = neighbour_bound(fa, dir, fb, true), lb = neighbour_bound(fb, dir, fa, false);
      if (la >= kernel_cut) covered |= 1u << dir, covered_lb = std::min(covered_lb, la);
      if (lb >= kernel_cut) covered |= 4u << dir, covered_lb = std::min(covered_lb, lb);
    }
    double fit_lb = kInf;  // lower bound on the fits' distance, eps not taken off
    // An arc pair retired by a lower bound `fits` on its patches' distance:
    // the pair's bound (eps and rounding taken off) and the fits' bound.
    auto settle = [&](double fits) {
      lb_pair = std::min(lb_pair, fits - fa.eps - fb.eps - round);
      fit_lb = std::min(fit_lb, fits);
    };
    // An arc pair left open (for refinement, or crossing): its patches' bound
    // `fits` (the quick look's), or 0, as what it keeps.
    auto leave_open = [&](double fits) {
      lb_pair = std::min(lb_pair, std::max(fits - fa.eps - fb.eps - round, 0.0));
      fit_lb = std::min(fit_lb, std::max(fits, 0.0));
    };
    // The arcs of one fit join G1: only the fit's own ends are boundaries
    // (patch_pair_distance's `outer`), so the fit pair is one problem; ends
    // covered by a neighbour's pair are not boundaries to search either.
    auto outer_ends = [](const BiarcFit& f, int i, unsigned cover) {
      int first = -1, last = -1;
      for (int k = 0; k < f.arcs; ++k)
        if (f.arc[k].length > 0) last = k, first = first < 0 ? k : first;
      return (i == first && !(cover & 1u) ? 1u : 0u) | (i == last && !(cover & 2u) ? 2u : 0u);
    };
    // B's patches once (the loop below pairs each with both of A's).
    Patch QB[2];
    for (int j = 0; j < fb.arcs; ++j)
      if (fb.arc[j].length > 0) QB[j] = make_patch(fb.arc[j], pb.R, pb.t);
    for (int i = 0; i < fa.arcs; ++i) {
      if (fa.arc[i].length <= 0) continue;
      const Patch P = make_patch(fa.arc[i], pa.R, pa.t);
      const unsigned outer_a = outer_ends(fa, i, covered);
      for (int j = 0; j < fb.arcs; ++j) {
        if (fb.arc[j].length <= 0) continue;
        const Patch& Q = QB[j];
        const unsigned outer = outer_a | outer_ends(fb, j, covered >> 2) << 2;
        // The hulls of the revolved patches first, along the witness's
        // direction: two exact support values, where the bounding tori of a
        // short arc or segment are fat, the quick look's circle solves bound
        // only those tori, the spine bound ignores the arc's window, and the
        // local proof needs ~20 boxes for pairs hundreds of tol clear of the
        // cut. Measured on the motion probe at eps 1e-5: 15 arc pairs a query
        // end here; as chord cones less the sagittas (23 a query then, the
        // closed forms first) they took 371 -> 281 M instructions, the exact
        // supports 202 -> 187 M, and first, before the closed forms, 185 M.
        // (Supports refined once or more from the witness direction settle
        // no more pairs.)
        if (const double hull = witness_hull().patches(P, Q);
            hull - fa.eps - fb.eps - round >= cut()) {
          ++st.hull_pairs;
          settle(hull);
          continue;
        }
        // Closed-form bounds next (the bounding tori, and the tubes of two
        // toroidal patches): an arc pair they retire needs no iteration.
        {
          Vec2 ca, cb;
          double ra, rb;
          patch_disk(P, &ca, &ra);
          patch_disk(Q, &cb, &rb);
          // (The patches' circles are about their solids' axes: `axes` applies.)
          auto bound = [&](const Circle3& a, const Circle3& b) { return axes(a.center, a.radius, b.center, b.radius); };
          double lb = bound(patch_disk_circle(P, ca), patch_disk_circle(Q, cb)) - ra - rb;
          if (!P.straight && !Q.straight)
            lb = std::max(lb, bound(patch_major_circle(P), patch_major_circle(Q)) - P.rho - Q.rho);
          if (lb - fa.eps - fb.eps - round >= cut()) {
            ++st.quick_pairs;
            settle(lb);
            continue;
          }
        }
        // The cheap look next (its exact case also offers a witness). Told what settles the
        // pair and where the witness is, it skips the circle solves that
        // provably cannot settle it (two thirds of them at eps 1e-5).
        const QuickGoal goal{fits_cut(), res.point_a};
        const PatchQuick quick = patch_pair_quick(P, Q, &goal);
        const double disk = quick.lower - fa.eps - fb.eps - round;
        if (disk >= cut()) {
          ++st.quick_pairs;
          settle(quick.lower);
          continue;
        }
        if (quick.exact) {
          ++st.quick_pairs;
          if (quick.lower - fa.eps - fb.eps < ub) offer(A.true_point(fa, quick.x), B.true_point(fb, quick.y));
          settle(quick.lower);
          continue;
        }
        // The spine bounds next: each patch, within its own window, against
        // the other's major circle (patch_spine_at_least), a one-dimensional
        // proof of about a dozen closed-form evaluations. Neighbours of the
        // closest pair, whose full tori meet near it, mostly end here.
        if (double spine = 0.0; spines_at_least(P, Q, kernel_cut, &spine)) {
          ++st.spine_pairs;
          settle(std::max(quick.lower, spine));
          continue;
        }
        // The local proof next: most pairs that reach it are well above the
        // cut, only not by the closed-form bounds. A query where it mostly
        // fails (a tolerance near the rounding of far-off coordinates, where
        // no box clears) stops paying for it.
        // Patches whose tori meet (disk <= 0) get a descent from the witness
        // first. Its pair, offered, may lower the cut; above the cut, the
        // hull along the pair's own direction or the spine bounds mostly
        // settle the pair, where the local proof needs boxes down to where the
        // tori cross and often ran out of them (128 boxes, a third of an
        // enumeration, then a descent all the same). A pair below the cut
        // holds a point pair the proof cannot clear: refined, or, within the
        // fits' errors, on to the overlap probes. Measured on the motion
        // probe's 30000 queries (2000 frames a pair), least of 3 runs, p90 /
        // mean us: eps 1e-5 31.0 / 16.8 -> 29.3 / 16.1, 1e-7 77.6 / 37.1 ->
        // 70.2 / 34.5, tol 1e-6 50.0 / 25.8 -> 41.5 / 21.9, 1e-3 26.6 / 13.2
        // -> 26.9 / 13.6; the proven overlaps' p99 at 1e-5 83.5 -> 76.0.
        // A pair the arc pair's descent reached (x on P, y on Q, d apart):
        // offered; then, at the cut it leaves (*cut2), the hulls along the
        // pair's own closest direction, from Q's point y towards P's x
        // (exact for cones side by side), and the spine bounds. (The hull was
        // once taken reversed, y - x, whenever Q was the boxed patch, where
        // it is at most 0 and retires nothing; the right way round the motion
        // probe's 600 queries at eps 1e-5 took 156.0 -> 143.1 M instructions,
        // 1e-7 354.4 -> 286.8, 1e-3 116.0 -> 113.8, tol 1e-6 208.6 -> 204.3.)
        // proven: *bound (>= *cut2), from the spine bounds when *by_spine;
        // above: the pair is above *cut2, unproven so far; open: the patches
        // hold a pair at or below *cut2 but apart by more than the fits'
        // errors: no bound on their distance, less those errors, can retire
        // the leaf pair (its fit errors exceed what the bracket has left), so
        // it will be refined (most pairs of a query whose tol is below its
        // fits' errors end here); within: the pair is within the fits' errors
        // (the patches may cross), or the cut is at most 0.
        // overlap: the steps across from the pair (probe_across, within
        // kAcrossReach) proved that the solids overlap. (A descent on
        // patches that cross ends near the crossing when the surfaces meet
        // at a small angle, or at a patch's end when the crossing is across
        // it; the local proof's boxes cannot pass there, and the probes after
        // it start elsewhere. Measured with these steps and the first
        // witness's, against neither, on the motion probe's 30000 queries,
        // least of 3 runs: the 1935 proven overlaps' median / p90 / p99 at
        // eps 1e-5 11.6 / 29.7 / 72.9 -> 8.6 / 21.2 / 64.0 us, at 1e-7 25.9 /
        // 82.3 / 296 -> 10.8 / 44.5 / 264; all queries' median / p90 / mean
        // at 1e-5 9.6 / 29.0 / 16.0 -> 9.6 / 28.7 / 16.0, at 1e-7 13.2 / 70.6
        // / 34.7 -> 12.1 / 67.4 / 33.8. M instructions for the probe's 600
        // queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6 90.4 / 76.8 / 177.0 /
        // 120.1 -> 92.8 / 79.1 / 178.4 / 123.4 (a step's point-in-solid test
        // costs about 2000), for its 200 overlap frames 25.3 / 18.4 / 66.6 /
        // 36.9 -> 19.7 / 16.7 / 41.9 / 24.6.)
        enum class Descended { proven, above, open, within, overlap };
        auto descended = [&](double d, const Vec3& x, const Vec3& y, double* cut2, double* bound, bool* by_spine) {
          if (d - fa.eps - fb.eps < ub) offer(A.true_point(fa, x), B.true_point(fb, y));
          if (probe_across(fa, x, fb, y, kAcrossReach)) return Descended::overlap;
          *cut2 = fits_cut();
          if (cut() > 0 && d > *cut2) {
            *by_spine = false;
            if (const double hull = patch_hull_bound(P, Q, Vec3(x - y), 0); hull >= *cut2) {
              *bound = hull;
              return Descended::proven;
            }
            *by_spine = true;
            return spines_at_least(P, Q, *cut2, bound) ? Descended::proven : Descended::above;
          }
          return cut() > 0 && d > fa.eps + fb.eps + round ? Descended::open : Descended::within;
        };
        bool may_cross = false;  // skip the local proof
        if (disk <= 0 && cut() > 0) {
          Vec3 xs, ys;
          const double d = patch_pair_descent(P, Q, res.point_a, 1e-3 * opt.tol, &xs, &ys);
          if (xs.allFinite() && ys.allFinite()) {
            double cut2, bound = 0.0;
            bool by_spine = false;
            switch (descended(d, xs, ys, &cut2, &bound, &by_spine)) {
              case Descended::proven:
                ++(by_spine ? st.spine_pairs : st.hull_pairs);
                settle(std::max(quick.lower, bound));
                continue;
              case Descended::open:
                leave_open(quick.lower);
                continue;
              case Descended::within:
                may_cross = true;
                break;
              case Descended::above:
                break;
              case Descended::overlap:
                return proven_overlap(shared);
            }
          }
        }
        if (!may_cross && (local_failed < 64 || 3 * st.local_pairs >= local_failed)) {
          double local = 0.0;
          int evals = 0;
          // Which patch gets the boxes. Patches apart at the fits' precision
          // (disk > 0): the one of the smaller parameter area (profile length
          // times largest radius). Both are whole rings, and the proof first
          // halves its boxes down to where the other patch is: a wide cone
          // boxed against a small torus pays a dozen levels before any box
          // can clear. When the boxes run out without meeting a point closer
          // than the cut, the other patch is boxed before the enumeration.
          // Patches that may cross keep the cone of a cone-torus pair (the
          // torus's closed form then bounds its boxes), else the smaller
          // extent: their proofs mostly fail, and the point a failure hands
          // to the descent below decides whether the overlap probes that
          // follow succeed without the enumeration (by area, the motion
          // probe's planned-overlap frames at eps 1e-5 took p99 165 -> 199 us).
          // Measured with the second descent below, M instructions for the
          // probe's 600 queries against that rule for all pairs: eps 1e-5
          // 141.9 -> 140.4, 1e-7 287.0 -> 279.7, 1e-3 112.6 -> 112.4, tol 1e-6
          // 202.5 -> 200.0 (all pairs by area: 138.5, 274.8, 112.4, 204.7).
          const Patch* boxed = &P;
          const Patch* other = &Q;
          Vec3 cp, cq;
          if (disk > 0 ? patch_profile_length(Q) * patch_max_radius(Q) < patch_profile_length(P) * patch_max_radius(P)
                       : P.straight != Q.straight ? Q.straight : patch_extent(Q, &cq) < patch_extent(P, &cp))
            std::swap(boxed, other);
          Vec2 closer(kInf, 0.0), seen(kInf, 0.0);
          bool proven = patches_at_least(*boxed, *other, kernel_cut, round, kLocalBudget, &local, &evals, &closer, &seen);
          st.local_boxes += evals;
          if (!proven && !std::isfinite(closer.x()) && disk > 0) {
            std::swap(boxed, other);
            proven = patches_at_least(*boxed, *other, kernel_cut, round, kLocalBudget, &local, &evals, &closer, &seen);
            st.local_boxes += evals;
          }
          // A proof that ran out of boxes without meeting a point closer
          // than the cut still saw where the pair comes closest: the descent
          // below starts there, and its pair, offered, may lower the cut
          // enough for the retry to pass (where the pair holds the contact
          // and the upper bound is still the first witness's, the enumeration
          // followed). Measured on the motion probe, M instructions for 600
          // queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6: 107.4 / 89.8 /
          // 224.6 / 168.0 -> 107.2 / 89.8 / 218.1 / 153.1; on 3000 queries
          // at tol 1e-6 the p90 88.8 -> 75.7 us and the planned overlaps'
          // p99 273 -> 169.
          // (Only for patches apart at the fits' precision: no gain.)
          if (!proven && !std::isfinite(closer.x())) closer = seen;
          const Patch& S = *boxed;
          const Patch& O = *other;
          const bool s_is_p = boxed == &P;
          bool by_spine = false;
          // A point of the boxed patch closer than the cut (the pair holds a
          // better candidate): descend from it to the pair's local minimum and
          // offer that pair; with the upper bound lowered, the proof may hold
          // at the new cut without the enumeration. (Only while the bracket is
          // away from 0: crossing patches go on to the overlap probes.) A
          // second try that meets a point closer than its cut descends once
          // more from there: the first descent may end in another local
          // minimum of the pair (from the point a depth-first failure meets
          // first), and the enumeration would only find the pair's true one.
          // (Measured: 600 probe queries at eps 1e-5 143.1 -> 141.9 M
          // instructions, 1e-7 286.8 -> 287.0, tol 1e-6 204.3 -> 202.5; over
          // 3000 queries the mean time 37.1 -> 36.5 us, p90 72.5 -> 71.2.)
          // The descent from there tries each parameter alone where the
          // step in both finds no decrease (each_alone): a bottle's rim over
          // a table, bench frame 21023, stopped 5e-5 above the pair's minimum
          // where Q's nearest point moves from the bottle's side to its rim,
          // and the retry then paid 278 boxes; with it, 121 boxes instead of
          // 400. On the bench's 30000 frames at eps 1e-5, least of 3 runs,
          // three runs each: proven overlaps' p99 47.9 / 48.1 / 47.0 -> 46.6 /
          // 46.3 / 45.7 us, median 9.6 us as before; M instructions for the
          // probe's 600 queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6 +0.2-0.3 %
          // (93.34 / 79.89 / 175.74 / 125.70 -> 93.57 / 80.07 / 176.17 /
          // 126.09), for the bench's 80 slowest proven overlaps -2.4 %. (For
          // every descent of the query, the first witness's too: +1 %.)
          double left_open_at = kInf;  // the descended distance of a pair left to refinement
          for (int descents = 0; descents < 2 && !proven && std::isfinite(closer.x()); ++descents) {
            Vec3 xs, xo;
            const double d = patch_pair_descent(S, O, closer, 1e-3 * opt.tol, &xs, &xo, true);
            closer = Vec2(kInf, 0.0);
            const Vec3& x = s_is_p ? xs : xo;
            const Vec3& y = s_is_p ? xo : xs;
            // The closed forms at the new cut first: the pair's own minimum
            // is near it, where the boxes cost the most; then the boxes again.
            // A pair left open would only be confirmed by the enumeration;
            // patches that may cross (within) still go on to it for its
            // overlap probes.
            double cut2;
            const Descended at = descended(d, x, y, &cut2, &local, &by_spine);
            if (at == Descended::overlap) return proven_overlap(shared);
            proven = at == Descended::proven;
            if (at == Descended::above) {
              by_spine = false;
              proven = patches_at_least(S, O, cut2, round, kRetryBudget, &local, &evals, &closer);
              st.local_boxes += evals;
            } else if (at == Descended::open) {
              left_open_at = d;
              break;
            }
          }
          if (left_open_at < kInf) {
            leave_open(quick.lower);
            continue;
          }
          if (proven) {
            ++(by_spine ? st.spine_pairs : st.local_pairs);
            settle(std::max(quick.lower, local));
            continue;
          }
          ++local_failed;
        }
        // Fits that may cross (their bound less the fit errors reaches 0),
        // once a query, before the enumeration: the best witness pair so far
        // may already prove an overlap.
        if (!tried_witness && disk <= 0 && ub < kInf && witness_probe(fa, fb)) return proven_overlap(shared);
        // Then the patches' deep points (deep_probe): an enumeration of
        // crossing patches costs up to a million instructions (their binormal
        // lines crowd near the crossing), the probe a few per cent of it.
        if (disk <= 0 && ub < kInf && deep_probe(P, Q, fa, fb)) return proven_overlap(shared);
        ++st.patch_pairs;
        // Parts that cannot beat the current bracket are skipped (their
        // bounds are kept in lower_skipped).
        // (The enumeration takes the full look's bound.)
        const PatchPairResult r =
            patch_pair_distance(P, Q, kernel_cut, quick.complete ? quick.lower : patch_pair_quick(P, Q).lower, outer);
        // The true points are within the fits' eps of the patch points: map
        // them (a Newton solve on the input curve) only when they may improve.
        if (r.found && r.upper - fa.eps - fb.eps < ub) offer(A.true_point(fa, r.x), B.true_point(fb, r.y));
        if (r.separated) {
          settle(std::max(quick.lower, std::min({r.found ? r.upper : kInf, r.lower_skipped, covered_lb})));
          continue;
        }
        all_separated = false;
        leave_open(quick.lower);
        // The patches may cross: try to prove that the solids overlap, from
        // the patch points most inside the other solid, then the candidate
        // pair's points and, along their meridians, the input curve beyond
        // the fits' spans (a crossing at a sharp edge).
        if (in_b(A.true_point(fa, r.a_low)) || in_b(A.true_point(fa, r.a_high)) ||
            in_a(B.true_point(fb, r.b_low)) || in_a(B.true_point(fb, r.b_high)) ||
            (r.found && (in_b(A.true_point(fa, r.x)) || in_a(B.true_point(fb, r.y)) ||
                         A.along_meridian(fa, r.x, 3, in_b) || B.along_meridian(fb, r.y, 3, in_a))))
          return proven_overlap(shared);
        // No shared point proven: a point where the fits cross still gives a
        // witness pair within the fits' errors, so touching solids need not
        // wait for the refinement to find one.
        Vec3 xc;
        if (ub > fa.eps + fb.eps && patch_crossing_point(P, Q, r.a_low, r.a_high, &xc))
          offer(A.true_point(fa, xc), B.true_point(fb, xc));
      }
    }
    remember(e.a, e.b, fit_lb);
    if (lb_pair >= cut()) {
      settled_lb = std::min(settled_lb, lb_pair);
      continue;
    }
    // Not resolved: refine the part that limits the bound.
    const bool a_ok = A.can_split(qa, opt.max_refine), b_ok = B.can_split(qb, opt.max_refine);
    bool split_a;
    if (all_separated) split_a = fa.eps >= fb.eps;      // the fit errors are what is left
    else split_a = qa.disk_r >= qb.disk_r;              // patches too big to separate
    if (split_a && !a_ok) split_a = false;
    if (!split_a && !b_ok) split_a = a_ok;
    if (!a_ok && !b_ok) {
      settled_lb = std::min(settled_lb, lb_pair);
      unresolved = true;
      if (res.reason.empty())
        res.reason = all_separated ? "refinement limit reached" : "patches could not be separated (degenerate contact)";
      continue;
    }
    split_pair(e, split_a);
  }

  st.nodes_built = A.tree.nodes_built() + B.tree.nodes_built();
  double lb = settled_lb;
  lb = std::min(lb, heap.least());
  if (containment_unknown) {
    lb = 0.0;
    if (res.reason.empty())
      res.reason = "containment undecided: a surface point of one solid lies within rounding of the other's boundary";
  }
  lb = std::max(lb, 0.0);
  // A bracket down to 0 met by a witness pair within tol of touching, with
  // no kernel run on crossing fits, may hide an overlap: the witness's probe
  // and the deep points, from the fits nearest its points.
  if (lb <= 0 && !tried_witness && ub < kInf && !unresolved) {
    const BiarcFit fa = A.nearest_fit(res.point_a), fb = B.nearest_fit(res.point_b);
    if (witness_probe(fa, fb) ||
        deep_probe(A.nearest_patch(fa, res.point_a), B.nearest_patch(fb, res.point_b), fa, fb))
      return proven_overlap(shared);
  }
  // A stop before any candidate (a small budget) still owes a finite
  // bracket: any two genuine surface points bound the distance from above.
  if (!(ub < kInf)) offer(A.surface_point(0), B.surface_point(0));
  if (!(ub < kInf)) {
    res.reason = "no candidate pair found";
    res.lower = lb;
    res.upper = kInf;
    res.distance = kInf;
    return res;
  }
  lb = std::min(lb, ub);
  res.lower = lb;
  res.upper = ub;
  res.distance = 0.5 * (lb + ub);
  res.converged = !unresolved && (ub - lb <= opt.tol || ub - lb <= rel * lb);
  if (threshold) res.decided = ub <= opt.threshold || lb > opt.threshold;
  // A bracket within a few rounding allowances of the coordinates: tol is
  // below what doubles resolve this far from the origin; say so rather than
  // "refinement limit reached". (Stress, far_from_origin at eps 1e-7: a cone
  // 1e6 from the origin, bracket width 7e-8, allowances 6.2e-8.)
  if (!res.converged && !res.decided && ub - lb > opt.tol && ub - lb <= 4 * (round + up_round)) {
    char why[200];
    std::snprintf(why, sizeof why,
                  "bracket at the rounding of coordinates up to %.3g from the origin (allowances %.2g): tol is below "
                  "what doubles resolve there",
                  coord, round + up_round);
    res.reason = why;
  }
  // A tree with unproven leaves (the spiral split could not prove its
  // hypotheses: fast/spiral_split.h) bounds nothing there; that, not what it
  // led to (an undecided containment test, say), is why.
  if (!res.converged && !res.decided && !(std::isfinite(pa.tree->max_error) && std::isfinite(pb.tree->max_error)))
    res.reason = std::string("the fit of solid ") + (std::isfinite(pa.tree->max_error) ? "b" : "a") +
                 " is not proven on some leaves (the spiral hypotheses could not be proven there): no finite bound "
                 "from them";
  if (!res.converged && res.reason.empty())
    res.reason = res.decided ? "threshold decided before the bracket met tol" : "bracket wider than tol";
  return res;
}

}  // namespace

SolidDistanceResult solid_distance(const PosedSolid& a, const PosedSolid& b, const DistanceOptions& options) {
  return query(a, b, options, nullptr);
}

SolidDistanceResult solid_distance(const PosedSolid& a, const PosedSolid& b, const DistanceOptions& options,
                                   const WarmStart& warm) {
  return query(a, b, options, &warm);
}

WarmStart warm_start_of(const SolidDistanceResult& r, const PosedSolid& a, const PosedSolid& b) {
  WarmStart w;
  w.valid = std::isfinite(r.upper) && r.point_a.allFinite() && r.point_b.allFinite();
  w.overlap = r.overlap;
  w.a_local = a.R.transpose() * (r.point_a - a.t);
  w.b_local = b.R.transpose() * (r.point_b - b.t);
  return w;
}

}  // namespace revdist
