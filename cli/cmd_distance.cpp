// `revdist distance CASE [--eps E] [--tol T] [--rel-tol R] [--engine fast|exact] [--json|--jsonl]`:
// the distance of every query of a case (SPEC sections 5 and 6). Results are written as
// they come (table rows, JSON records), so memory stays flat and a stopped run keeps
// what it finished; --json stays one valid document when SIGINT, SIGTERM or SIGHUP
// stops the run (it ends after the current query, marked "stopped").
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <stdexcept>
#include <algorithm>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>
#include <unistd.h>

#include "cli/commands.h"
#include "cli/output.h"
#include "core/case_io.h"
#include "core/case_scale.h"
#include "core/input_error.h"
#include "core/json_util.h"
#include "exact/solid_distance_exact.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"

namespace revdist::cli {

namespace {

using Json = nlohmann::json;

// A stop signal under --json (StopGuard below): the run ends after the query
// under way, which an exact query ends early, with the bracket proven so far.
std::atomic<int> g_stop{0};

struct Options {
  std::string file;
  double eps = 1e-5;  // default: 1e-5 * the model's unit (core/case_scale.h)
  double tol = 1e-6;  // default: 1e-6 * the model's unit
  double rel_tol = 0.0;
  bool eps_given = false, tol_given = false;
  std::string engine = "fast";
  bool json = false;
  bool jsonl = false;
};

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

// One query's answer, whichever engine gave it.
struct Answer {
  Json json;  // the result record of SPEC section 5
  double lower = 0, upper = 0, gap = 0;
  bool overlap = false, converged = false;
  std::string reason;
  long work = 0;
};

// Every exit-0 answer holds a finite bracket (issue 10 item 15): an engine that ends
// without one says so in the record, and the run exits 1 at the end.
void require_finite(Answer& a) {
  if (std::isfinite(a.lower) && std::isfinite(a.upper) && a.lower <= a.upper) return;
  a.converged = false;
  a.reason = "no finite bracket" + (a.reason.empty() ? std::string() : ": " + a.reason);
  a.json["converged"] = false;
  a.json["reason"] = a.reason;
}

// The fast engine: biarc trees at eps, then the traversal per query.
class FastEngine {
 public:
  FastEngine(const Case& c, const Options& o) : c_(c), model_(build_case_model(c, o.eps)) {
    opt_.tol = o.tol;
    opt_.rel_tol = o.rel_tol;
  }
  Answer query(std::size_t ia, std::size_t ib) const {
    const auto t0 = std::chrono::steady_clock::now();
    const SolidDistanceResult r = solid_distance(model_.instances[ia], model_.instances[ib], opt_);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    Answer a;
    a.json = {{"a", c_.instances[ia].name},      {"b", c_.instances[ib].name},
              {"lower", r.lower},                {"upper", r.upper},
              {"distance", r.distance},          {"overlap", r.overlap},
              {"converged", r.converged},        {"point_a", vec_json(r.point_a)},
              {"point_b", vec_json(r.point_b)},
              {"stats", {{"node_pairs", r.stats.node_pairs},
                         {"leaf_pairs", r.stats.leaf_pairs},
                         {"patch_pairs", r.stats.patch_pairs},
                         {"quick_pairs", r.stats.quick_pairs},
                         {"local_pairs", r.stats.local_pairs},
                         {"refined_parts", r.stats.refined},
                         {"time_us", us}}}};
    if (!r.converged) a.json["reason"] = r.reason;
    a.lower = r.lower;
    a.upper = r.upper;
    a.gap = (r.point_a - r.point_b).norm();
    a.overlap = r.overlap;
    a.converged = r.converged;
    a.reason = r.reason;
    a.work = r.stats.node_pairs;
    require_finite(a);
    return a;
  }

 private:
  const Case& c_;
  CaseModel model_;
  DistanceOptions opt_;
};

// The certified engine (exact/solid_distance_exact.h) works on the input
// curves themselves (no biarc trees, so --eps does not apply): lower/upper are
// doubles rounded outward from a proven interval; "converged" means
// upper - lower <= tol (or <= rel_tol * lower), tol = --tol, or 1e-9 x the query's
// scale when not given.
// stats keeps fast's keys with the exact engine's meaning: node_pairs = parameter
// boxes bounded, leaf_pairs = element pairs (profile element of a x of b),
// patch_pairs = element pairs searched by branch and bound, quick_pairs =
// element pairs settled in closed form (tube against tube), refined_parts =
// boxes re-bounded on MPFI near contact.
class ExactEngine {
 public:
  ExactEngine(const Case& c, const Options& o) : c_(c), o_(o) {
    if (o.tol_given) xo_.absolute_width = o.tol;
    xo_.relative_width = 1e-9;
    // A query too big for the engine (kMaxExactElementPairs) is refused
    // before any is answered, not after minutes or half the output.
    std::vector<long> elements(c.instances.size());
    for (std::size_t i = 0; i < c.instances.size(); ++i)
      elements[i] = exact_elements(profile_at(c.solids[c.instances[i].solid], c.instances[i].time));
    for (const auto& [ia, ib] : c.queries)
      if (elements[ia] * elements[ib] > kMaxExactElementPairs)
        throw InputError(o.file + ": query [" + quote(c.instances[ia].name) + ", " + quote(c.instances[ib].name) +
                         "]: " + std::to_string(elements[ia]) + " x " + std::to_string(elements[ib]) +
                         " profile elements (Bezier segments), more than the " + std::to_string(kMaxExactElementPairs) +
                         " element pairs the exact engine takes a query (the fast engine has no such limit)");
  }
  Answer query(std::size_t ia, std::size_t ib) const {
    const Instance& ins_a = c_.instances[ia];
    const Instance& ins_b = c_.instances[ib];
    const Profile pa = profile_at(c_.solids[ins_a.solid], ins_a.time);
    const Profile pb = profile_at(c_.solids[ins_b.solid], ins_b.time);
    ExactSolidOptions xo = xo_;
    // A query running past a second shows its bracket on stderr: plain lines
    // when stderr is not a terminal (logs), one rewritten line when it is.
    const bool tty = isatty(fileno(stderr));
    bool shown = false;
    const std::string na = printable(ins_a.name, 40), nb = printable(ins_b.name, 40);
    xo.progress = [&](const ExactProgress& p) {
      std::fprintf(stderr, "%sdistance %s-%s: %.1f s, %ld boxes, [%.17g, %.17g] width %.3g (target %.3g)%s",
                   tty ? "\r" : "", na.c_str(), nb.c_str(), p.seconds, p.boxes, p.lower, p.upper,
                   p.upper - p.lower, p.target_width, tty ? "" : "\n");
      std::fflush(stderr);
      shown = true;
    };
    xo.stop = [] { return g_stop.load() != 0; };
    const ExactSolidResult r = solid_distance_exact(pa, ins_a.pose, pb, ins_b.pose, xo);
    if (shown && tty) std::fprintf(stderr, "\n");
    const double tol = o_.tol_given ? o_.tol : 1e-9 * r.scale;
    const bool converged =
        r.certified && (r.upper - r.lower <= tol || r.upper - r.lower <= o_.rel_tol * r.lower);
    const double distance = r.certified ? 0.5 * r.lower + 0.5 * r.upper : r.upper;
    const double us = r.time_ms * 1e3;
    Answer a;
    a.json = {{"a", ins_a.name},
              {"b", ins_b.name},
              {"lower", r.lower},
              {"upper", r.certified ? Json(r.upper) : Json(nullptr)},
              {"distance", distance},
              {"overlap", r.overlap},
              {"converged", converged},
              {"certified", r.certified},
              {"tol", tol},
              {"scale", r.scale},
              {"point_a", vec_json(r.point_a)},
              {"point_b", vec_json(r.point_b)},
              {"stats", {{"node_pairs", r.boxes},
                         {"leaf_pairs", r.element_pairs},
                         {"patch_pairs", r.searched_pairs},
                         {"quick_pairs", r.closed_form_pairs},
                         {"refined_parts", r.mpfi_boxes},
                         {"boxes", r.boxes},
                         {"mpfi_boxes", r.mpfi_boxes},
                         {"closed_form_pairs", r.closed_form_pairs},
                         {"time_us", us}}}};
    if (!r.reason.empty()) a.json["reason"] = r.reason;
    a.lower = r.lower;
    a.upper = r.certified ? r.upper : std::numeric_limits<double>::infinity();
    a.gap = (r.point_a - r.point_b).norm();
    a.overlap = r.overlap;
    a.converged = converged;
    a.reason = r.reason;
    a.work = r.boxes;
    require_finite(a);
    return a;
  }

 private:
  const Case& c_;
  const Options& o_;
  ExactSolidOptions xo_;
};

// --json and a stop signal: the document is closed after the query under way
// (queries are budgeted, see SPEC 6), so a script reading the output still
// gets valid JSON with every finished result and "stopped": the signal's name.
// A second signal ends the run at once (the user insists; the document is then
// cut, as with SIGKILL). --jsonl and the table need nothing: every line is
// whole when it is written.
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void request_stop(int sig) {
  if (g_stop.exchange(sig) != 0) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  static const char msg[] =
      "revdist: stopping after the current query to close the JSON document (signal again to stop now)\n";
  const ssize_t ignored = ::write(2, msg, sizeof msg - 1);
  (void)ignored;
}

class StopGuard {
 public:
  explicit StopGuard(bool active) : active_(active) {
    if (!active_) return;
    struct sigaction sa {};
    sa.sa_handler = request_stop;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; ++i) sigaction(kStopSignals[i], &sa, &old_[i]);
  }
  ~StopGuard() { restore(); }
  void restore() {
    if (!active_) return;
    active_ = false;
    for (int i = 0; i < 3; ++i) sigaction(kStopSignals[i], &old_[i], nullptr);
  }

 private:
  bool active_;
  struct sigaction old_[3];
};

const char* signal_name(int sig) { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP"; }

// Table cells: the bracket rounded outward to as many digits as its width needs (at most
// 12; --json keeps every digit), so the printed bracket still holds the distance.
int bracket_digits(double lower, double upper) {
  const double w = upper - lower, m = std::max(std::abs(lower), std::abs(upper));
  if (!(w > 0) || !(m > 0) || !std::isfinite(w)) return 6;
  return std::clamp(static_cast<int>(std::ceil(std::log10(m / w))) + 2, 4, 12);
}

std::string pad(std::string s, std::size_t w) {
  if (s.size() < w) s += std::string(w - s.size(), ' ');
  return s;
}

template <class Engine>
void answer_all(const Case& c, const Engine& engine, const Options& o, const char* work_column) {
  const std::size_t n = c.queries.size();
  // Name columns as wide as the longest name, at most 16 (longer names are cut).
  std::size_t name_w = 1;
  for (const Instance& inst : c.instances) name_w = std::max(name_w, std::min<std::size_t>(printable(inst.name).size(), 16));
  auto check_stdout = [] {
    if (std::ferror(stdout)) throw RunError("error writing standard output");
  };
  if (o.json) {
    // exact without --tol: 1e-9 x each query's scale; the absolute one is in each record's "tol".
    const bool relative = o.engine == "exact" && !o.tol_given;
    std::printf("{\"format\": \"revdist-result/1\", \"engine\": %s, \"eps\": %s, \"tol\": %s,%s \"rel_tol\": %s,\n"
                " \"results\": [",
                Json(o.engine).dump().c_str(), Json(o.eps).dump().c_str(), Json(relative ? 1e-9 : o.tol).dump().c_str(),
                relative ? " \"tol_relative_to_scale\": true," : "", Json(o.rel_tol).dump().c_str());
  } else if (!o.jsonl) {
    // Times and full digits are in --json; the table keeps what a reader needs.
    std::printf("%s  %s  %-15s  %-15s  %-7s  %-12s  %7s  %s\n", pad("a", name_w).c_str(), pad("b", name_w).c_str(),
                "lower", "upper", "width", "witness_gap", work_column, "status");
  }
  std::fflush(stdout);
  StopGuard stop_guard(o.json);
  Progress progress("distance", n);
  long unbracketed = 0;
  std::size_t done = 0;
  for (std::size_t q = 0; q < n && g_stop.load() == 0; ++q) {
    Answer a;
    try {
      a = engine.query(c.queries[q].first, c.queries[q].second);
    } catch (const std::exception& e) {
      // A query that fails (out of memory) still leaves a whole document:
      // the finished records and the error, as a stopped run does.
      if (o.json) std::printf("%s], \"error\": %s}\n", done == 0 ? "" : "\n ", Json(e.what()).dump().c_str());
      std::fflush(stdout);
      throw;
    }
    ++done;
    unbracketed += !(std::isfinite(a.upper) && std::isfinite(a.lower));
    if (o.json) {
      std::printf("%s\n  %s", q == 0 ? "" : ",", a.json.dump().c_str());
    } else if (o.jsonl) {
      std::printf("%s\n", a.json.dump().c_str());
    } else {
      const int k = bracket_digits(a.lower, a.upper);
      const std::string status =
          a.overlap ? "overlap" : a.converged ? "ok" : "NOT converged: " + printable(a.reason, 200);
      std::printf("%s  %s  %-15s  %-15s  %-7s  %-12s  %7ld  %s\n",
                  pad(printable(c.instances[c.queries[q].first].name, name_w), name_w).c_str(),
                  pad(printable(c.instances[c.queries[q].second].name, name_w), name_w).c_str(),
                  digits_down(a.lower, k).c_str(), digits_up(a.upper, k).c_str(),
                  digits_up(a.upper - a.lower, 2).c_str(), fixed_digits(a.gap, std::min(k, 7)).c_str(), a.work,
                  status.c_str());
    }
    // Flushed per record: a stopped run keeps every finished query.
    std::fflush(stdout);
    check_stdout();
    progress.update(q + 1);
  }
  progress.finish();
  const int stopped = g_stop.load();
  if (o.json && stopped != 0) {
    std::printf("%s], \"stopped\": \"%s\"}\n", done == 0 ? "" : "\n ", signal_name(stopped));
    std::fflush(stdout);
    // Die of the signal, as the shell and a parent process expect.
    stop_guard.restore();
    std::signal(stopped, SIG_DFL);
    std::raise(stopped);
  }
  if (o.json) std::printf("%s]}\n", n == 0 ? "" : "\n ");
  std::fflush(stdout);
  check_stdout();
  if (unbracketed > 0)
    throw RunError(std::to_string(unbracketed) + " of " + std::to_string(n) +
                   " queries ended without a finite bracket (see their reason)");
}

// eps and tol are absolute lengths. Unset, they scale with the model (core/case_scale.h);
// set, they must be finite, positive and above what double rounding can resolve here.
void settle_tolerances(const Case& c, Options& o) {
  const CaseScale s = case_scale(c);
  const double unit = default_unit(s);
  if (!o.eps_given) o.eps = std::max(1e-5 * unit, min_eps(s));
  if (!o.tol_given) o.tol = o.rel_tol > 0 ? min_tol(s) : std::max(1e-6 * unit, min_tol(s));
  if (o.eps_given) require_resolvable_eps(o.eps, s.extent, c.file);
  if (o.tol_given) require_resolvable_tol(o.tol, s.query_extent, c.file);
}

void check_option(double v, const char* name, bool allow_zero) {
  if (!std::isfinite(v) || v < 0 || (v == 0 && !allow_zero))
    throw InputError(std::string(name) + " must be a finite " + (allow_zero ? "non-negative" : "positive") +
                     " number, got " + fixed_digits(v, 6));
}

void run(Options o) {
  if (o.eps_given) check_option(o.eps, "--eps", false);
  if (o.tol_given) check_option(o.tol, "--tol", false);
  check_option(o.rel_tol, "--rel-tol", true);
  if (o.rel_tol >= 1) throw InputError("--rel-tol must be below 1 (a fraction of the distance), got " + fixed_digits(o.rel_tol, 6));
  if (o.json && o.jsonl) throw InputError("--json and --jsonl exclude each other");
  const Case c = read_case(o.file);
  settle_tolerances(c, o);
  if (o.engine == "exact") {
    answer_all(c, ExactEngine(c, o), o, "boxes");
  } else {
    answer_all(c, FastEngine(c, o), o, "pairs");
  }
}

}  // namespace

void add_distance_command(CLI::App& app) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("distance", "Minimum distance for every query of a revdist/1 case");
  cmd->add_option("CASE", opts->file, "revdist/1 JSON case")->required();
  CLI::Option* eps = cmd->add_option(
      "--eps", opts->eps,
      "biarc approximation bound (proven), an absolute length in the case's units; default 1e-5, times the "
      "largest profile size when that lies outside [0.01, 100]; at least 1e-12 of the largest solid extent");
  CLI::Option* tol = cmd->add_option(
      "--tol", opts->tol,
      "stop when upper - lower <= tol, an absolute length; default 1e-6, scaled like --eps (with --rel-tol "
      "alone: the smallest meaningful tol; exact engine: 1e-9 x the query's scale); at least 2e-13 of "
      "|translation| + solid extent");
  cmd->add_option("--rel-tol", opts->rel_tol,
                  "also stop when upper - lower <= rel-tol * lower (digits rather than units); 0 = off");
  cmd->add_option("--engine", opts->engine, "fast (double) or exact (certified)")
      ->check(CLI::IsMember({"fast", "exact"}));
  cmd->add_flag("--json", opts->json,
                "machine-readable JSON (revdist-result/1), written as results come; SIGINT/SIGTERM/SIGHUP end it "
                "after the current query with a valid document marked \"stopped\"");
  cmd->add_flag("--jsonl", opts->jsonl, "one JSON result record per line (streams; a stopped run keeps its lines)");
  cmd->callback([opts, eps, tol] {
    Options o = *opts;
    o.eps_given = eps->count() > 0;
    o.tol_given = tol->count() > 0;
    run(o);
  });
}

}  // namespace revdist::cli
