// Profile validation: joins, axis contact, r >= 0 and self-intersection, proven by
// Bezier hull arguments and subdivision (see profile_check.h for what is proven).
#include "core/profile_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/curve_eval.h"
#include "core/input_error.h"

namespace revdist {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}
std::string fmt(const Vec2& p) { return "(" + fmt(p.x()) + ", " + fmt(p.y()) + ")"; }

[[noreturn]] void fail_piece(const std::string& where, std::size_t piece, const std::string& problem) {
  throw InputError(where + " piece " + std::to_string(piece) + ": " + problem);
}
[[noreturn]] void fail(const std::string& where, const std::string& problem) {
  throw InputError(where + ": " + problem);
}

double weight(const BezierSegment& s, std::size_t i) { return s.weights.empty() ? 1.0 : s.weights[i]; }

// --- r bounds -------------------------------------------------------------------------

// Whether some point of s has r < level (or undecided at the depth limit); *at gets it.
// r - level = sum w_i (r_i - level) B_i / sum w_i B_i with w_i > 0, so non-negative
// coefficients prove r >= level on the whole segment.
bool r_below(const BezierSegment& s, double level, int depth, Vec2* at) {
  bool all_above = true;
  for (std::size_t i = 0; i < s.points.size(); ++i)
    if (weight(s, i) * (s.points[i].x() - level) < 0) all_above = false;
  if (all_above) return false;
  for (const Vec2& end : {s.points.front(), s.points.back()}) {
    if (end.x() < level) {
      *at = end;
      return true;
    }
  }
  if (depth == 0) {
    *at = split_segment(s, 0.5).first.points.back();
    return true;
  }
  const auto halves = split_segment(s, 0.5);
  return r_below(halves.first, level, depth - 1, at) || r_below(halves.second, level, depth - 1, at);
}

// --- geometry of segments -------------------------------------------------------------

struct Box {
  Vec2 lo, hi;
};
Box box_of(const BezierSegment& s) {
  Box b{s.points[0], s.points[0]};
  for (const Vec2& p : s.points) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}
double box_distance(const Box& a, const Box& b) {
  const Vec2 gap = (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(Vec2::Zero());
  return gap.norm();
}

double segment_distance(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) {
  const double d1 = cross2(a1 - a0, b0 - a0), d2 = cross2(a1 - a0, b1 - a0);
  const double d3 = cross2(b1 - b0, a0 - b0), d4 = cross2(b1 - b0, a1 - b0);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0.0;
  return std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                   point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
}

double polygon_length(const BezierSegment& s) {
  double l = 0;
  for (std::size_t i = 1; i < s.points.size(); ++i) l += (s.points[i] - s.points[i - 1]).norm();
  return l;
}

double diameter(const BezierSegment& s) {
  const Box b = box_of(s);
  return (b.hi - b.lo).norm();
}

// Whether the non-zero vectors lie in an open half-plane (some n has n.v > 0 for all):
// the largest angular gap between them exceeds pi. A small margin keeps rounding of
// atan2 from deciding nearly opposite vectors.
bool in_open_half_plane(const std::vector<Vec2>& vs) {
  std::vector<double> angles;
  for (const Vec2& v : vs)
    if (v.x() != 0 || v.y() != 0) angles.push_back(std::atan2(v.y(), v.x()));
  if (angles.size() <= 1) return true;
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2 * kPi - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) gap = std::max(gap, angles[i] - angles[i - 1]);
  return gap > kPi + 1e-12;
}

// Injective: with positive weights, edges in an open half-plane make the projection on
// its normal strictly monotone (a Bernstein numerator with one sign change has one root).
bool injective(const BezierSegment& s) {
  std::vector<Vec2> edges;
  for (std::size_t i = 1; i < s.points.size(); ++i) edges.push_back(s.points[i] - s.points[i - 1]);
  return in_open_half_plane(edges);
}

struct Seg {
  BezierSegment bez;
  std::size_t piece;
  double chain_start;  // upper bound of the arc length from the profile start
  double length;       // upper bound of its arc length (control polygon length)
};

void cut_injective(const BezierSegment& s, std::size_t piece, double tol, int depth, std::vector<Seg>& out) {
  if (injective(s) || depth == 0 || diameter(s) <= tol) {
    out.push_back({s, piece, 0.0, polygon_length(s)});
    return;
  }
  const auto halves = split_segment(s, 0.5);
  cut_injective(halves.first, piece, tol, depth - 1, out);
  cut_injective(halves.second, piece, tol, depth - 1, out);
}

// Whether a and b come within tol of each other (or stay undecided down to the depth
// limit); *at gets a point near the contact.
bool near(const BezierSegment& a, const BezierSegment& b, double tol, int depth, Vec2* at) {
  if (box_distance(box_of(a), box_of(b)) > tol) return false;
  const double ea = chord_flatness(a.points), eb = chord_flatness(b.points);
  const double d = segment_distance(a.points.front(), a.points.back(), b.points.front(), b.points.back());
  if (d - ea - eb > tol) return false;
  if (d + ea + eb <= tol || depth == 0) {
    *at = 0.5 * (a.points.front() + a.points.back());
    return true;
  }
  if (ea >= eb) {
    const auto h = split_segment(a, 0.5);
    return near(h.first, b, tol, depth - 1, at) || near(h.second, b, tol, depth - 1, at);
  }
  const auto h = split_segment(b, 0.5);
  return near(a, h.first, tol, depth - 1, at) || near(a, h.second, tol, depth - 1, at);
}

// a ends where b starts (at j). Proves they share no other point: a line through j that
// has a's control points on one side and b's on the other separates the two hulls.
// Subdivides towards j; the far halves must stay more than tol apart from the other
// segment. Returns false with *at set when that fails (a fold-back or a crossing).
bool meet_only_at_joint(const BezierSegment& a, const BezierSegment& b, double tol, int depth, Vec2* at) {
  const Vec2 j = b.points.front();
  std::vector<Vec2> dirs;
  for (std::size_t i = 0; i + 1 < a.points.size(); ++i) dirs.push_back(a.points[i] - j);
  for (std::size_t i = 1; i < b.points.size(); ++i) dirs.push_back(j - b.points[i]);
  if (in_open_half_plane(dirs)) return true;
  *at = j;
  if (depth == 0 || polygon_length(a) <= 4 * tol || polygon_length(b) <= 4 * tol) return false;
  const auto ha = split_segment(a, 0.5), hb = split_segment(b, 0.5);
  if (near(ha.first, hb.first, tol, 60, at) || near(ha.first, hb.second, tol, 60, at) ||
      near(ha.second, hb.second, tol, 60, at))
    return false;
  return meet_only_at_joint(ha.second, hb.first, tol, depth - 1, at);
}

// The pairs (i < k) of segments whose bounding boxes come within tol of each other, in
// increasing order: every other pair is more than tol apart (near() would say so at once)
// and cannot share a joint. A uniform grid with cells about the median box size keeps this
// near-linear (100,000 pieces in well under a second) where all pairs would take minutes;
// boxes spanning many cells are compared with every segment instead.
std::vector<std::pair<std::size_t, std::size_t>> candidate_pairs(const std::vector<Seg>& segs, double tol) {
  const std::size_t m = segs.size();
  std::vector<Box> boxes(m);
  std::vector<double> extent(m);
  Box all{Vec2::Constant(std::numeric_limits<double>::infinity()), Vec2::Constant(-std::numeric_limits<double>::infinity())};
  for (std::size_t i = 0; i < m; ++i) {
    boxes[i] = box_of(segs[i].bez);
    boxes[i].lo -= Vec2::Constant(tol);
    boxes[i].hi += Vec2::Constant(tol);
    extent[i] = (boxes[i].hi - boxes[i].lo).maxCoeff();
    all.lo = all.lo.cwiseMin(boxes[i].lo);
    all.hi = all.hi.cwiseMax(boxes[i].hi);
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  auto overlap = [&](std::size_t i, std::size_t k) {
    return boxes[i].lo.x() <= boxes[k].hi.x() && boxes[k].lo.x() <= boxes[i].hi.x() &&
           boxes[i].lo.y() <= boxes[k].hi.y() && boxes[k].lo.y() <= boxes[i].hi.y();
  };
  if (m < 64) {
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t k = i + 1; k < m; ++k)
        if (overlap(i, k)) pairs.emplace_back(i, k);
    return pairs;
  }
  std::vector<double> sorted = extent;
  std::nth_element(sorted.begin(), sorted.begin() + m / 2, sorted.end());
  const double cell = std::max(sorted[m / 2], 1e-300);
  // Cells per axis stay below 2^20 so a cell index packs into 64 bits.
  const double span = (all.hi - all.lo).maxCoeff();
  const double size = std::max(cell, span / double(1 << 20));
  auto index = [&](double v, double lo) { return static_cast<std::uint64_t>(std::floor((v - lo) / size)); };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  std::vector<std::size_t> big;
  for (std::size_t i = 0; i < m; ++i) {
    const std::uint64_t x0 = index(boxes[i].lo.x(), all.lo.x()), x1 = index(boxes[i].hi.x(), all.lo.x());
    const std::uint64_t y0 = index(boxes[i].lo.y(), all.lo.y()), y1 = index(boxes[i].hi.y(), all.lo.y());
    if ((x1 - x0 + 1) * (y1 - y0 + 1) > 16) {
      big.push_back(i);
      continue;
    }
    for (std::uint64_t x = x0; x <= x1; ++x)
      for (std::uint64_t y = y0; y <= y1; ++y) grid[(x << 32) | y].push_back(i);
  }
  for (const auto& [key, ids] : grid)
    for (std::size_t a = 0; a < ids.size(); ++a)
      for (std::size_t b = a + 1; b < ids.size(); ++b)
        if (overlap(ids[a], ids[b])) pairs.emplace_back(std::min(ids[a], ids[b]), std::max(ids[a], ids[b]));
  for (const std::size_t i : big)
    for (std::size_t k = 0; k < m; ++k)
      if (k != i && (k > i || !std::binary_search(big.begin(), big.end(), k)) && overlap(i, k))
        pairs.emplace_back(std::min(i, k), std::max(i, k));
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

// Where curve piece p (Bezier or B-spline) stops inside its domain: a
// parameter where its speed |C'| is at most `slow`, not within 1e-9 of the
// domain's width of its ends (a repeated end control point is a stop at the
// end, and harmless). At such a point the curve may turn back on itself (a
// cusp): its two branches leave one point in one direction, within any
// tolerance of each other near it, and no tangent exists there for the
// spiral split and the fits' error bounds. `slow`: 1e-9 of the control
// polygon's length (`polygon`, about the mean speed) per unit of the domain.
// The speed is sampled (32 points a Bezier piece, 16 a B-spline's knot span),
// and each local minimum at most half its larger neighbour (a zero between
// two samples leaves at least that dip) refined by golden sections.
bool stops_inside(const Piece& p, double polygon, double* at) {
  const auto [lo, hi] = piece_domain(p);
  const double margin = 1e-9 * (hi - lo), slow = 1e-9 * polygon / (hi - lo);
  auto speed = [&](double u) {
    Vec2 d[2];
    piece_derivatives(p, u, 1, d);
    return d[1].norm();
  };
  std::vector<double> ends{lo, hi};
  if (p.kind == PieceKind::bspline) {
    ends.clear();
    for (double k : p.knots)
      if (k >= lo && k <= hi && (ends.empty() || k > ends.back())) ends.push_back(k);
  }
  const int per = p.kind == PieceKind::bspline ? 16 : 32;
  std::vector<double> us;
  for (std::size_t j = 0; j + 1 < ends.size(); ++j)
    for (int k = 0; k < per; ++k) us.push_back(ends[j] + (ends[j + 1] - ends[j]) * k / per);
  us.push_back(hi);
  std::vector<double> v(us.size());
  for (std::size_t i = 0; i < us.size(); ++i) v[i] = speed(us[i]);
  for (std::size_t i = 0; i < us.size(); ++i) {
    const double left = i > 0 ? v[i - 1] : v[i], right = i + 1 < us.size() ? v[i + 1] : v[i];
    if (left < v[i] || right < v[i] || v[i] > 0.5 * std::max(left, right)) continue;  // no dip towards 0
    double a = us[i > 0 ? i - 1 : i], b = us[i + 1 < us.size() ? i + 1 : i];
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    double c = b - g * (b - a), d = a + g * (b - a), fc = speed(c), fd = speed(d);
    for (int it = 0; it < 80 && b - a > 1e-15 * (hi - lo); ++it) {
      if (fc <= fd) b = d, d = c, fd = fc, c = b - g * (b - a), fc = speed(c);
      else a = c, c = d, fc = fd, d = a + g * (b - a), fd = speed(d);
    }
    const double u = fc <= fd ? c : d, f = std::min(fc, fd);
    if (f <= slow && u > lo + margin && u < hi - margin) {
      *at = u;
      return true;
    }
  }
  return false;
}

}  // namespace

void profile_box(const Profile& profile, Vec2* lo, Vec2* hi) {
  *lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  *hi = -*lo;
  auto take = [&](const Vec2& q) {
    *lo = lo->cwiseMin(q);
    *hi = hi->cwiseMax(q);
  };
  for (const Piece& p : profile.pieces) {
    for (const Vec2& q : p.points) take(q);
    if (p.kind != PieceKind::arc || p.points.size() != 3) continue;
    const ArcGeometry g = arc_geometry(p);
    if (!(std::isfinite(g.radius) && g.center.allFinite())) continue;  // (collinear points: rejected as an arc)
    const double a0 = std::min(g.start_angle, g.start_angle + g.sweep);
    const double a1 = std::max(g.start_angle, g.start_angle + g.sweep);
    const double quarter = 0.5 * kPi;
    for (double k = std::ceil(a0 / quarter); k * quarter <= a1; ++k)
      take(g.center + g.radius * Vec2(std::cos(k * quarter), std::sin(k * quarter)));
  }
}

double profile_size(const Profile& profile) {
  Vec2 lo, hi;
  profile_box(profile, &lo, &hi);
  return profile.pieces.empty() ? 0.0 : (hi - lo).norm();
}

double profile_tolerance(const Profile& profile) { return 1e-9 * profile_size(profile); }

void join_profile(Profile& profile, const std::string& where) {
  if (profile.pieces.empty()) fail(where, "the profile has no pieces");
  const double tol = profile_tolerance(profile);
  if (!(tol > 0)) fail(where, "the profile is a single point");
  std::vector<Piece>& ps = profile.pieces;
  for (std::size_t i = 1; i < ps.size(); ++i) {
    const Vec2 gap = ps[i].start() - ps[i - 1].end();
    if (gap.norm() > tol)
      fail_piece(where, i,
                 "does not join piece " + std::to_string(i - 1) + ": starts at " + fmt(ps[i].start()) +
                     ", previous ends at " + fmt(ps[i - 1].end()) + " (gap " + fmt(gap.norm()) +
                     " > tolerance " + fmt(tol) + ")");
    ps[i].points.front() = ps[i - 1].points.back();
  }
  const Vec2 first = ps.front().start(), last = ps.back().end();
  const bool ends_on_axis = std::abs(first.x()) <= tol && std::abs(last.x()) <= tol;
  if ((last - first).norm() <= tol) {
    if (ends_on_axis) fail(where, "closed loop touches the axis at " + fmt(first));
    ps.back().points.back() = ps.front().points.front();
    profile.closed_loop = true;
  } else if (ends_on_axis) {
    ps.front().points.front().x() = 0.0;
    ps.back().points.back().x() = 0.0;
    profile.closed_loop = false;
  } else {
    fail(where, "the profile neither reaches the axis at both ends nor closes: starts at " + fmt(first) +
                    ", ends at " + fmt(last));
  }
}

void check_profile(const Profile& profile, const std::string& where) {
  const double tol = profile_tolerance(profile);
  const std::vector<Piece>& ps = profile.pieces;
  std::vector<Seg> segs;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const BezierSegment all{ps[i].points, {}, 0, 1};
    if (diameter(all) <= tol) fail_piece(where, i, "degenerate piece (all its points within " + fmt(tol) + ")");
    // (A curve lies within the hull of its control points.)
    double r_max = 0;
    Vec2 lowest = ps[i].points.front();
    for (const Vec2& q : ps[i].points) {
      r_max = std::max(r_max, q.x());
      if (q.x() < lowest.x()) lowest = q;
    }
    // (A piece on the far side of the axis is that, not one lying on it.)
    if (r_max <= tol && lowest.x() < -tol)
      fail_piece(where, i, "negative r: r <= 0 throughout, down to r = " + fmt(lowest.x()) + " at " + fmt(lowest));
    if (r_max <= tol) fail_piece(where, i, "lies on the axis (r = 0 throughout): it bounds no volume");
    double u_stop;
    if ((ps[i].kind == PieceKind::bezier || ps[i].kind == PieceKind::bspline) &&
        stops_inside(ps[i], polygon_length(all), &u_stop))
      fail_piece(where, i,
                 "the curve stops at parameter " + fmt(u_stop) + ", at " + fmt(piece_point(ps[i], u_stop)) +
                     " (its derivative vanishes inside the piece: a cusp, where it may turn back on itself); split the "
                     "piece there");
    for (const BezierSegment& s : piece_bezier_segments(ps[i])) {
      Vec2 at;
      if (profile.closed_loop && r_below(s, tol, 40, &at))
        fail_piece(where, i, "closed loop touches or crosses the axis near " + fmt(at));
      if (!profile.closed_loop && r_below(s, -tol, 40, &at))
        fail_piece(where, i, "negative r: the curve reaches r = " + fmt(at.x()) + " < 0 at " + fmt(at));
      cut_injective(s, i, tol, 30, segs);
    }
  }
  // A closed loop of one or two segments would have adjacent segments sharing both ends.
  while (profile.closed_loop && segs.size() < 4) {
    std::vector<Seg> finer;
    for (const Seg& s : segs) {
      const auto h = split_segment(s.bez, 0.5);
      finer.push_back({h.first, s.piece, 0.0, polygon_length(h.first)});
      finer.push_back({h.second, s.piece, 0.0, polygon_length(h.second)});
    }
    segs.swap(finer);
  }
  double chain = 0;
  for (Seg& s : segs) {
    s.chain_start = chain;
    chain += s.length;
  }
  const std::size_t m = segs.size();
  auto describe = [&](const Seg& a, const Seg& b, const Vec2& at) {
    const std::string who = a.piece == b.piece ? "piece " + std::to_string(a.piece) + " meets itself"
                                               : "pieces " + std::to_string(a.piece) + " and " +
                                                     std::to_string(b.piece) + " meet";
    return "self-intersecting profile: " + who + " near " + fmt(at);
  };
  for (const auto& [i, k] : candidate_pairs(segs, tol)) {
    {
      const Seg& a = segs[i];
      const Seg& b = segs[k];
      Vec2 at;
      const bool adjacent = k == i + 1;
      const bool wrap_adjacent = profile.closed_loop && i == 0 && k == m - 1 && m > 1;
      if (adjacent || wrap_adjacent) {
        const bool ok = adjacent ? meet_only_at_joint(a.bez, b.bez, tol, 40, &at)
                                 : meet_only_at_joint(b.bez, a.bez, tol, 40, &at);
        if (!ok) {
          if (a.piece == b.piece && !wrap_adjacent) fail(where, describe(a, b, at));
          fail(where, "self-intersecting profile: pieces " + std::to_string(adjacent ? a.piece : b.piece) +
                          " and " + std::to_string(adjacent ? b.piece : a.piece) +
                          " fold back or cross at their joint near " + fmt(at));
        }
        continue;
      }
      double between = b.chain_start - (a.chain_start + a.length);
      if (profile.closed_loop) between = std::min(between, chain - (b.chain_start + b.length) + a.chain_start);
      if (between <= 4 * tol) continue;  // within tolerance of adjacent: see profile_check.h
      if (near(a.bez, b.bez, tol, 60, &at)) fail(where, describe(a, b, at));
    }
  }
}

}  // namespace revdist
