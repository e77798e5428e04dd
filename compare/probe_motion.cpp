// Developer probe for the query's speed (issue 9): the paper's 15 pairs in the
// same near-contact motion as `revdist bench` (Figure 12), timed per query in
// thread CPU time with the work counters, on poses cached in a file so that two
// builds (or callgrind) see the same queries (by default
// /tmp/revdist_motion_poses_<frames>.bin, written by the first run). `--save F`
// / `--check F` write and compare the brackets (they must intersect) between
// builds.
// Usage: revdist_probe_motion [--eps E] [--tol T] [--frames N] [--poses FILE] [--bench-poses FILE]
//                             [--save FILE] [--check FILE] [--times FILE] [--repeat K]
//                             [--select LO,HI] [--only-overlap] [--index K] [--coherent] [--perfect-warm] [--worst K]
// --bench-poses FILE takes the frames of a `revdist bench paper --poses FILE`
// file (its pairs of the five static models, in its order) instead.
// --worst K lists the K slowest queries (frame, pair, target distance, time,
// bracket and work counters): where the tail comes from.
// --only-overlap restricts --select and --worst to the queries answered with
// a proven overlap (bracket [0, 0]); --index K to query K alone (the frame
// number --worst prints). --times FILE writes each query's time (us), one a
// line in frame order, to compare two builds query by query.
// --repeat K times each query K times and keeps its least time.
// --perfect-warm starts each query from its own answer (a cold query's, as
// a WarmStart): what a witness exact from the start would save.
// --coherent starts each query from the previous frame's answer of the same
// pair (WarmStart, frame coherence).
// --case K FILE writes frame K as a case file (the two models, their poses as
// quaternions [w, x, y, z] from the frame's rotations): a regression of it.
// --select re-runs the queries whose time ranks between quantiles LO and HI
// with callgrind's collection toggled on around each (run under
// `valgrind --tool=callgrind --collect-atstart=no`): the profile of, say, the
// median queries rather than of the tail.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#else
#define CALLGRIND_TOGGLE_COLLECT
#endif

#include "compare/bench_paper.h"
#include "compare/motion.h"
#include "compare/thread_clock.h"
#include "core/case_io.h"
#include "fast/biarc_tree.h"
#include "fast/solid_distance.h"

using namespace revdist;

namespace {

// One frame as stored: pair indices and the two poses (rotation, translation).
struct FramePose {
  int a, b;
  double target;
  double Ra[9], ta[3], Rb[9], tb[3];
};

struct Bracket {
  double lower, upper;
};

}  // namespace

int main(int argc, char** argv) {
  double eps = 1e-5, tol = -1;
  int frames = 40, repeat = 1, worst = 0;
  bool coherent = false, only_overlap = false, perfect = false;
  long only_index = -1;
  std::string bench_poses;  // a `revdist bench paper --poses` file: its static pairs' frames
  double sel_lo = -1, sel_hi = -1;
  std::string poses_file, save, check, times, case_file;
  long case_frame = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : "";
    if (a == "--eps") eps = atof(v), ++i;
    else if (a == "--tol") tol = atof(v), ++i;
    else if (a == "--frames") frames = atoi(v), ++i;
    else if (a == "--poses") poses_file = v, ++i;
    else if (a == "--bench-poses") bench_poses = v, ++i;
    else if (a == "--save") save = v, ++i;
    else if (a == "--times") times = v, ++i;
    else if (a == "--check") check = v, ++i;
    else if (a == "--repeat") repeat = atoi(v), ++i;
    else if (a == "--coherent") coherent = true;
    else if (a == "--perfect-warm") perfect = true;
    else if (a == "--only-overlap") only_overlap = true;
    else if (a == "--index") only_index = atol(v), ++i;
    else if (a == "--worst") worst = atoi(v), ++i;
    else if (a == "--case" && i + 2 < argc) case_frame = atol(v), case_file = argv[i + 2], i += 2;
    else if (a == "--select") {
      if (sscanf(v, "%lf,%lf", &sel_lo, &sel_hi) != 2) return 2;
      ++i;
    }
    else {
      fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  // The default cache holds one frame count: a cache of another count would
  // silently stand in for --frames.
  if (poses_file.empty()) poses_file = "/tmp/revdist_motion_poses_" + std::to_string(frames) + ".bin";
  if (tol < 0) tol = 2 * eps;
  const BenchInput in = paper_bench_input(default_models_dir());
  std::vector<Profile> profiles;
  for (const auto& s : in.statics) profiles.push_back(profile_at(s.def, 0.0));

  std::vector<FramePose> poses;
  if (!bench_poses.empty()) {
    std::string bytes;
    if (FILE* f = fopen(bench_poses.c_str(), "rb")) {
      char buf[1 << 16];
      for (std::size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) bytes.append(buf, n);
      fclose(f);
    }
    const BenchPoses bp = decode_bench_poses(bytes, bench_poses);
    auto index = [&](const std::string& name) {
      for (std::size_t k = 0; k < in.statics.size(); ++k)
        if (in.statics[k].name == name) return static_cast<int>(k);
      return -1;
    };
    for (const auto& [name, frames_of] : bp.pairs) {
      const std::size_t dash = name.find('-');
      const int ia = index(name.substr(0, dash)), ib = dash == std::string::npos ? -1 : index(name.substr(dash + 1));
      if (ia < 0 || ib < 0) continue;  // (pairs with the deformable model)
      for (const MotionFrame& f : frames_of) {
        FramePose p{ia, ib, f.target, {}, {}, {}, {}};
        std::memcpy(p.Ra, f.R_WA.data(), sizeof p.Ra), std::memcpy(p.ta, f.t_WA.data(), sizeof p.ta);
        std::memcpy(p.Rb, f.R_WB.data(), sizeof p.Rb), std::memcpy(p.tb, f.t_WB.data(), sizeof p.tb);
        poses.push_back(p);
      }
    }
  } else if (FILE* f = fopen(poses_file.c_str(), "rb")) {
    FramePose p;
    while (fread(&p, sizeof p, 1, f) == 1) poses.push_back(p);
    fclose(f);
  }
  if (poses.empty()) {
    double extent = INFINITY;
    for (const Profile& p : profiles) extent = std::min(extent, profile_extent(p));
    const double setup_eps = std::max(eps, 1e-4 * extent);
    std::vector<BiarcTree> fine;
    for (const Profile& p : profiles) fine.push_back(build_biarc_tree(p, setup_eps));
    MotionOptions mo;
    mo.frames = frames;
    std::uint64_t seed = 20200501;
    for (std::size_t i = 0; i < profiles.size(); ++i)
      for (std::size_t j = i; j < profiles.size(); ++j) {
        mo.seed = seed++;
        PosedSolid A{&profiles[i], &fine[i]}, B{&profiles[j], &fine[j]};
        for (const MotionFrame& f : near_contact_motion(A, [&](int) { return B; }, mo)) {
          FramePose p{static_cast<int>(i), static_cast<int>(j), f.target, {}, {}, {}, {}};
          std::memcpy(p.Ra, f.R_WA.data(), sizeof p.Ra), std::memcpy(p.ta, f.t_WA.data(), sizeof p.ta);
          std::memcpy(p.Rb, f.R_WB.data(), sizeof p.Rb), std::memcpy(p.tb, f.t_WB.data(), sizeof p.tb);
          poses.push_back(p);
        }
      }
    if (FILE* f = fopen(poses_file.c_str(), "wb")) {
      fwrite(poses.data(), sizeof(FramePose), poses.size(), f);
      fclose(f);
    }
  }

  if (case_frame >= 0) {
    if (case_frame >= static_cast<long>(poses.size())) return 2;
    const FramePose& p = poses[case_frame];
    std::ifstream in_pairs(default_models_dir() + "/paper_pairs.json");
    const nlohmann::json models = nlohmann::json::parse(in_pairs);
    const std::string na = in.statics[p.a].name, nb = in.statics[p.b].name;
    nlohmann::json doc;
    doc["format"] = "revdist/1";
    doc["comment"] = "motion probe frame " + std::to_string(case_frame) + ": " + na + " and " + nb;
    doc["solids"][na] = models["solids"][na];
    doc["solids"][nb] = models["solids"][nb];
    auto instance = [](const char* name, const std::string& solid, const double* R, const double* t) {
      const Mat3 rot = Eigen::Map<const Mat3>(R);
      const Eigen::Quaterniond q(rot);
      return nlohmann::json{{"name", name}, {"solid", solid}, {"rotation", {q.w(), q.x(), q.y(), q.z()}},
                            {"translation", {t[0], t[1], t[2]}}};
    };
    doc["instances"] = {instance("a", na, p.Ra, p.ta), instance("b", nb, p.Rb, p.tb)};
    doc["queries"] = nlohmann::json::array({nlohmann::json::array({"a", "b"})});
    std::ofstream(case_file) << doc.dump(1) << "\n";
    return 0;
  }
  std::vector<BiarcTree> trees;
  for (const Profile& p : profiles) trees.push_back(build_biarc_tree(p, eps));
  DistanceOptions o;
  o.tol = tol;
  std::vector<double> us, over_us;
  std::vector<Bracket> got;
  std::vector<SolidDistanceResult> results;  // first repetition (--worst)
  DistanceStats sum;
  int overlaps = 0, unconverged = 0;
  std::vector<WarmStart> warms(poses.size());  // each frame's warm start (--coherent)
  for (int rep = 0; rep < repeat; ++rep)
    for (std::size_t k = 0; k < poses.size(); ++k) {
      const FramePose& p = poses[k];
      PosedSolid A{&profiles[p.a], &trees[p.a]}, B{&profiles[p.b], &trees[p.b]};
      A.R = Eigen::Map<const Mat3>(p.Ra), A.t = Eigen::Map<const Vec3>(p.ta);
      B.R = Eigen::Map<const Mat3>(p.Rb), B.t = Eigen::Map<const Vec3>(p.tb);
      if (perfect && rep == 0) warms[k] = warm_start_of(solid_distance(A, B, o), A, B);
      const double c0 = thread_cpu_us();
      const SolidDistanceResult r = solid_distance(A, B, o, warms[k]);
      const double dt = thread_cpu_us() - c0;
      if (coherent && k + 1 < poses.size() && poses[k + 1].a == p.a && poses[k + 1].b == p.b)
        warms[k + 1] = warm_start_of(r, A, B);
      if (rep > 0) {  // each query's least time over the repetitions: less of the machine's noise
        us[k] = std::min(us[k], dt);
        continue;
      }
      us.push_back(dt);
      got.push_back({r.lower, r.upper});
      if (worst > 0) results.push_back(r);
      if (getenv("PROBE_FINE") && p.target < 0 && !r.overlap) {
        DistanceOptions f = o;
        f.tol = 1e-10;
        const SolidDistanceResult g = solid_distance(A, B, f);
        printf("unproven overlap frame %zu target %.3e: [%.3e, %.3e] -> tol 1e-10: [%.6e, %.6e] overlap %d converged %d %s\n",
               got.size() - 1, p.target, r.lower, r.upper, g.lower, g.upper, g.overlap, g.converged, g.reason.c_str());
      }
      overlaps += r.overlap, unconverged += !r.converged;
      sum.node_pairs += r.stats.node_pairs, sum.bounds += r.stats.bounds, sum.leaf_pairs += r.stats.leaf_pairs;
      sum.patch_pairs += r.stats.patch_pairs, sum.quick_pairs += r.stats.quick_pairs, sum.refined += r.stats.refined;
      sum.local_pairs += r.stats.local_pairs, sum.local_boxes += r.stats.local_boxes;
      sum.spine_pairs += r.stats.spine_pairs, sum.spine_evals += r.stats.spine_evals;
      sum.hull_pairs += r.stats.hull_pairs, sum.hull_parts += r.stats.hull_parts, sum.spine_parts += r.stats.spine_parts;
    }
  std::vector<double> proven_us;  // the queries answered with a proven overlap
  for (std::size_t k = 0; k < us.size(); ++k) {
    if (poses[k].target < 0) over_us.push_back(us[k]);
    if (got[k].upper <= 0) proven_us.push_back(us[k]);
  }
  DistanceStats sel;
  if (sel_lo >= 0) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < us.size(); ++i)
      if ((!only_overlap || got[i].upper <= 0) && (only_index < 0 || only_index == static_cast<long>(i)))
        order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return us[x] < us[y]; });
    const std::size_t lo = static_cast<std::size_t>(sel_lo * order.size());
    const std::size_t hi = std::min(order.size(), static_cast<std::size_t>(sel_hi * order.size()));
    for (std::size_t k = lo; k < hi; ++k) {
      const FramePose& p = poses[order[k]];
      PosedSolid A{&profiles[p.a], &trees[p.a]}, B{&profiles[p.b], &trees[p.b]};
      A.R = Eigen::Map<const Mat3>(p.Ra), A.t = Eigen::Map<const Vec3>(p.ta);
      B.R = Eigen::Map<const Mat3>(p.Rb), B.t = Eigen::Map<const Vec3>(p.tb);
      CALLGRIND_TOGGLE_COLLECT;
      const SolidDistanceResult r = solid_distance(A, B, o, warms[order[k]]);
      CALLGRIND_TOGGLE_COLLECT;
      sel.node_pairs += r.stats.node_pairs, sel.bounds += r.stats.bounds, sel.leaf_pairs += r.stats.leaf_pairs;
      sel.patch_pairs += r.stats.patch_pairs, sel.quick_pairs += r.stats.quick_pairs;
    }
    const double m = static_cast<double>(std::max<std::size_t>(hi - lo, 1));
    printf("selected %zu queries (ranks %zu..%zu): node_pairs %.1f bounds %.1f leaf_pairs %.1f patch_pairs %.1f quick %.1f\n",
           hi - lo, lo, hi, sel.node_pairs / m, sel.bounds / m, sel.leaf_pairs / m, sel.patch_pairs / m,
           sel.quick_pairs / m);
  }
  const double n = static_cast<double>(us.size());
  printf("queries %zu eps %g tol %g: median %.1f us p90 %.1f p99 %.1f mean %.1f | overlap frames %zu median %.1f p99 %.1f\n",
         us.size(), eps, tol, nearest_rank_percentile(us, 0.5), nearest_rank_percentile(us, 0.9), nearest_rank_percentile(us, 0.99), [&] {
           double s = 0;
           for (double u : us) s += u;
           return s / n;
         }(), over_us.size(), nearest_rank_percentile(over_us, 0.5), nearest_rank_percentile(over_us, 0.99));
  printf("proven overlaps %zu: median %.1f us p90 %.1f p99 %.1f\n", proven_us.size(), nearest_rank_percentile(proven_us, 0.5),
         nearest_rank_percentile(proven_us, 0.9), nearest_rank_percentile(proven_us, 0.99));
  printf("per query: popped pairs retired by their capsules' hulls %.1f, given a fit's spine bound %.1f\n", sum.hull_parts / n,
         sum.spine_parts / n);
  printf("per query: node_pairs %.1f bounds %.1f leaf_pairs %.1f patch_pairs %.1f quick %.1f hull %.1f spine %.1f (points %.1f) local %.1f (boxes %.1f) refined %.1f; overlaps %d unconverged %d\n",
         sum.node_pairs / n, sum.bounds / n, sum.leaf_pairs / n, sum.patch_pairs / n, sum.quick_pairs / n,
         sum.hull_pairs / n, sum.spine_pairs / n, sum.spine_evals / n, sum.local_pairs / n, sum.local_boxes / n, sum.refined / n, overlaps,
         unconverged);
  if (worst > 0) {
    std::vector<std::size_t> order(us.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    if (only_overlap)  // --worst among the proven overlaps
      order.erase(std::remove_if(order.begin(), order.end(), [&](std::size_t i) { return got[i].upper > 0; }), order.end());
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return us[x] > us[y]; });
    for (std::size_t k = 0; k < std::min<std::size_t>(worst, order.size()); ++k) {
      const std::size_t i = order[k];
      const SolidDistanceResult& r = results[i];
      const DistanceStats& s = r.stats;
      printf("frame %zu pair %d-%d target %.2e: %.1f us [%.6e, %.6e]%s node %ld bounds %ld leaf %ld patch %ld local %ld "
             "(boxes %ld) spine %ld hull %ld refined %ld %s\n",
             i, poses[i].a, poses[i].b, poses[i].target, us[i], r.lower, r.upper, r.overlap ? " overlap" : "",
             (long)s.node_pairs, (long)s.bounds, (long)s.leaf_pairs, (long)s.patch_pairs, (long)s.local_pairs,
             (long)s.local_boxes, (long)s.spine_pairs, (long)s.hull_pairs, (long)s.refined, r.reason.c_str());
    }
  }
  if (!times.empty())
    if (FILE* f = fopen(times.c_str(), "w")) {
      for (double u : us) fprintf(f, "%.3f\n", u);
      fclose(f);
    }
  if (!save.empty())
    if (FILE* f = fopen(save.c_str(), "wb")) {
      fwrite(got.data(), sizeof(Bracket), got.size(), f);
      fclose(f);
    }
  if (!check.empty()) {
    std::vector<Bracket> ref(got.size());
    FILE* f = fopen(check.c_str(), "rb");
    if (!f || fread(ref.data(), sizeof(Bracket), ref.size(), f) != ref.size()) {
      fprintf(stderr, "cannot read %s\n", check.c_str());
      return 1;
    }
    fclose(f);
    int bad = 0;
    double worst_width = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
      const double slack = 1e-12;
      if (got[i].lower > ref[i].upper + slack || got[i].upper < ref[i].lower - slack) {
        if (bad++ < 10)
          printf("frame %zu: [%.17g, %.17g] misses reference [%.17g, %.17g]\n", i, got[i].lower, got[i].upper,
                 ref[i].lower, ref[i].upper);
      }
      worst_width = std::max(worst_width, got[i].upper - got[i].lower);
    }
    printf("check vs %s: %d disjoint brackets, widest %.3g\n", check.c_str(), bad, worst_width);
    return bad ? 1 : 0;
  }
  return 0;
}
