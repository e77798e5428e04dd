// revdist/1 case reader (SPEC section 3): parses solids, instances and queries and
// rejects bad input with one line naming the file, the item and the problem.
#include "core/case_io.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>

#include "core/input_error.h"
#include "core/json_util.h"
#include "core/profile_check.h"

namespace revdist {

namespace {

// Shortest decimal that reads back as v, for messages.
std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  if (std::strtod(buf, nullptr) != v) std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Besides kMaxMagnitude (core/json_util.h): a profile's join tolerance (1e-9 of its
// size) must stay above the rounding of its coordinates.
constexpr double kMinProfileSize = 1e-100;
constexpr double kMaxOffsetRatio = 1e6;    // largest |coordinate| / profile size
// Largest / smallest weight within one piece. (1e6 was allowed: a rational
// quadratic arc with middle weight 3e4 ran the fit out of memory, 2.9 GB and
// std::bad_alloc; 2e4 and every cubic tried at 1e4 fit in a few microseconds.)
constexpr double kMaxWeightRatio = 1e4;

std::string in_quotes(const std::string& s) { return quote(s); }

const char* kind_name(PieceKind k) {
  switch (k) {
    case PieceKind::line: return "line";
    case PieceKind::arc: return "arc";
    case PieceKind::bezier: return "bezier";
    case PieceKind::bspline: return "bspline";
  }
  return "?";
}

JsonWhere sub(const JsonWhere& w, const std::string& what) { return {w.file, w.item + " " + what}; }

std::vector<Vec2> read_points(const Json& j, const JsonWhere& where) {
  if (!j.is_array()) where.fail("expected an array of [r, z] points");
  std::vector<Vec2> pts;
  for (std::size_t i = 0; i < j.size(); ++i) pts.push_back(read_vec2(j[i], sub(where, "point " + std::to_string(i))));
  return pts;
}

std::vector<double> read_weights(const Json& j, std::size_t count, const JsonWhere& where) {
  if (!j.is_array()) where.fail("\"weights\" must be an array of numbers");
  if (j.size() != count)
    where.fail(std::to_string(j.size()) + " weights for " + std::to_string(count) + " points");
  std::vector<double> w;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const double v = read_number(j[i], sub(where, "weight " + std::to_string(i)));
    if (!(v > 0)) where.fail("weight " + fmt(v) + " <= 0 (index " + std::to_string(i) + ")");
    w.push_back(v);
  }
  // Only ratios matter (a common factor leaves the curve unchanged); a huge ratio pulls
  // the curve into a near-cusp at one control point whose fit never ends (issue 10 item 17).
  const auto [lo, hi] = std::minmax_element(w.begin(), w.end());
  if (*hi > kMaxWeightRatio * *lo)
    where.fail("weights " + fmt(*lo) + " and " + fmt(*hi) + " differ by more than a factor " +
               fmt(kMaxWeightRatio) + " (the curve degenerates towards one control point)");
  // Scaled (exactly, by a power of two) to a largest weight in [1, 2): weights of
  // 5e-324 or 1.7e308, a valid curve, underflowed or overflowed the evaluation.
  const int e = std::ilogb(*hi);
  for (double& v : w) v = std::ldexp(v, -e);
  return w;
}

void check_knots(const Piece& p, const JsonWhere& where) {
  const std::vector<double>& t = p.knots;
  const int deg = p.degree;
  const std::size_t n = p.points.size();
  if (n < static_cast<std::size_t>(deg) + 1)
    where.fail("degree " + std::to_string(deg) + " needs at least " + std::to_string(deg + 1) + " points, got " +
               std::to_string(n));
  if (t.size() != n + deg + 1)
    where.fail("degree " + std::to_string(deg) + " with " + std::to_string(n) + " points needs " +
               std::to_string(n + deg + 1) + " knots, got " + std::to_string(t.size()));
  for (std::size_t i = 1; i < t.size(); ++i)
    if (t[i] < t[i - 1])
      where.fail("knots decrease at index " + std::to_string(i) + " (" + fmt(t[i - 1]) + " > " + fmt(t[i]) + ")");
  for (int i = 1; i <= deg; ++i)
    if (t[i] != t[0] || t[t.size() - 1 - i] != t.back())
      where.fail("knots not clamped: the first and the last " + std::to_string(deg + 1) + " knots must be equal");
  if (!(t.front() < t.back())) where.fail("the knot vector has zero length");
  // Only the knots' ratios matter, but their differences must be finite doubles.
  if (!(std::abs(t.front()) <= kMaxMagnitude && std::abs(t.back()) <= kMaxMagnitude))
    where.fail("knots " + fmt(t.front()) + " .. " + fmt(t.back()) + " outside +-" + fmt(kMaxMagnitude));
  // Interior knots lie strictly inside: an end repeated more than degree + 1
  // times leaves a control point without effect (the curve would not start
  // or end at it).
  if (n > static_cast<std::size_t>(deg) + 1 && !(t[deg + 1] > t.front() && t[n - 1] < t.back()))
    where.fail("an end knot is repeated more than degree + 1 = " + std::to_string(deg + 1) + " times");
  for (std::size_t i = deg + 1; i < n;) {
    std::size_t k = i;
    while (k < n && t[k] == t[i]) ++k;
    if (k - i > static_cast<std::size_t>(deg))
      where.fail("interior knot " + fmt(t[i]) + " has multiplicity " + std::to_string(k - i) + " > degree " +
                 std::to_string(deg));
    i = k;
  }
}

// A B-spline does not change under an affine map of its knots. Moving them to start at 0
// and span [1, 2) keeps parameter-space thresholds of the fit meaningful (knots scaled by
// 1e-100 made the spiral split run without end). Only exact operations are used: the
// shift when t - t0 is exact for every knot, and a power-of-two scale.
void normalize_knots(std::vector<double>& t) {
  const double t0 = t.front();
  bool exact_shift = true;
  for (double v : t) exact_shift = exact_shift && (v - t0) + t0 == v && (v - t0) - v == -t0;
  if (exact_shift)
    for (double& v : t) v -= t0;
  const int e = std::ilogb(t.back() - t.front());
  for (double& v : t) v = std::ldexp(v, -e);
}

Piece read_piece(const Json& j, const JsonWhere& where) {
  if (!j.is_object()) where.fail("expected a piece object such as {\"line\": [[r, z], [r, z]]}");
  static const char* kinds[] = {"line", "arc", "bezier", "bspline"};
  int found = -1;
  for (int k = 0; k < 4; ++k) {
    if (!j.contains(kinds[k])) continue;
    if (found >= 0) where.fail(std::string("both \"") + kinds[found] + "\" and \"" + kinds[k] + "\" in one piece");
    found = k;
  }
  if (found < 0) {
    std::string key;
    for (auto it = j.begin(); it != j.end(); ++it)
      if (it.key() != "comment") key = it.key();
    where.fail(key.empty() ? std::string("empty piece")
                           : "unknown piece type " + in_quotes(key) + " (expected line, arc, bezier or bspline)");
  }
  Piece p;
  p.kind = static_cast<PieceKind>(found);
  const Json& body = j[kinds[found]];
  switch (p.kind) {
    case PieceKind::line:
    case PieceKind::arc: {
      reject_unknown_members(j, {kinds[found]}, where);
      p.points = read_points(body, where);
      const std::size_t want = p.kind == PieceKind::line ? 2 : 3;
      if (p.points.size() != want)
        where.fail(std::string("a ") + kinds[found] + " needs " + std::to_string(want) + " points, got " +
                   std::to_string(p.points.size()));
      p.degree = p.kind == PieceKind::line ? 1 : 2;
      break;
    }
    case PieceKind::bezier: {
      reject_unknown_members(j, {"bezier", "weights"}, where);
      p.points = read_points(body, where);
      if (p.points.size() < 2) where.fail("a bezier needs at least 2 points, got " + std::to_string(p.points.size()));
      if (p.points.size() > kMaxPieceDegree + 1)
        where.fail("bezier degree " + std::to_string(p.points.size() - 1) + " > " + std::to_string(kMaxPieceDegree));
      p.degree = static_cast<int>(p.points.size()) - 1;
      if (j.contains("weights")) p.weights = read_weights(j["weights"], p.points.size(), where);
      break;
    }
    case PieceKind::bspline: {
      reject_unknown_members(j, {"bspline"}, where);
      if (!body.is_object()) where.fail("\"bspline\" must be an object {degree, knots, points, weights?}");
      reject_unknown_members(body, {"degree", "knots", "points", "weights"}, where);
      const double deg = read_number(require(body, "degree", where), sub(where, "degree"));
      if (deg != std::floor(deg) || deg < 1 || deg > kMaxPieceDegree)
        where.fail("degree " + fmt(deg) + " is not an integer in 1.." + std::to_string(kMaxPieceDegree));
      p.degree = static_cast<int>(deg);
      p.points = read_points(require(body, "points", where), where);
      const Json& knots = require(body, "knots", where);
      if (!knots.is_array()) where.fail("\"knots\" must be an array of numbers");
      for (std::size_t i = 0; i < knots.size(); ++i)
        p.knots.push_back(read_number(knots[i], sub(where, "knot " + std::to_string(i))));
      if (body.contains("weights")) p.weights = read_weights(body["weights"], p.points.size(), where);
      check_knots(p, where);
      normalize_knots(p.knots);
      break;
    }
  }
  return p;
}

// Arcs need three distinct, non-collinear points; the tolerance is the profile's.
void check_arcs(const Profile& profile, const std::string& item, const JsonWhere& top) {
  const double tol = profile_tolerance(profile);
  for (std::size_t i = 0; i < profile.pieces.size(); ++i) {
    const Piece& p = profile.pieces[i];
    if (p.kind != PieceKind::arc) continue;
    const JsonWhere w{top.file, item + " piece " + std::to_string(i)};
    const Vec2 a = p.points[1] - p.points[0], b = p.points[2] - p.points[0], c = p.points[2] - p.points[1];
    if (a.norm() <= tol || b.norm() <= tol || c.norm() <= tol)
      w.fail("arc points coincide (an arc runs from p0 through pm to a different p1)");
    // sin of the angle at p0 below 1e-12: the radius would exceed 1e12 chords.
    if (std::abs(a.x() * b.y() - a.y() * b.x()) <= 1e-12 * a.norm() * b.norm())
      w.fail("arc points are collinear (use a line)");
  }
}

// Coordinates in the range the engines handle (see kMaxMagnitude); a curve piece whose
// end control point is repeated has a zero end tangent (a singular point the spiral
// split cannot start from).
void check_magnitudes(const Profile& profile, const std::string& item, const JsonWhere& top) {
  double big = 0;
  for (std::size_t i = 0; i < profile.pieces.size(); ++i) {
    const JsonWhere w{top.file, item + " piece " + std::to_string(i)};
    for (const Vec2& q : profile.pieces[i].points) {
      big = std::max({big, std::abs(q.x()), std::abs(q.y())});
      if (std::max(std::abs(q.x()), std::abs(q.y())) > kMaxMagnitude)
        w.fail("coordinate " + fmt(std::max(std::abs(q.x()), std::abs(q.y()))) + " beyond the supported range +-" +
               fmt(kMaxMagnitude));
    }
  }
  const double size = profile_size(profile);
  const JsonWhere w{top.file, item};
  if (size < kMinProfileSize)
    w.fail("the profile's size " + fmt(size) + " is below the supported " + fmt(kMinProfileSize));
  if (big > kMaxOffsetRatio * size)
    w.fail("the profile (size " + fmt(size) + ") lies " + fmt(big) + " from the origin of its plane, more than " +
           fmt(kMaxOffsetRatio) + " times its size: double rounding would exceed its tolerances");
  const double tol = profile_tolerance(profile);
  for (std::size_t i = 0; i < profile.pieces.size(); ++i) {
    const Piece& p = profile.pieces[i];
    if (p.kind != PieceKind::bezier && p.kind != PieceKind::bspline) continue;
    const std::size_t n = p.points.size();
    if (n < 3) continue;
    const JsonWhere wp{top.file, item + " piece " + std::to_string(i)};
    if ((p.points[1] - p.points[0]).norm() <= tol)
      wp.fail("the first two control points coincide (a zero tangent at the start: split the piece or drop one)");
    if ((p.points[n - 1] - p.points[n - 2]).norm() <= tol)
      wp.fail("the last two control points coincide (a zero tangent at the end: split the piece or drop one)");
  }
}

Profile read_profile(const Json& j, const std::string& item, const JsonWhere& top) {
  const JsonWhere w{top.file, item};
  if (!j.is_array() || j.empty()) w.fail("a profile must be a non-empty array of pieces");
  Profile profile;
  for (std::size_t i = 0; i < j.size(); ++i)
    profile.pieces.push_back(read_piece(j[i], {top.file, item + " piece " + std::to_string(i)}));
  check_magnitudes(profile, item, top);
  check_arcs(profile, item, top);
  const std::string where = top.file + ": " + item;
  join_profile(profile, where);
  check_profile(profile, where);
  return profile;
}

void check_same_structure(const Profile& a, const Profile& b, const std::string& item, const JsonWhere& top) {
  const JsonWhere w{top.file, item};
  if (a.pieces.size() != b.pieces.size())
    w.fail("has " + std::to_string(b.pieces.size()) + " pieces, keyframe 0 has " + std::to_string(a.pieces.size()));
  for (std::size_t i = 0; i < a.pieces.size(); ++i) {
    const Piece& p = a.pieces[i];
    const Piece& q = b.pieces[i];
    const JsonWhere wp = sub(w, "piece " + std::to_string(i));
    if (p.kind != q.kind) wp.fail(std::string("is a ") + kind_name(q.kind) + ", in keyframe 0 a " + kind_name(p.kind));
    if (p.degree != q.degree || p.points.size() != q.points.size())
      wp.fail("degree " + std::to_string(q.degree) + " with " + std::to_string(q.points.size()) +
              " points, keyframe 0 has degree " + std::to_string(p.degree) + " with " +
              std::to_string(p.points.size()));
    if (p.knots != q.knots) wp.fail("knots differ from keyframe 0");
  }
  if (a.closed_loop != b.closed_loop)
    w.fail(std::string("is ") + (b.closed_loop ? "a closed loop" : "an axis profile") + ", keyframe 0 is " +
           (a.closed_loop ? "a closed loop" : "an axis profile"));
}

SolidDef read_solid(const std::string& name, const Json& j, const JsonWhere& top) {
  const std::string item = "solid " + in_quotes(name);
  const JsonWhere w{top.file, item};
  if (!j.is_object()) w.fail("expected an object with \"profile\" or \"keyframes\"");
  reject_unknown_members(j, {"profile", "keyframes"}, w);
  const bool has_profile = j.contains("profile"), has_keys = j.contains("keyframes");
  if (has_profile == has_keys) w.fail("needs exactly one of \"profile\" and \"keyframes\"");
  SolidDef s;
  s.name = name;
  if (has_profile) {
    s.keyframes.push_back(read_profile(j["profile"], item, top));
    return s;
  }
  const Json& keys = j["keyframes"];
  if (!keys.is_array() || keys.empty()) w.fail("\"keyframes\" must be a non-empty array of profiles");
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string kitem = item + " keyframe " + std::to_string(k);
    s.keyframes.push_back(read_profile(keys[k], kitem, top));
    if (k > 0) check_same_structure(s.keyframes[0], s.keyframes[k], kitem, top);
  }
  return s;
}

std::string read_string(const Json& j, const JsonWhere& where) {
  if (!j.is_string()) where.fail("expected a string");
  return j.get<std::string>();
}

// An instance's motion over scene frames (core/motion.h).
InstanceMotion read_motion(const Json& j, const JsonWhere& w) {
  if (!j.is_object()) w.fail("expected an object {velocity?, acceleration?, spin?, wave?, time_rate?}");
  reject_unknown_members(j, {"velocity", "acceleration", "spin", "wave", "time_rate"}, w);
  InstanceMotion m;
  if (j.contains("velocity")) m.velocity = read_vec3(j["velocity"], sub(w, "velocity"));
  if (j.contains("acceleration")) m.acceleration = read_vec3(j["acceleration"], sub(w, "acceleration"));
  if (j.contains("spin")) m.spin = read_vec3(j["spin"], sub(w, "spin"));
  if (j.contains("wave")) {
    const Json& wv = j["wave"];
    const JsonWhere ww = sub(w, "wave");
    if (!wv.is_object()) ww.fail("expected an object {amplitude, period, phase?}");
    reject_unknown_members(wv, {"amplitude", "period", "phase"}, ww);
    m.wave_amplitude = read_vec3(require(wv, "amplitude", ww), sub(ww, "amplitude"));
    m.wave_period = read_number(require(wv, "period", ww), sub(ww, "period"));
    if (!(m.wave_period > 0)) ww.fail("period " + fmt(m.wave_period) + " <= 0 (frames)");
    if (wv.contains("phase")) m.wave_phase = read_number(wv["phase"], sub(ww, "phase"));
  }
  if (j.contains("time_rate")) m.time_rate = read_number(j["time_rate"], sub(w, "time_rate"));
  // Rates in the coordinates' range (a spin of 1e160 overflowed its norm to inf and
  // every later pose to NaN), a period whose 2 pi f / period stays finite.
  auto within = [&](const Vec3& v, const char* what) {
    if (!(v.cwiseAbs().maxCoeff() <= kMaxMagnitude))
      sub(w, what).fail("a component beyond the supported range +-" + fmt(kMaxMagnitude));
  };
  within(m.velocity, "velocity");
  within(m.acceleration, "acceleration");
  within(m.spin, "spin");
  within(m.wave_amplitude, "wave amplitude");
  if (!(m.wave_period >= 1 / kMaxMagnitude && std::abs(m.wave_phase) <= kMaxMagnitude))
    sub(w, "wave").fail("period " + fmt(m.wave_period) + " or phase " + fmt(m.wave_phase) +
                        " outside [1e-100, 1e100] frames, +-1e100 radians");
  if (!(std::abs(m.time_rate) <= kMaxMagnitude)) sub(w, "time_rate").fail("beyond +-" + fmt(kMaxMagnitude));
  return m;
}

Instance read_instance(const Json& j, const JsonWhere& at, const Case& c, const std::map<std::string, std::size_t>& solids) {
  if (!j.is_object()) at.fail("expected an instance object {name, solid, rotation?, translation?, time?}");
  Instance inst;
  inst.name = read_string(require(j, "name", at), at / "name");
  if (inst.name.empty()) (at / "name").fail("empty instance name");
  const JsonWhere w{at.file, "instance " + in_quotes(inst.name)};
  reject_unknown_members(j, {"name", "solid", "rotation", "translation", "time", "motion"}, w);
  const std::string solid = read_string(require(j, "solid", w), sub(w, "solid"));
  const auto it = solids.find(solid);
  if (it == solids.end()) w.fail("unknown solid " + in_quotes(solid));
  inst.solid = it->second;
  if (j.contains("rotation")) {
    const Json& q = j["rotation"];
    const JsonWhere wq = sub(w, "rotation");
    if (!q.is_array() || q.size() != 4) wq.fail("expected a quaternion [w, x, y, z]");
    double n2 = 0;
    for (int i = 0; i < 4; ++i) {
      inst.pose.q[i] = read_number(q[i], wq);
      n2 += inst.pose.q[i] * inst.pose.q[i];
    }
    double m = 0;
    for (int i = 0; i < 4; ++i) m = std::max(m, std::abs(inst.pose.q[i]));
    if (m == 0) wq.fail("the zero quaternion is not a rotation");
    // A quaternion whose |q|^2 underflows is the same rotation scaled up by a
    // power of two (exactly: no component grows past the largest);
    // [1e-170, 1e-170, 0, 0] was refused as the zero quaternion. Others are
    // kept as given.
    if (!(n2 >= DBL_MIN)) {
      const int up = -std::ilogb(m);
      n2 = 0;
      for (int i = 0; i < 4; ++i) {
        inst.pose.q[i] = std::ldexp(inst.pose.q[i], up);
        n2 += inst.pose.q[i] * inst.pose.q[i];
      }
    }
    if (!(n2 >= DBL_MIN) || !std::isfinite(n2)) wq.fail("quaternion too large to normalise (|q|^2 = " + fmt(n2) + ")");
  }
  if (j.contains("translation")) {
    inst.pose.translation = read_vec3(j["translation"], sub(w, "translation"));
    if (inst.pose.translation.cwiseAbs().maxCoeff() > kMaxMagnitude)
      sub(w, "translation").fail("component " + fmt(inst.pose.translation.cwiseAbs().maxCoeff()) +
                                 " beyond the supported range +-" + fmt(kMaxMagnitude));
  }
  if (j.contains("motion")) inst.motion = read_motion(j["motion"], sub(w, "motion"));
  const SolidDef& s = c.solids[inst.solid];
  if (j.contains("time")) {
    inst.time = read_number(j["time"], sub(w, "time"));
    const double last = static_cast<double>(s.keyframes.size() - 1);
    if (!s.deformable() && inst.time != 0)
      w.fail("time " + fmt(inst.time) + " given for static solid " + in_quotes(s.name) + " (only keyframed solids take a time)");
    if (inst.time < 0 || inst.time > last)
      w.fail("time " + fmt(inst.time) + " outside [0, " + fmt(last) + "] for solid " + in_quotes(s.name));
  }
  if (inst.motion.time_rate != 0 && !s.deformable())
    sub(sub(w, "motion"), "time_rate").fail("static solid " + in_quotes(s.name) + " has no keyframes to run through");
  return inst;
}

}  // namespace

Profile profile_at(const SolidDef& solid, double time) {
  const std::size_t k = solid.keyframes.size();
  if (k == 1) return solid.keyframes[0];
  const double s = std::clamp(time, 0.0, static_cast<double>(k - 1));
  const std::size_t i0 = static_cast<std::size_t>(std::floor(s));
  const double t = s - static_cast<double>(i0);
  if (t == 0 || i0 + 1 >= k) return solid.keyframes[i0];
  const Profile& a = solid.keyframes[i0];
  const Profile& b = solid.keyframes[i0 + 1];
  Profile out = a;
  for (std::size_t i = 0; i < out.pieces.size(); ++i) {
    Piece& p = out.pieces[i];
    const Piece& q = b.pieces[i];
    for (std::size_t j = 0; j < p.points.size(); ++j) p.points[j] = (1 - t) * a.pieces[i].points[j] + t * q.points[j];
    if (!p.weights.empty() || !q.weights.empty()) {
      std::vector<double> w(p.points.size());
      for (std::size_t j = 0; j < w.size(); ++j) {
        const double wa = a.pieces[i].weights.empty() ? 1.0 : a.pieces[i].weights[j];
        const double wb = q.weights.empty() ? 1.0 : q.weights[j];
        w[j] = (1 - t) * wa + t * wb;
      }
      p.weights = std::move(w);
    }
  }
  return out;
}

namespace {
Case read_case_from(const Json& doc, const std::string& path, bool all_pairs_when_absent);
}  // namespace

Case read_case(const std::string& path, bool all_pairs_when_absent) {
  return read_case_from(read_json_file(path), path, all_pairs_when_absent);
}

Case read_case_text(const std::string& text, const std::string& path) {
  return read_case_from(parse_json_text(text, path), path, true);
}

namespace {
Case read_case_from(const Json& doc, const std::string& path, bool all_pairs_when_absent) {
  const JsonWhere top{path, ""};
  if (!doc.is_object()) top.fail("expected a JSON object");
  require_format(doc, "revdist/1", top);
  Case c;
  c.file = path;
  const Json& solids = require(doc, "solids", top);
  if (!solids.is_object() || solids.empty()) (top / "solids").fail("expected a non-empty object of named solids");
  std::map<std::string, std::size_t> solid_index;
  for (auto it = solids.begin(); it != solids.end(); ++it) {
    solid_index[it.key()] = c.solids.size();
    c.solids.push_back(read_solid(it.key(), it.value(), top));
  }
  std::map<std::string, std::size_t> instance_index;
  if (doc.contains("instances")) {
    const Json& insts = doc["instances"];
    if (!insts.is_array()) (top / "instances").fail("expected an array of instances");
    for (std::size_t i = 0; i < insts.size(); ++i) {
      Instance inst = read_instance(insts[i], (top / "instances")[i], c, solid_index);
      if (!instance_index.emplace(inst.name, c.instances.size()).second)
        JsonWhere{path, "instance " + in_quotes(inst.name)}.fail("duplicate instance name");
      c.instances.push_back(std::move(inst));
    }
  }
  // A blend of two valid keyframes can still dip below the axis or cross itself.
  std::set<std::pair<std::size_t, double>> checked;
  for (const Instance& inst : c.instances) {
    const SolidDef& s = c.solids[inst.solid];
    if (!s.deformable() || inst.time == std::floor(inst.time) || !checked.emplace(inst.solid, inst.time).second)
      continue;
    const std::string item = "instance " + in_quotes(inst.name) + " (solid " + in_quotes(s.name) + " at time " +
                             fmt(inst.time) + ")";
    const Profile blended = profile_at(s, inst.time);
    check_magnitudes(blended, item, top);
    check_arcs(blended, item, top);
    check_profile(blended, path + ": " + item);
  }
  if (doc.contains("queries")) {
    const Json& qs = doc["queries"];
    const JsonWhere wq = top / "queries";
    if (!qs.is_array()) wq.fail("expected an array of [instance, instance] pairs");
    for (std::size_t i = 0; i < qs.size(); ++i) {
      const JsonWhere w = wq[i];
      if (!qs[i].is_array() || qs[i].size() != 2) w.fail("expected a pair [\"a\", \"b\"] of instance names");
      std::size_t ab[2];
      for (int k = 0; k < 2; ++k) {
        const std::string name = read_string(qs[i][k], w[k]);
        const auto it = instance_index.find(name);
        if (it == instance_index.end()) w.fail("unknown instance " + in_quotes(name));
        ab[k] = it->second;
      }
      if (ab[0] == ab[1]) w.fail("pairs instance " + in_quotes(c.instances[ab[0]].name) + " with itself");
      c.queries.emplace_back(ab[0], ab[1]);
    }
  } else if (all_pairs_when_absent) {
    // (20000 instances made 2e8 pairs: 2 GB and std::bad_alloc before any
    // query; 3000 made 4.5e6, 667 MB of answers in 30 s, not done.)
    const std::size_t n = c.instances.size(), pairs = n < 2 ? 0 : n * (n - 1) / 2;
    if (pairs > kMaxAllPairs)
      (top / "instances")
          .fail(std::to_string(n) + " instances and no \"queries\": all " + std::to_string(pairs) +
                " pairs, more than the " + std::to_string(kMaxAllPairs) +
                " a run takes; list the pairs in \"queries\", or ask `revdist scene` (its broad phase finds them)");
    for (std::size_t i = 0; i < c.instances.size(); ++i)
      for (std::size_t k = i + 1; k < c.instances.size(); ++k) c.queries.emplace_back(i, k);
  }
  return c;
}
}  // namespace

}  // namespace revdist
