// `revdist scene CASE [--within D | --closest K | --nearest NAME] [--frames N] [--threads T] [--json]`:
// many instances, far pairs never touched (SPEC section 5, issue 8); and
// `revdist scene-gen rings|shelf`, the generator of scene cases.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/output.h"
#include "compare/scene_gen.h"
#include "core/case_io.h"
#include "core/case_scale.h"
#include "core/input_error.h"
#include "core/json_util.h"
#include "fast/scene/scene.h"

namespace revdist::cli {

namespace {

using Json = nlohmann::json;

struct Options {
  std::string file;
  double within = -1;  // < 0: not asked
  long closest = 0;    // 0: not asked
  std::string nearest;
  bool nearest_given = false;
  long frames = 1;
  int threads = 1;
  double eps = 1e-5;
  double tol = 1e-6;
  bool eps_given = false, tol_given = false;
  bool json = false;
  bool stats_only = false;
  bool no_coherence = false;
  bool lazy = false;
};

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json stats_json(const SceneStats& s) {
  return {{"instances", s.instances},        {"pairs_total", s.pairs_total},
          {"pairs_tested", s.pairs_tested},  {"pairs_culled", s.pairs_culled},
          {"pairs_threshold", s.pairs_threshold}, {"pairs_coherent", s.pairs_coherent},
          {"narrow_calls", s.narrow_calls},
          {"node_pairs", s.node_pairs},      {"nodes_built", s.nodes_built},
          {"broad_nodes", s.broad_nodes},    {"broad_rebuilt", s.broad_rebuilt},
          {"time_ms", s.time_ms},            {"cpu_ms", s.cpu_ms},
          {"serial_ms", s.serial_ms},        {"span_ms", s.span_ms}};
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(std::floor(p * static_cast<double>(v.size() - 1) + 0.5)))];
}

void run(Options o) {
  if (!(o.eps > 0) || !(o.tol > 0) || !std::isfinite(o.eps) || !std::isfinite(o.tol))
    throw InputError("--eps and --tol must be positive");
  const int asked = (o.within >= 0) + (o.closest > 0 && o.nearest.empty()) + !o.nearest.empty();
  if (asked > 1) throw InputError("ask one of --within, --closest, --nearest (with --closest K for K neighbours)");
  if (std::isnan(o.within) || (o.within >= 0 && !std::isfinite(o.within)))
    throw InputError("--within must be a finite distance >= 0");
  if (o.nearest_given && o.nearest.empty()) throw InputError("--nearest: empty instance name");
  const Case c = read_case(o.file, false);
  // As `distance`: unset, eps and tol scale with the model; set, fits and
  // brackets below what doubles resolve for this case are refused (its poses
  // at frame 0 set the queries' extent).
  const CaseScale scale = case_scale(c);
  if (!o.eps_given) o.eps = std::max(1e-5 * default_unit(scale), min_eps(scale));
  if (!o.tol_given) o.tol = std::max(1e-6 * default_unit(scale), min_tol(scale));
  require_resolvable_eps(o.eps, scale.extent, o.file);
  require_resolvable_tol(o.tol, scale.query_extent, o.file);
  // Every pose of every frame in the coordinates' range (core/case_io.cpp), from
  // the motion's terms: |translation(f)| <= |t| + F |v| + F^2 |a| / 2 + 2 |amplitude|.
  const double F = static_cast<double>(o.frames - 1);
  for (const Instance& ins : c.instances) {
    const InstanceMotion& m = ins.motion;
    const double reach = ins.pose.translation.norm() + F * m.velocity.norm() + 0.5 * F * F * m.acceleration.norm() +
                         2 * m.wave_amplitude.norm();
    if (!(reach <= kMaxMagnitude))
      throw InputError(o.file + ": instance " + quote(ins.name) + ": its motion leaves the supported range +-1e100 by frame " +
                       std::to_string(o.frames - 1));
  }
  std::size_t query_instance = 0;
  if (!o.nearest.empty()) {
    while (query_instance < c.instances.size() && c.instances[query_instance].name != o.nearest) ++query_instance;
    if (query_instance == c.instances.size())
      throw InputError(o.file + ": --nearest: unknown instance \"" + o.nearest + "\"");
  }
  const std::size_t k = static_cast<std::size_t>(std::max(1L, o.closest));
  const std::string kind = o.within >= 0 ? "within" : !o.nearest.empty() ? "nearest" : "closest";

  SceneOptions so;
  so.eps = o.eps;
  so.distance.tol = o.tol;
  so.threads = o.threads;
  so.coherence = !o.no_coherence;
  so.lazy_trees = o.lazy;
  const auto b0 = std::chrono::steady_clock::now();
  Scene scene(c, so);
  const double build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - b0).count();

  Json frames = Json::array();
  std::string text;
  SceneStats total;
  std::vector<double> frame_ms;
  Progress progress("scene", static_cast<std::size_t>(o.frames));  // output.h: after 1 s only
  std::vector<ScenePair> pairs;  // one vector for every frame: within() reuses its elements
  constexpr std::size_t kMaxRecords = 500000;
  std::size_t records = 0;
  for (long f = 0; f < o.frames; ++f) {
    SceneStats st;
    scene.set_frame(static_cast<double>(f), &st);
    // Every frame's pairs are kept until the end (one document): past
    // kMaxRecords, refused before anything is written (--within 100 on 60
    // spheres for 100000 frames aborted out of memory at 4 GB), and before a
    // frame's queries when its pairs certainly within D are too many.
    bool room = true;
    if (kind == "within") room = scene.within(o.within, &st, &pairs, o.stats_only ? SIZE_MAX : kMaxRecords - records);
    else pairs = kind == "nearest" ? scene.nearest(query_instance, k, &st) : scene.closest(k, &st);
    total.add(st);
    frame_ms.push_back(st.time_ms);
    records += o.stats_only ? 0 : pairs.size();
    if (!room || records > kMaxRecords)
      throw InputError("--frames " + std::to_string(o.frames) + ": more than " + std::to_string(kMaxRecords) +
                       " pair records by frame " + std::to_string(f) +
                       " (each frame's pairs are written); ask fewer frames or pairs, or --stats-only");
    Json pj = Json::array();
    Table table({"a", "b", "distance", "lower", "upper", "overlap", kind == "within" ? "within" : "converged"});
    if (!o.stats_only)
      for (const ScenePair& p : pairs) {
        const SolidDistanceResult& r = p.result;
        const std::string& na = c.instances[p.a].name;
        const std::string& nb = c.instances[p.b].name;
        if (o.json) {
          Json j{{"a", na}, {"b", nb}, {"lower", r.lower}, {"upper", r.upper}, {"distance", r.distance},
                 {"overlap", r.overlap}, {"converged", r.converged}, {"decided", r.decided},
                 {"point_a", vec_json(r.point_a)}, {"point_b", vec_json(r.point_b)}};
          if (kind == "within") j["within"] = p.within;
          pj.push_back(std::move(j));
        } else {
          table.add({na, nb, full(r.distance), full(r.lower), full(r.upper), r.overlap ? "yes" : "no",
                     kind == "within" ? (p.within ? "yes" : "undecided") : (r.converged ? "yes" : "no")});
        }
      }
    if (o.json) {
      frames.push_back({{"frame", f}, {"pairs", pj}, {"stats", stats_json(st)}});
    } else {
      char line[256];
      std::snprintf(line, sizeof line,
                    "frame %ld: %zu pairs; tested %ld of %ld, culled %ld, settled by threshold %ld, from the previous "
                    "frame %ld, nodes built %ld, %.3f ms (cpu %.3f ms)\n",
                    f, pairs.size(), st.pairs_tested, st.pairs_total, st.pairs_culled, st.pairs_threshold,
                    st.pairs_coherent, st.nodes_built, st.time_ms, st.cpu_ms);
      text += line;
      if (!o.stats_only && !pairs.empty()) text += table.str();
    }
    progress.update(static_cast<std::size_t>(f + 1));
  }
  progress.finish();
  const Json summary{{"frames", o.frames},
                     {"build_ms", build_ms},
                     {"frame_ms_median", percentile(frame_ms, 0.5)},
                     {"frame_ms_p90", percentile(frame_ms, 0.9)},
                     {"total", stats_json(total)}};
  if (o.json) {
    Json doc{{"format", "revdist-scene/1"}, {"query", kind}, {"eps", o.eps}, {"tol", o.tol}, {"threads", o.threads}};
    if (kind == "within") doc["within"] = o.within;
    else doc["k"] = k;
    if (kind == "nearest") doc["nearest"] = o.nearest;
    doc["pairs"] = frames[0]["pairs"];
    doc["stats"] = frames[0]["stats"];
    if (o.frames > 1) doc["frames"] = std::move(frames);
    doc["summary"] = summary;
    std::printf("%s\n", doc.dump(1).c_str());
  } else {
    std::printf("%s", text.c_str());
    std::printf("%ld frames, %zu instances: build %.3f ms, frame median %.3f ms, p90 %.3f ms (wall)\n", o.frames,
                scene.size(), build_ms, percentile(frame_ms, 0.5), percentile(frame_ms, 0.9));
  }
}

}  // namespace

void add_scene_command(CLI::App& app) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("scene", "Many instances: pairs within D, the K closest pairs, nearest neighbours");
  cmd->add_option("CASE", opts->file, "revdist/1 JSON case (instances may carry a \"motion\")")->required();
  cmd->add_option("--within", opts->within, "every pair at distance <= D")->check(finite_number(false));
  // (K = 10^9 on 2000 rings wrote 209 MB in 58 s; on 10000, std::bad_alloc.)
  cmd->add_option("--closest", opts->closest, "the K closest pairs (default: 1, the scene's minimum; at most 100000)")
      ->check(CLI::Range(1L, 100000L));
  CLI::Option* nearest = cmd->add_option("--nearest", opts->nearest, "the K (--closest) nearest instances to this one");
  cmd->add_option("--frames", opts->frames, "frames 0..N-1, instances moved by their motion (at most 100000)")
      ->check(CLI::Range(1L, 100000L))->capture_default_str();
  cmd->add_option("--threads", opts->threads, "worker threads (answers do not depend on it)")
      ->check(CLI::Range(1, 256))->capture_default_str();
  CLI::Option* eps = cmd->add_option("--eps", opts->eps, "biarc approximation bound (proven; default 1e-5 x the model's unit)");
  CLI::Option* tol = cmd->add_option("--tol", opts->tol, "stop when upper - lower <= tol (default 1e-6 x the model's unit)");
  cmd->add_flag("--json", opts->json, "machine-readable JSON (revdist-scene/1)");
  cmd->add_flag("--stats-only", opts->stats_only, "counters and times only, no pair list");
  cmd->add_flag("--no-coherence", opts->no_coherence,
                "--within: recompute every pair each frame instead of settling it from its previous frame");
  cmd->add_flag("--lazy", opts->lazy,
                "lazy biarc trees for deforming shapes (time_rate): nodes fitted when a query first reaches them");
  cmd->callback([opts, nearest, eps, tol] {
    opts->nearest_given = nearest->count() > 0;
    opts->eps_given = eps->count() > 0;
    opts->tol_given = tol->count() > 0;
    run(*opts);
  });
}

namespace {

struct GenOptions {
  std::string kind;
  int n = 1000;
  std::uint64_t seed = 1;
  std::string out;
};

}  // namespace

void add_scene_gen_command(CLI::App& app) {
  auto o = std::make_shared<GenOptions>();
  CLI::App* cmd = app.add_subcommand("scene-gen", "Generate a scene case: an interlocked ring mesh or a shelf");
  cmd->add_option("KIND", o->kind, "rings (paper Figure 1, in motion) or shelf (mixed solids)")
      ->required()->check(CLI::IsMember({"rings", "shelf"}));
  // (10^7 ran out of memory and aborted, 10^6 took 3.5 GB for a 483 MB file; 2 x 10^5
  // wrote 97 MB, past the 64 MiB every reader takes; 10^5: 48 MB, 0.45 GB and 1.3 s.)
  cmd->add_option("--n", o->n, "about this many instances")->check(CLI::Range(2, 100000))->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed (motions, shelf items)")
      ->check(seed_number(std::numeric_limits<std::uint64_t>::max()))->capture_default_str();
  cmd->add_option("--out", o->out, "output file (written whole or not at all); stdout when absent")
      ->check(non_empty_path());
  cmd->callback([o] {
    const nlohmann::json doc = o->kind == "rings" ? ring_mesh_case(o->n, o->seed) : shelf_case(o->n, o->seed);
    const std::string text = doc.dump(1) + "\n";
    if (o->out.empty()) std::fputs(text.c_str(), stdout);
    else write_file_atomically(o->out, text);
  });
}

}  // namespace revdist::cli
