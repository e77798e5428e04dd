// Certified two-sided Hausdorff bound between a curve part and its arcs (paper
// section 4.1; SPEC section 6: "the engine proves each fit is within eps").
//
// Notation. C = piece[u0, u1], the exact input curve part (fit_audit_curve.cpp
// encloses it as rational Bezier segments with interval coefficients). A_i, the
// arcs: start S, tangent T (stored, |T| ~ 1), N = perp(T), curvature k, length
// L; end E = S + sin(kL)/k T + 2 sin^2(kL/2)/k N and end tangent
// T_E = cos(kL) T + sin(kL) N, all enclosed with MPFI (the arc's circle has
// centre c = S + N/k, radius R = |T|/|k|; a straight arc has k = 0).
//   rad_i(X)  = | |X - c| - R | = |k |X-S|^2 - 2 (X-S).N| / (|k(X-S) - N| + |N|),
//               the distance to the whole circle (line when k = 0), in a form
//               that has no cancellation as k -> 0;
//   h0_i(X)   = T.(X - S),  h1_i(X) = T_E.(E - X);
//   W_i       = {h0 >= 0, h1 >= 0}, the closed sector of the arc (a slab when
//               k = 0): its boundary lines are the normals at S and E, which
//               meet at c. We require |k| L < pi, so W_i is convex.
// Facts used (elementary; each is a line of plane geometry):
//   F1. X in W_i  =>  dist(X, A_i) = rad_i(X); always dist(X, A_i) >= rad_i(X).
//   F2. X outside W_i  =>  dist(X, A_i) = min(|X - S|, |X - E|).
//   F3. If (X - c).(S - c) >= 0 (angle at c at most 90 degrees), then
//       |X - S| <= rad_i(X) + sqrt(2) (R/|X - c|) |h0_i(X)| / |T|
//       (the radial projection Q of X is a chord 2R sin(a/2) <= sqrt(2) R sin a
//       from S, and |X - c| sin a is X's distance to the normal line at S). Same
//       at E with h1. The test is |T|^2 - k (X - S).N >= 0, at E with N_E.
//
// Theorem (the bound returned). Cover [u0, u1] by sub-intervals U (nodes); for
// each, with C(U) in its control-point box:
//   (a) forward: sup over C(U) of dist(X, A) <= min over candidates of
//       * per arc: max(sup rad_i if C(U) may meet W_i, bound for the part
//         outside W_i by F2 and F3);
//       * per consecutive pair i, j = i + 1 with h0_i >= 0 and h1_j >= 0 on C(U):
//         max(sup rad_i, sup rad_j, sliver) — a point is in W_i, or in W_j, or in
//         the sliver h1_i < 0, h0_j < 0 between the two nearly equal normal lines
//         at the joint, where |h0_j| <= |h0_j + h1_i| (an affine function whose
//         gradient T_j - T_E,i is rounding noise) and F3 bounds |X - S_j|;
//   (b) reverse, per arc i with k != 0: C(U) avoids the closed opposite cone
//       {h0_i <= 0, h1_i <= 0} (which contains c): all Bernstein coefficients of
//       h0_i (or of h1_i) positive. On the plane minus that cone the polar angle
//       about c is continuous, with the arc's angles between those of the "before"
//       and "after" regions. So along the continuous curve the angle passes every
//       ray of A_i between the rays of C(u0) and C(u1) (intermediate values);
//       where C meets the ray through an arc point Q, |Q - C(u)| = rad_i(C(u)),
//       bounded by M_i = max of sup rad_i over nodes that may meet W_i. For k = 0
//       the same with the coordinate along T instead of the angle.
//   (c) end points: if C(u0) may lie inside W_i (h0_i(C(u0)) > 0 possible; the
//       arcs start at a double rounding of C(u0), not at C(u0)), the arc points
//       before its ray are within |S - C(u0)| + 2 rad_i(C(u0)) of C(u0) (chord to
//       the radial projection, then triangle inequality); C(u0) beyond the end of
//       A_i is refused. Same at C(u1) with E. An arc of length 0 is a point: the
//       reverse bound is its distance to the nearest evaluated curve point.
// Then H(C, A) <= max(max_U forward(U), max_i M_i, end terms); and for a curve
// point X, H >= dist(X, A) >= min_i (rad_i(X) or F2), the lower bound reported.
// If the tangent is read normalised instead, each arc moves by <= ||T| - 1| L
// (scaling about S), which is added. All ranges over U come from Bernstein
// coefficients (convex hull; positive weights) of the numerators in homogeneous
// form: rad_i via k|P - wS|^2 - 2w(P - wS).N over w^2 (degree 2p), h0_i, h1_i
// (degree p); subdividing at t = 1/2 makes them converge quadratically, so the
// bound closes on the true error without the wrapping of naive interval boxes.
// Branch and bound: the node of worst bound is halved first, until the bound is
// <= max(target, 1.05 x lower bound), the depth or node budget is reached.
#include "exact/fit_audit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>
#include <utility>

#include "core/curve_eval.h"
#include "exact/fit_audit_internal.h"

namespace revdist {

namespace {

using namespace fit_audit_detail;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSqrt2Up = 1.4142135623730951;  // the double above sqrt(2)
// Node budget per audit: a leaf needs ~10-60 nodes at eps = 1e-5 (halving the
// neighbourhoods of the joint and the ends); the budget only stops runaway cases
// (a wrong fit never meets its target), whose bound is then reported as is.
constexpr int kMaxNodes = 3000;
constexpr int kMaxDepth = 52;  // halvings of one segment's parameter interval

// a + sqrt(2) b c / d, rounded up (inputs >= 0; d > 0).
double up_f3(double a, double b, double c, double d) {
  if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c) || !(d > 0)) return kInf;
  return (Ia(a) + Ia(kSqrt2Up) * Ia(b) * Ia(c) / Ia(d)).hi();
}

double max_abs_hi(const Poly& c) {
  double m = 0.0;
  for (const Ia& v : c) m = std::max(m, abs(v).hi());
  return m;
}

struct ArcData {
  bool point = false;     // length 0: the set is the point S
  bool straight = false;  // k = 0
  double length = 0.0;
  Ia k, tnorm, tnorm2;
  P2 S, T, N, E, TE, NE;
};

bool make_arc(const Arc2& a, ArcData& d, std::string* reason) {
  const double f[6] = {a.start.x(), a.start.y(), a.tangent.x(), a.tangent.y(), a.curvature, a.length};
  for (double v : f) {
    if (!std::isfinite(v)) {
      *reason = "arc with a non-finite field";
      return false;
    }
  }
  if (!(a.length >= 0) || a.tangent.squaredNorm() == 0.0) {
    *reason = "arc with negative length or zero tangent";
    return false;
  }
  d.point = a.length == 0.0;
  d.straight = a.curvature == 0.0;
  d.length = a.length;
  d.k = Ia(a.curvature);
  d.S = {a.start.x(), a.start.y()};
  d.T = {a.tangent.x(), a.tangent.y()};
  d.N = perp(d.T);
  d.tnorm2 = dot(d.T, d.T);
  d.tnorm = sqrt_nonneg(d.tnorm2);
  const Ia len(a.length);
  if (d.straight) {
    d.E = d.S + len * d.T;
    d.TE = d.T;
  } else {
    const Ia kl = d.k * len;
    if (!(abs(kl).hi() < pi().lo())) {
      *reason = "arc turns by half a turn or more";
      return false;
    }
    const Ia s = sin(kl), h = sin(kl / Ia(2.0));
    d.E = d.S + (s / d.k) * d.T + (Ia(2.0) * h * h / d.k) * d.N;
    d.TE = cos(kl) * d.T + s * d.N;
  }
  d.NE = perp(d.TE);
  return true;
}

// rad_i at a point enclosure X.
Ia radial(const ArcData& a, const P2& X) {
  const P2 D = X - a.S;
  const Ia g = a.k * dot(D, D) - Ia(2.0) * dot(D, a.N);
  const Ia den = norm(a.k * D - a.N) + a.tnorm;
  return abs(g) / den;
}

// Proven lower bound of dist(X, A_i) (facts F1, F2).
double point_lower(const ArcData& a, const P2& X) {
  if (a.point) return std::max(0.0, (norm(X - a.S) - Ia(a.length)).lo());
  const Ia h0 = dot(a.T, X - a.S), h1 = dot(a.TE, a.E - X);
  if (h0.neg() || h1.neg()) return std::min(norm(X - a.S).lo(), norm(X - a.E).lo());
  return radial(a, X).lo();
}

struct Node {
  int seg = 0, depth = 0;
  std::vector<Poly> polys;  // x, y, w (homogeneous), then per arc: G, H0, H1
  double score = 0.0;       // max(forward, reverse terms); +inf when undecided
  double forward = 0.0;
  std::vector<double> rev;  // per arc: sup rad_i if C(U) may meet W_i, else 0
  bool cone_ok = true;
  bool weights_ok = true;
};

class Auditor {
 public:
  Auditor(std::vector<ArcData> arcs, double target) : arcs_(std::move(arcs)), target_(target) {}

  FitAudit run(const std::vector<HomSeg>& segs);

 private:
  std::vector<ArcData> arcs_;
  double target_;
  double lower_ = 0.0;
  std::vector<double> point_cover_;  // per point-arc: min over curve points of |X - S|, rounded up

  Node root(const HomSeg& s, int index) const;
  void eval(Node& nd) const;
  void note_point(const Ia& x, const Ia& y, const Ia& w);
  bool end_terms(const P2& X0, const P2& X1, double* term, std::string* reason) const;
};

Node Auditor::root(const HomSeg& s, int index) const {
  Node nd;
  nd.seg = index;
  nd.polys = {s.x, s.y, s.w};
  for (const ArcData& a : arcs_) {
    if (a.point) {
      nd.polys.emplace_back();
      nd.polys.emplace_back();
      nd.polys.emplace_back();
      continue;
    }
    const std::size_t n = s.x.size();
    Poly qx(n), qy(n), qn(n), h0(n), h1(n);
    for (std::size_t j = 0; j < n; ++j) {
      qx[j] = s.x[j] - s.w[j] * a.S.x;
      qy[j] = s.y[j] - s.w[j] * a.S.y;
      qn[j] = qx[j] * a.N.x + qy[j] * a.N.y;
      h0[j] = a.T.x * qx[j] + a.T.y * qy[j];
      h1[j] = a.TE.x * (s.w[j] * a.E.x - s.x[j]) + a.TE.y * (s.w[j] * a.E.y - s.y[j]);
    }
    const Poly qq = [&] {
      Poly p = bernstein_product(qx, qx);
      const Poly p2 = bernstein_product(qy, qy);
      for (std::size_t m = 0; m < p.size(); ++m) p[m] = p[m] + p2[m];
      return p;
    }();
    const Poly wqn = bernstein_product(s.w, qn);
    Poly g(qq.size());
    for (std::size_t m = 0; m < g.size(); ++m) g[m] = a.k * qq[m] - Ia(2.0) * wqn[m];
    nd.polys.push_back(std::move(g));
    nd.polys.push_back(std::move(h0));
    nd.polys.push_back(std::move(h1));
  }
  eval(nd);
  return nd;
}

void Auditor::eval(Node& nd) const {
  const Poly& x = nd.polys[0];
  const Poly& y = nd.polys[1];
  const Poly& w = nd.polys[2];
  const std::size_t n_arcs = arcs_.size();
  nd.rev.assign(n_arcs, 0.0);
  nd.cone_ok = true;
  double wmin = kInf;
  for (const Ia& v : w) wmin = std::min(wmin, v.lo());
  nd.weights_ok = wmin > 0;
  if (!nd.weights_ok) {
    nd.forward = nd.score = kInf;
    return;
  }
  // Control-point box: the segment lies in the convex hull of its control points.
  P2 box{x[0] / w[0], y[0] / w[0]};
  for (std::size_t j = 1; j < x.size(); ++j) {
    box.x = hull(box.x, x[j] / w[j]);
    box.y = hull(box.y, y[j] / w[j]);
  }
  const double wmin2 = sqr(Ia(wmin)).lo();

  struct PerArc {
    double rad = kInf, rrho = kInf, tlo = 0.0;
    bool h0_nonneg = false, h1_nonneg = false, qs_ok = false;
  };
  std::vector<PerArc> pa(n_arcs);
  double forward = kInf;
  for (std::size_t i = 0; i < n_arcs; ++i) {
    const ArcData& a = arcs_[i];
    if (a.point) {
      forward = std::min(forward, (norm(box - a.S) + Ia(a.length)).hi());
      continue;
    }
    const Poly& G = nd.polys[3 + 3 * i];
    const Poly& H0 = nd.polys[4 + 3 * i];
    const Poly& H1 = nd.polys[5 + 3 * i];
    PerArc& q = pa[i];
    const P2 D = box - a.S;
    const Ia r1 = norm(a.k * D - a.N);  // |k| |X - c|
    const double den_lo = (r1 + a.tnorm).lo();
    q.rad = den_lo > 0 ? (Ia(max_abs_hi(G)) / (Ia(wmin2) * Ia(den_lo))).hi() : kInf;
    q.rrho = r1.lo() > 0 ? (a.tnorm / Ia(r1.lo())).hi() : kInf;  // R / |X - c|
    q.tlo = a.tnorm.lo();
    bool h0_pos = true, h1_pos = true, h0_neg = true, h1_neg = true;
    q.h0_nonneg = q.h1_nonneg = true;
    double neg0 = 0.0, neg1 = 0.0;  // sup of max(0, -H) over the coefficients
    for (const Ia& v : H0) {
      h0_pos &= v.pos();
      h0_neg &= v.neg();
      q.h0_nonneg &= v.nonneg();
      neg0 = std::max(neg0, (-v).hi());
    }
    for (const Ia& v : H1) {
      h1_pos &= v.pos();
      h1_neg &= v.neg();
      q.h1_nonneg &= v.nonneg();
      neg1 = std::max(neg1, (-v).hi());
    }
    neg0 = (Ia(neg0) / Ia(wmin)).hi();
    neg1 = (Ia(neg1) / Ia(wmin)).hi();
    if (!a.straight && !h0_pos && !h1_pos) nd.cone_ok = false;
    const bool maybe_in = !(h0_neg || h1_neg);
    const bool surely_in = q.h0_nonneg && q.h1_nonneg;
    q.qs_ok = (a.tnorm2 - a.k * dot(D, a.N)).nonneg();
    const bool qe_ok = (a.tnorm2 - a.k * dot(box - a.E, a.NE)).nonneg();
    double outside = 0.0;
    if (!surely_in) {
      const double before = q.h0_nonneg ? 0.0 : (q.qs_ok ? up_f3(q.rad, q.rrho, neg0, q.tlo) : kInf);
      const double after = q.h1_nonneg ? 0.0 : (qe_ok ? up_f3(q.rad, q.rrho, neg1, q.tlo) : kInf);
      outside = std::min({norm(box - a.S).hi(), norm(box - a.E).hi(), std::max(before, after)});
    }
    forward = std::min(forward, std::max(maybe_in ? q.rad : 0.0, outside));
    nd.rev[i] = maybe_in ? q.rad : 0.0;
  }
  // The joint of consecutive arcs i, j: points in W_i, in W_j, or in the sliver.
  for (std::size_t i = 0; i + 1 < n_arcs; ++i) {
    const std::size_t j = i + 1;
    const ArcData& ai = arcs_[i];
    const ArcData& aj = arcs_[j];
    if (ai.point || aj.point || !pa[i].h0_nonneg || !pa[j].h1_nonneg) continue;
    double sliver = 0.0;
    if (!pa[i].h1_nonneg && !pa[j].h0_nonneg) {
      if (!pa[j].qs_ok) continue;
      const Ia aff = dot(aj.T - ai.TE, box - aj.S) + dot(ai.TE, ai.E - aj.S);
      sliver = up_f3(pa[j].rad, pa[j].rrho, abs(aff).hi(), pa[j].tlo);
    }
    forward = std::min(forward, std::max({pa[i].rad, pa[j].rad, sliver}));
  }
  nd.forward = forward;
  double score = forward;
  for (double r : nd.rev) score = std::max(score, r);
  nd.score = nd.cone_ok ? score : kInf;
}

void Auditor::note_point(const Ia& x, const Ia& y, const Ia& w) {
  const P2 X{x / w, y / w};
  double lower = kInf;
  for (std::size_t i = 0; i < arcs_.size(); ++i) {
    lower = std::min(lower, point_lower(arcs_[i], X));
    if (arcs_[i].point) point_cover_[i] = std::min(point_cover_[i], norm(X - arcs_[i].S).hi());
  }
  lower_ = std::max(lower_, lower);
}

// Term (c) of the theorem at both ends of the curve part.
bool Auditor::end_terms(const P2& X0, const P2& X1, double* term, std::string* reason) const {
  double t = 0.0;
  for (std::size_t i = 0; i < arcs_.size(); ++i) {
    const ArcData& a = arcs_[i];
    if (a.point) continue;
    if (!dot(a.T, X0 - a.S).nonpos()) {
      if (!dot(a.TE, a.E - X0).nonneg()) {
        *reason = "curve part starts beyond the end of arc " + std::to_string(i);
        return false;
      }
      t = std::max(t, (norm(a.S - X0) + Ia(2.0) * radial(a, X0)).hi());
    }
    if (!dot(a.TE, a.E - X1).nonpos()) {
      if (!dot(a.T, X1 - a.S).nonneg()) {
        *reason = "curve part ends before the start of arc " + std::to_string(i);
        return false;
      }
      t = std::max(t, (norm(a.E - X1) + Ia(2.0) * radial(a, X1)).hi());
    }
  }
  *term = t;
  return true;
}

FitAudit Auditor::run(const std::vector<HomSeg>& segs) {
  FitAudit out;
  point_cover_.assign(arcs_.size(), kInf);
  const HomSeg& first = segs.front();
  const HomSeg& last = segs.back();
  const P2 X0{first.x.front() / first.w.front(), first.y.front() / first.w.front()};
  const P2 X1{last.x.back() / last.w.back(), last.y.back() / last.w.back()};
  double ends = 0.0;
  if (!end_terms(X0, X1, &ends, &out.reason)) return out;

  std::vector<Node> pool;
  std::vector<int> free_ids;
  std::priority_queue<std::pair<double, int>> heap;
  auto keep = [&](Node&& nd) {
    int id;
    if (free_ids.empty()) {
      id = static_cast<int>(pool.size());
      pool.push_back(std::move(nd));
    } else {
      id = free_ids.back();
      free_ids.pop_back();
      pool[id] = std::move(nd);
    }
    heap.emplace(pool[id].score, id);
  };
  for (std::size_t s = 0; s < segs.size(); ++s) {
    note_point(segs[s].x.front(), segs[s].y.front(), segs[s].w.front());
    note_point(segs[s].x.back(), segs[s].y.back(), segs[s].w.back());
    keep(root(segs[s], static_cast<int>(s)));
  }
  int count = static_cast<int>(segs.size());
  while (!heap.empty()) {
    const auto [score, id] = heap.top();
    if (score <= std::max(target_, 1.05 * lower_) || count >= kMaxNodes || pool[id].depth >= kMaxDepth) break;
    heap.pop();
    Node left, right;
    left.seg = right.seg = pool[id].seg;
    left.depth = right.depth = pool[id].depth + 1;
    left.polys.resize(pool[id].polys.size());
    right.polys.resize(pool[id].polys.size());
    for (std::size_t k = 0; k < pool[id].polys.size(); ++k) {
      if (!pool[id].polys[k].empty()) halve(pool[id].polys[k], left.polys[k], right.polys[k]);
    }
    free_ids.push_back(id);
    note_point(left.polys[0].back(), left.polys[1].back(), left.polys[2].back());
    eval(left);
    eval(right);
    keep(std::move(left));
    keep(std::move(right));
    count += 2;
  }
  out.nodes = count;
  out.lower_bound = lower_;

  // The final cover: every node still in the heap.
  double forward = 0.0;
  std::vector<double> rev(arcs_.size(), 0.0);
  while (!heap.empty()) {
    const Node& nd = pool[heap.top().second];
    heap.pop();
    if (!nd.weights_ok) {
      out.reason = "weights not proven positive";
      return out;
    }
    if (!nd.cone_ok) {
      out.reason = "curve may pass behind an arc's centre (no angular order to match arc and curve points)";
      return out;
    }
    forward = std::max(forward, nd.forward);
    for (std::size_t i = 0; i < rev.size(); ++i) rev[i] = std::max(rev[i], nd.rev[i]);
  }
  double bound = std::max(forward, ends);
  Ia slack(0.0);
  for (std::size_t i = 0; i < arcs_.size(); ++i) {
    const ArcData& a = arcs_[i];
    bound = std::max(bound, a.point ? point_cover_[i] : rev[i]);
    slack = hull(slack, abs(a.tnorm - Ia(1.0)) * Ia(a.length));
  }
  out.certified_error = (Ia(bound) + slack).hi();
  out.certified = std::isfinite(out.certified_error);
  if (!out.certified) {
    out.certified_error = kInf;
    out.reason = "no finite bound within the node budget";
  }
  return out;
}

}  // namespace

FitAudit audit_fit(const Piece& piece, double u0, double u1, const Arc2* arcs, int n_arcs, double target) {
  FitAudit out;
  if (arcs == nullptr || n_arcs < 1) {
    out.reason = "no arcs";
    return out;
  }
  const auto [lo, hi] = piece_domain(piece);
  if (!(std::isfinite(u0) && std::isfinite(u1) && lo <= u0 && u0 < u1 && u1 <= hi)) {
    out.reason = "parameter range not inside the piece's domain";
    return out;
  }
  std::vector<ArcData> data(n_arcs);
  for (int i = 0; i < n_arcs; ++i) {
    if (!make_arc(arcs[i], data[i], &out.reason)) {
      out.reason += " (arc " + std::to_string(i) + ")";
      return out;
    }
  }
  const std::vector<HomSeg> segs = fit_audit_detail::curve_part_segments(piece, u0, u1, &out.reason);
  if (segs.empty()) return out;
  Auditor auditor(std::move(data), std::isfinite(target) && target > 0 ? target : 0.0);
  return auditor.run(segs);
}

TreeAudit audit_leaves(const std::vector<FitLeaf>& leaves, std::vector<FitAudit>* per_leaf, bool tight,
                       const std::function<void(std::size_t)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  TreeAudit t;
  if (per_leaf) per_leaf->clear();
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const FitLeaf& l = leaves[i];
    const FitAudit a = audit_fit(*l.piece, l.u0, l.u1, l.arcs, l.n_arcs, tight ? 0.0 : l.claimed);
    ++t.leaves;
    t.nodes += a.nodes;
    const bool over = a.certified && a.certified_error > l.claimed;
    const bool violation = over && a.lower_bound > l.claimed;
    if (a.certified) {
      ++t.certified;
      if (a.certified_error > t.max_certified_error || t.certified == 1) {
        t.max_certified_error = a.certified_error;
        t.max_lower_bound = a.lower_bound;
        t.worst_leaf = i;
      }
    }
    if (violation) ++t.violations;
    else if (over) ++t.unconfirmed;
    if ((over || !a.certified) && t.first_problem == static_cast<std::size_t>(-1)) {
      t.first_problem = i;
      t.first_problem_reason = violation ? "proven error exceeds the claimed eps (a fitter bug)"
                               : over    ? "certified bound exceeds the claimed eps (not confirmed; the proven lower "
                                           "bound is below the claim)"
                                         : a.reason;
    }
    if (per_leaf) per_leaf->push_back(a);
    if (progress) progress(i + 1);
  }
  t.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

}  // namespace revdist
