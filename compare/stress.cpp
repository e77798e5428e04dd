// Running the stress families: every case checked against its closed form, the
// brute force on the true surfaces and (on a sample) the certified engine; per
// family counts and worst errors; shard-exact JSON and merging.
#include "compare/stress.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "compare/brute_force.h"
#include "compare/run_info.h"
#include "compare/thread_clock.h"
#include "core/case_io.h"
#include "exact/circle_distance_exact.h"
#include "exact/solid_distance_exact.h"
#include "fast/case_model.h"

namespace revdist {

namespace {

using Json = nlohmann::json;
constexpr double kEpsMachine = std::numeric_limits<double>::epsilon();

// What one case showed.
struct Outcome {
  bool nan = false;
  bool not_converged = false;
  std::string reason;  // the query's, when it did not converge
  std::map<std::string, double> violations;  // kind -> margin / scale
  double abs_error = 0.0, rel_error = 0.0;
  bool exact_checked = false, exact_uncertified = false, brute_checked = false, expected_checked = false;
  std::string what;
  void violate(const std::string& kind, double margin_rel) {
    double& v = violations[kind];
    v = std::max(v, margin_rel);
  }
};

bool finite(const Vec3& v) { return v.allFinite(); }

// Bracket [lo, hi] against a reference interval [rlo, rhi] that holds the distance.
void check_bracket(Outcome* o, double lo, double hi, double rlo, double rhi, double allow, double scale,
                   const char* above, const char* below) {
  if (lo > rhi + allow) o->violate(above, (lo - rhi) / scale);
  if (hi < rlo - allow) o->violate(below, (rlo - hi) / scale);
}

void record_error(Outcome* o, double distance, double reference, double tol) {
  o->abs_error = std::abs(distance - reference);
  o->rel_error = o->abs_error / std::max(reference, tol);
}

Outcome check_solid(const StressCase& c, const StressOptions& opt, const StressEngines& engines) {
  Outcome o;
  const Case& cs = c.solids;
  double size = 0.0;
  std::vector<Profile> blended;
  for (const Instance& ins : cs.instances) blended.push_back(profile_at(cs.solids[ins.solid], ins.time));
  std::vector<std::unique_ptr<ProfileNearest>> near;
  for (const Profile& p : blended) {
    near.push_back(std::make_unique<ProfileNearest>(p, 128));
    size = std::max(size, near.back()->size());
  }
  const double eps = opt.eps * size, tol = opt.tol * size;
  const CaseModel model = build_case_model(cs, eps);
  const PosedSolid& A = model.instances[0];
  const PosedSolid& B = model.instances[1];
  const double scale = std::max({size, A.t.cwiseAbs().maxCoeff(), B.t.cwiseAbs().maxCoeff()});
  // Rounding of the world transforms and of the bracket arithmetic (as tests/fast/solid_stress_test).
  const double allow = 1e-12 * scale;
  DistanceOptions dopt;
  dopt.tol = tol;
  const SolidDistanceResult r = engines.solid(A, B, dopt);
  if (!std::isfinite(r.lower) || !std::isfinite(r.upper) || !std::isfinite(r.distance) || !finite(r.point_a) ||
      !finite(r.point_b)) {
    o.nan = true;
    return o;
  }
  o.not_converged = !r.converged;
  if (o.not_converged) o.reason = r.reason;
  if (r.lower > r.upper + allow || r.lower < 0 || r.distance < r.lower - allow || r.distance > r.upper + allow)
    o.violate("inconsistent", std::max(r.lower - r.upper, 0.0) / scale);
  if (r.converged && r.upper - r.lower > tol + allow) o.violate("width_over_tol", (r.upper - r.lower - tol) / scale);

  // Witnesses: genuine points of the true surfaces (SPEC 6: within eps), as far apart as the bracket says.
  const PosedProfile pa{near[0].get(), A.R, A.t}, pb{near[1].get(), B.R, B.t};
  if (!r.overlap) {
    const double off = std::max(pa.surface_distance(r.point_a), pb.surface_distance(r.point_b));
    if (off > eps + allow) o.violate("witness_off", off / scale);
    const double w = (r.point_a - r.point_b).norm();
    if (w < r.lower - allow || w > r.upper + allow)
      o.violate("witness_off", std::max(r.lower - w, w - r.upper) / scale);
  }

  double reference = std::numeric_limits<double>::quiet_NaN();
  if (std::isfinite(c.expected)) {
    // The construction's distance, to the rounding of the mirrored pose (a few ulps of scale).
    o.expected_checked = true;
    check_bracket(&o, r.lower, r.upper, c.expected, c.expected, allow, scale, "lower_above_reference",
                  "upper_below_reference");
    reference = c.expected;
  }
  if (opt.exact_every > 0 && c.index % opt.exact_every == 0) {
    ExactSolidOptions xo;
    xo.max_boxes = opt.exact_max_boxes;
    xo.absolute_width = tol;  // fast's bracket is that wide; a disjoint interval is what matters
    const Instance& ia = cs.instances[0];
    const Instance& ib = cs.instances[1];
    const ExactSolidResult x = solid_distance_exact(blended[0], ia.pose, blended[1], ib.pose, xo);
    if (x.certified) {
      o.exact_checked = true;
      check_bracket(&o, r.lower, r.upper, x.lower, x.upper, allow, scale, "exact_disjoint", "exact_disjoint");
      if (!std::isfinite(reference)) reference = 0.5 * (x.lower + x.upper);
    } else {
      o.exact_uncertified = true;
    }
  }
  const BruteResult b = brute_surface_distance(pa, pb, 16, 32, 4);
  o.brute_checked = true;
  // Genuine surface points: an upper bound of the solid distance, whatever the nesting.
  if (r.lower > b.distance + allow) o.violate("lower_above_brute", (r.lower - b.distance) / scale);
  if (!std::isfinite(reference)) reference = b.distance;
  record_error(&o, r.distance, reference, tol);
  char buf[400];
  std::snprintf(buf, sizeof buf, "fast [%.17g, %.17g] overlap=%d converged=%d; expected %.17g; brute %.17g", r.lower,
                r.upper, r.overlap, r.converged, c.expected, b.distance);
  o.what = buf;
  return o;
}

double point_circle_distance(const Vec3& p, const Circle3& c) {
  const Vec3 n = c.normal.normalized(), d = p - c.center;
  const double h = n.dot(d), rho = (d - h * n).norm();
  return std::hypot(h, rho - c.radius);
}

// Genuine pairs on both circles: points of b at n angles, measured exactly
// against a, the best refined by golden section.
double circle_brute(const Circle3& a, const Circle3& b) {
  const Vec3 n = b.normal.normalized();
  const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  auto at = [&](double t) { return point_circle_distance(b.center + b.radius * (std::cos(t) * u + std::sin(t) * v), a); };
  const int m = b.radius > 0 ? 720 : 1;
  double best = INFINITY, bt = 0;
  for (int i = 0; i < m; ++i) {
    const double t = 2 * M_PI * i / m, d = at(t);
    if (d < best) best = d, bt = t;
  }
  if (m > 1) {
    double lo = bt - 2 * M_PI / m, hi = bt + 2 * M_PI / m;
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    for (int it = 0; it < 80; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      const double f1 = at(x1), f2 = at(x2);
      best = std::min({best, f1, f2});
      if (f1 < f2) hi = x2; else lo = x1;
    }
  }
  return best;
}

Outcome check_circle(const StressCase& c, const StressOptions& opt, const StressEngines& engines) {
  Outcome o;
  const double scale = std::max({c.a.radius, c.b.radius, (c.a.center - c.b.center).norm(),
                                 c.a.center.cwiseAbs().maxCoeff(), c.b.center.cwiseAbs().maxCoeff(), 1e-300});
  const Circle3Circle3Result r = engines.circle(c.a, c.b);
  if (!std::isfinite(r.distance) || !finite(r.point_a) || !finite(r.point_b)) {
    o.nan = true;
    return o;
  }
  // The bracket the circle engine claims (cli/cmd_circles.cpp): 64 ulps of the pair's scale.
  const double pair_scale = std::max({c.a.radius, c.b.radius, (c.a.center - c.b.center).norm()});
  const double slack = 64 * kEpsMachine * pair_scale;
  const double lo = std::max(0.0, r.distance - slack), hi = r.distance + slack;
  const double allow = 64 * kEpsMachine * scale;  // rounding of centres far from the origin
  const double on = std::max(point_circle_distance(r.point_a, c.a), point_circle_distance(r.point_b, c.b));
  if (on > 1e-12 * scale) o.violate("witness_off", on / scale);
  const double w = (r.point_a - r.point_b).norm();
  if (std::abs(w - r.distance) > slack + allow) o.violate("witness_off", std::abs(w - r.distance) / scale);
  double reference = std::numeric_limits<double>::quiet_NaN();
  if (std::isfinite(c.expected)) {
    o.expected_checked = true;
    // Closed forms hold before the rigid motion rounds the inputs (circle_families.h): 1e-10 x scale, its target.
    check_bracket(&o, lo, hi, c.expected, c.expected, 1e-10 * scale, scale, "lower_above_reference",
                  "upper_below_reference");
    reference = c.expected;
  }
  if (opt.circle_exact_every > 0 && c.index % opt.circle_exact_every == 0) {
    const ExactCircleResult x = circle3_circle3_distance_exact(c.a, c.b);
    if (x.status != ExactStatus::not_certified) {
      o.exact_checked = true;
      check_bracket(&o, lo, hi, x.lower, x.upper, allow, scale, "exact_disjoint", "exact_disjoint");
      reference = 0.5 * (x.lower + x.upper);  // the proven value beats the closed form of the unrounded input
    } else {
      o.exact_uncertified = true;
    }
  }
  const double b = circle_brute(c.a, c.b);
  o.brute_checked = true;
  if (lo > b + allow) o.violate("lower_above_brute", (lo - b) / scale);
  if (!std::isfinite(reference)) reference = b;
  // Relative to the pair's scale: the circle kernel's accuracy target is k eps scale, and many pairs touch.
  o.abs_error = std::abs(r.distance - reference);
  o.rel_error = o.abs_error / std::max(pair_scale, 1e-300);
  char buf[300];
  std::snprintf(buf, sizeof buf, "fast %.17g; expected %.17g; brute %.17g", r.distance, c.expected, b);
  o.what = buf;
  return o;
}

// Worst first: any violation beats any error; then the larger score; then the lower index.
bool worse(bool va, double sa, long ia, bool vb, double sb, long ib) {
  if (va != vb) return va;
  if (sa != sb) return sa > sb;
  return ia < ib;
}

// Adds a case to the family's list of unconverged ones, which keeps the
// lowest indices (shards merge to the unsharded run's list).
void list_unconverged(std::vector<FamilyStats::Unconverged>* list, FamilyStats::Unconverged u) {
  auto at = std::lower_bound(list->begin(), list->end(), u.index,
                             [](const FamilyStats::Unconverged& x, long i) { return x.index < i; });
  if (at != list->end() && at->index == u.index) return;
  list->insert(at, std::move(u));
  if (list->size() > kListedUnconverged) list->pop_back();
}

void add_outcome(FamilyStats* f, const StressCase& c, const Outcome& o) {
  if (o.not_converged && (f->unconverged.size() < kListedUnconverged || c.index < f->unconverged.back().index))
    list_unconverged(&f->unconverged, {c.index, o.reason + "; " + o.what + (c.note.empty() ? "" : "; " + c.note),
                                       stress_case_json(c)});
  ++f->n;
  f->nans += o.nan;
  f->not_converged += o.not_converged;
  f->violations += !o.violations.empty();
  for (const auto& [k, v] : o.violations) ++f->kinds[k];
  f->max_abs_error = std::max(f->max_abs_error, o.abs_error);
  f->max_rel_error = std::max(f->max_rel_error, o.rel_error);
  f->exact_checked += o.exact_checked;
  f->exact_uncertified += o.exact_uncertified;
  f->brute_checked += o.brute_checked;
  f->expected_checked += o.expected_checked;
  const bool v = !o.violations.empty() || o.nan;
  double score = o.rel_error;
  for (const auto& [k, m] : o.violations) score = std::max(score, m);
  if (o.nan) score = INFINITY;
  if (f->worst_index < 0 || worse(v, score, c.index, f->worst_violation, f->worst_score, f->worst_index)) {
    f->worst_violation = v;
    f->worst_score = score;
    f->worst_index = c.index;
    std::string kinds;
    for (const auto& [k, m] : o.violations) kinds += (kinds.empty() ? "" : ",") + k;
    f->worst_what = (o.nan ? std::string("NaN; ") : "") + (kinds.empty() ? "" : "violations " + kinds + "; ") + o.what +
                    (c.note.empty() ? "" : "; " + c.note);
    f->worst_case = stress_case_json(c);
  }
}

Json profile_json(const Profile& p) {
  Json pieces = Json::array();
  auto pts = [](const std::vector<Vec2>& v) {
    Json a = Json::array();
    for (const Vec2& q : v) a.push_back({q.x(), q.y()});
    return a;
  };
  for (const Piece& piece : p.pieces) {
    switch (piece.kind) {
      case PieceKind::line: pieces.push_back({{"line", pts(piece.points)}}); break;
      case PieceKind::arc: pieces.push_back({{"arc", pts(piece.points)}}); break;
      case PieceKind::bezier: {
        Json j{{"bezier", pts(piece.points)}};
        if (!piece.weights.empty()) j["weights"] = piece.weights;
        pieces.push_back(j);
        break;
      }
      case PieceKind::bspline: {
        Json b{{"degree", piece.degree}, {"knots", piece.knots}, {"points", pts(piece.points)}};
        if (!piece.weights.empty()) b["weights"] = piece.weights;
        pieces.push_back({{"bspline", b}});
        break;
      }
    }
  }
  return pieces;
}

Json circle_json(const Circle3& c) {
  return {{"center", {c.center.x(), c.center.y(), c.center.z()}},
          {"normal", {c.normal.x(), c.normal.y(), c.normal.z()}},
          {"radius", c.radius}};
}

}  // namespace

Json stress_case_json(const StressCase& c) {
  const std::string comment = "stress family " + c.family + ", case " + std::to_string(c.index) +
                              (c.note.empty() ? "" : ": " + c.note);
  if (c.is_circle) {
    Json pair{{"a", circle_json(c.a)}, {"b", circle_json(c.b)}};
    if (std::isfinite(c.expected)) pair["expected"] = c.expected;
    return {{"format", "revdist-circles/1"}, {"comment", comment}, {"pairs", Json::array({pair})}};
  }
  Json solids = Json::object();
  for (const SolidDef& s : c.solids.solids) {
    if (s.keyframes.size() == 1) {
      solids[s.name] = {{"profile", profile_json(s.keyframes[0])}};
    } else {
      Json k = Json::array();
      for (const Profile& p : s.keyframes) k.push_back(profile_json(p));
      solids[s.name] = {{"keyframes", k}};
    }
  }
  Json instances = Json::array();
  for (const Instance& ins : c.solids.instances) {
    Json i{{"name", ins.name},
           {"solid", c.solids.solids[ins.solid].name},
           {"rotation", ins.pose.q},
           {"translation", {ins.pose.translation.x(), ins.pose.translation.y(), ins.pose.translation.z()}}};
    if (c.solids.solids[ins.solid].deformable()) i["time"] = ins.time;
    instances.push_back(i);
  }
  Json out{{"format", "revdist/1"}, {"comment", comment}, {"solids", solids}, {"instances", instances},
           {"queries", Json::array({Json::array({"a", "b"})})}};
  if (std::isfinite(c.expected)) out["expected"] = c.expected;
  return out;
}

StressReport run_stress(const std::vector<std::string>& families, long n, std::uint64_t seed, int shard_k, int shard_m,
                        const StressOptions& options, const StressEngines& engines,
                        const std::function<void(long, long)>& progress) {
  StressReport rep;
  rep.seed = seed;
  rep.n = n;
  rep.shard_k = shard_k;
  rep.shard_m = shard_m;
  rep.options = options;
  long total = 0;
  for (long i = 0; i < n; ++i) total += i % shard_m == shard_k - 1;
  total *= static_cast<long>(families.size());
  long done = 0;
  for (const std::string& name : families) {
    FamilyStats f;
    f.name = name;
    f.circle = name.rfind("circle_", 0) == 0;
    const double t0 = 1e-6 * thread_cpu_us();
    for (long i = shard_k - 1; i < n; i += shard_m) {
      const StressCase c = make_stress_case(name, i, seed);
      add_outcome(&f, c, c.is_circle ? check_circle(c, options, engines) : check_solid(c, options, engines));
      if (progress) progress(++done, total);
    }
    f.time_s = 1e-6 * thread_cpu_us() - t0;
    rep.families.push_back(std::move(f));
  }
  return rep;
}

Json stress_json(const StressReport& r) {
  Json fams = Json::array();
  long total_n = 0, total_v = 0, total_nan = 0, total_nc = 0, total_x = 0, total_xu = 0;
  double total_t = 0;
  for (const FamilyStats& f : r.families) {
    Json kinds = Json::object();
    for (const auto& [k, v] : f.kinds) kinds[k] = v;
    Json unconverged = Json::array();
    for (const FamilyStats::Unconverged& u : f.unconverged)
      unconverged.push_back({{"index", u.index}, {"what", u.what}, {"case", u.case_json}});
    fams.push_back({{"name", f.name},
                    {"kind", f.circle ? "circle" : "solid"},
                    {"n", f.n},
                    {"violations", f.violations},
                    {"max_abs_error", f.max_abs_error},
                    {"max_rel_error", f.max_rel_error},
                    {"nans", f.nans},
                    {"not_converged", f.not_converged},
                    {"not_converged_cases", unconverged},
                    {"time_s", f.time_s},
                    {"exact_checked", f.exact_checked},
                    {"exact_uncertified", f.exact_uncertified},
                    {"brute_checked", f.brute_checked},
                    {"expected_checked", f.expected_checked},
                    {"violation_kinds", kinds},
                    {"worst", {{"index", f.worst_index},
                               {"violation", f.worst_violation},
                               {"score", f.worst_score},
                               {"what", f.worst_what},
                               {"case", f.worst_case}}}});
    total_n += f.n, total_v += f.violations, total_nan += f.nans, total_nc += f.not_converged;
    total_x += f.exact_checked, total_xu += f.exact_uncertified, total_t += f.time_s;
  }
  return {{"format", "revdist-stress/1"},
          {"seed", r.seed},
          {"n", r.n},
          {"shard", std::to_string(r.shard_k) + "/" + std::to_string(r.shard_m)},
          {"eps", r.options.eps},
          {"tol", r.options.tol},
          {"exact_every", r.options.exact_every},
          {"exact_max_boxes", r.options.exact_max_boxes},
          {"circle_exact_every", r.options.circle_exact_every},
          {"references",
           "every case: the construction's closed form where it has one (mirror pairs, tube pairs, circle families), and "
           "the brute force on the true surfaces (genuine points: lower must not exceed it); solid cases with index % "
           "exact_every == 0 and circle cases with index % circle_exact_every == 0: the certified exact/ interval. "
           "eps and tol are relative to each case's size. Errors are |distance - reference|, reference = closed form, "
           "else exact midpoint, else brute force; relative over max(reference, tol) for solids, over the pair's scale "
           "max(radii, centre distance) for circles."},
          {"run", run_info()},
          {"totals", {{"n", total_n}, {"violations", total_v}, {"nans", total_nan}, {"not_converged", total_nc},
                      {"exact_checked", total_x}, {"exact_uncertified", total_xu}, {"time_s", total_t}}},
          {"families", fams}};
}

StressReport stress_from_json(const Json& j) {
  // Counts are integers in [0, 1e12] (a shard claiming -5 violations, n = 1.5 or
  // 2^62 was merged before).
  auto count = [](const Json& v, const std::string& what) {
    if (!v.is_number_integer() || v.get<double>() < 0 || v.get<double>() > 1e12)
      throw std::runtime_error(what + " must be an integer in [0, 1e12], got " + v.dump().substr(0, 40));
    return v.get<long>();
  };
  try {
    if (j.at("format") != "revdist-stress/1") throw std::runtime_error("not a revdist-stress/1 record");
    StressReport r;
    r.seed = j.at("seed").get<std::uint64_t>();
    r.n = count(j.at("n"), "n");
    const std::string shard = j.at("shard").get<std::string>();
    int used = 0;
    if (std::sscanf(shard.c_str(), "%d/%d%n", &r.shard_k, &r.shard_m, &used) != 2 ||
        used != static_cast<int>(shard.size()) || r.shard_k < 1 || r.shard_k > r.shard_m || r.shard_m > 100000)
      throw std::runtime_error("bad shard \"" + shard.substr(0, 40) + "\" (K/M with 1 <= K <= M)");
    r.options.eps = j.at("eps").get<double>();
    r.options.tol = j.at("tol").get<double>();
    r.options.exact_every = j.at("exact_every").get<int>();
    r.options.exact_max_boxes = j.at("exact_max_boxes").get<long>();
    r.options.circle_exact_every = j.at("circle_exact_every").get<int>();
    for (const Json& fj : j.at("families")) {
      FamilyStats f;
      f.name = fj.at("name").get<std::string>();
      f.circle = fj.at("kind") == "circle";
      f.n = count(fj.at("n"), f.name + " n");
      f.violations = count(fj.at("violations"), f.name + " violations");
      f.max_abs_error = fj.at("max_abs_error").get<double>();
      f.max_rel_error = fj.at("max_rel_error").get<double>();
      f.nans = count(fj.at("nans"), f.name + " nans");
      f.not_converged = count(fj.at("not_converged"), f.name + " not_converged");
      f.time_s = fj.at("time_s").get<double>();
      f.exact_checked = count(fj.at("exact_checked"), f.name + " exact_checked");
      f.exact_uncertified = count(fj.at("exact_uncertified"), f.name + " exact_uncertified");
      f.brute_checked = count(fj.at("brute_checked"), f.name + " brute_checked");
      f.expected_checked = count(fj.at("expected_checked"), f.name + " expected_checked");
      for (const auto& [k, v] : fj.at("violation_kinds").items()) f.kinds[k] = count(v, f.name + " " + k);
      if (f.violations > f.n || f.nans > f.n || f.not_converged > f.n)
        throw std::runtime_error(f.name + ": more violations, NaNs or unconverged cases than cases");
      const Json& w = fj.at("worst");
      f.worst_index = w.at("index").get<long>();
      f.worst_violation = w.at("violation").get<bool>();
      // A NaN case scores +inf, which JSON writes as null.
      f.worst_score = w.at("score").is_null() ? INFINITY : w.at("score").get<double>();
      f.worst_what = w.at("what").get<std::string>();
      f.worst_case = w.at("case");
      // (Records written before the list was added have none.)
      if (fj.contains("not_converged_cases")) {
        for (const Json& u : fj.at("not_converged_cases")) {
          const long index = count(u.at("index"), f.name + " not_converged_cases index");
          if (!f.unconverged.empty() && index <= f.unconverged.back().index)
            throw std::runtime_error(f.name + ": not_converged_cases out of order");
          f.unconverged.push_back({index, u.at("what").get<std::string>(), u.at("case")});
        }
        if (f.unconverged.size() > kListedUnconverged ||
            static_cast<long>(f.unconverged.size()) > f.not_converged)
          throw std::runtime_error(f.name + ": more not_converged_cases than not_converged or than listed");
      }
      r.families.push_back(std::move(f));
    }
    return r;
  } catch (const Json::exception& e) {
    throw std::runtime_error(std::string("malformed revdist-stress/1 record: ") + e.what());
  }
}

StressReport merge_stress(const std::vector<StressReport>& shards) {
  if (shards.empty()) throw std::runtime_error("nothing to merge");
  const StressReport& first = shards[0];
  std::set<int> seen;
  for (const StressReport& s : shards) {
    if (s.seed != first.seed || s.n != first.n || s.shard_m != first.shard_m)
      throw std::runtime_error("shards of different runs (seed, n or shard count differ)");
    if (s.options.eps != first.options.eps || s.options.tol != first.options.tol ||
        s.options.exact_every != first.options.exact_every || s.options.exact_max_boxes != first.options.exact_max_boxes ||
        s.options.circle_exact_every != first.options.circle_exact_every)
      throw std::runtime_error("shards of different runs (options differ)");
    if (s.families.size() != first.families.size()) throw std::runtime_error("shards with different families");
    for (std::size_t i = 0; i < s.families.size(); ++i)
      if (s.families[i].name != first.families[i].name) throw std::runtime_error("shards with different families");
    if (!seen.insert(s.shard_k).second) throw std::runtime_error("shard " + std::to_string(s.shard_k) + " given twice");
  }
  if (static_cast<int>(seen.size()) != first.shard_m)
    throw std::runtime_error("missing shards: have " + std::to_string(seen.size()) + " of " + std::to_string(first.shard_m));
  StressReport out = first;
  out.shard_k = out.shard_m = 1;
  for (std::size_t s = 1; s < shards.size(); ++s) {
    for (std::size_t i = 0; i < out.families.size(); ++i) {
      FamilyStats& f = out.families[i];
      const FamilyStats& g = shards[s].families[i];
      f.n += g.n, f.violations += g.violations, f.nans += g.nans, f.not_converged += g.not_converged;
      f.exact_checked += g.exact_checked, f.exact_uncertified += g.exact_uncertified;
      f.brute_checked += g.brute_checked, f.expected_checked += g.expected_checked, f.time_s += g.time_s;
      f.max_abs_error = std::max(f.max_abs_error, g.max_abs_error);
      f.max_rel_error = std::max(f.max_rel_error, g.max_rel_error);
      for (const auto& [k, v] : g.kinds) f.kinds[k] += v;
      for (const FamilyStats::Unconverged& u : g.unconverged) list_unconverged(&f.unconverged, u);
      if (g.worst_index >= 0 &&
          (f.worst_index < 0 || worse(g.worst_violation, g.worst_score, g.worst_index, f.worst_violation,
                                      f.worst_score, f.worst_index))) {
        f.worst_violation = g.worst_violation, f.worst_score = g.worst_score, f.worst_index = g.worst_index;
        f.worst_what = g.worst_what, f.worst_case = g.worst_case;
      }
    }
  }
  return out;
}

}  // namespace revdist
