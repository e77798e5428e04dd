#!/usr/bin/env python3
"""Mutation check: does the default test run catch a broken engine? (issue 10)

Copies the source tree to a scratch folder, breaks the engine on purpose one
mutant at a time (drop an eps from a lower bound, flip a sign in a kernel, skip
a candidate class, ...), rebuilds there and runs the default tests
(ctest -LE stress). A mutant is caught when some test fails. The real tree is
never touched. Not part of the default run: it rebuilds once per mutant.

Mutation sites are found by exact text patterns. When the code changes and a
pattern no longer matches (or matches more than once), the mutant is reported
STALE with its file and pattern, so whoever changed the code can point it at
the new site; the other mutants still run.

  scripts/mutation_check.py                 all mutants, full default suite
  scripts/mutation_check.py --list          the mutants and whether their patterns match
  scripts/mutation_check.py -m lower_eps    one mutant (repeatable)
  scripts/mutation_check.py -R 'Solid'      restrict ctest to a regex (faster, weaker)
Exit status: 0 when every mutant ran and was caught, 1 otherwise.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (name, file, pattern, replacement, what it breaks). Patterns are literal text
# and must occur exactly once in the file.
MUTANTS = [
    ("lower_eps", "fast/solid_distance.cpp",
     "lb_pair = std::min(lb_pair, fits - fa.eps - fb.eps - round);",
     "lb_pair = std::min(lb_pair, fits - fb.eps - round);",
     "leaf lower bound forgets A's fit error eps"),
    ("node_bound_radius", "fast/solid_distance.cpp",
     "A.frame, B.disk_circle(pb), B.frame) - pa.disk_r - pb.disk_r;",
     "A.frame, B.disk_circle(pb), B.frame) - pa.disk_r;",
     "node-pair lower bound forgets B's bounding-torus tube radius"),
    ("cheap_bound_radius", "fast/solid_distance.cpp",
     "Solid::disk_circle_radius(pb)) - pa.disk_r -\n         pb.disk_r;",
     "Solid::disk_circle_radius(pb)) - pa.disk_r;",
     "queued (closed-form) node-pair bound forgets B's tube radius"),
    ("no_rounding", "fast/solid_distance.cpp",
     "const double round = 256 * DBL_EPSILON * coord;", "const double round = 0.0 * coord;",
     "lower bounds lose their rounding allowance"),
    ("upper_not_outward", "fast/solid_distance.cpp",
     "const double up_round = 32 * DBL_EPSILON * coord;", "const double up_round = 0.0 * coord;",
     "upper bounds rounded to nearest, not outward"),
    ("containment_ignored", "fast/solid_distance.cpp",
     "    lb = 0.0;\n    if (res.reason.empty())", "    if (res.reason.empty())",
     "undecided containment still reports the surface distance as lower bound"),
    ("apart_balls_too_small", "fast/patch_distance.cpp",
     "const double r = bx.ball + margin;", "const double r = 0.25 * bx.ball;",
     "cheap separation proof uses balls too small to hold their boxes"),
    ("gauss_cone_ignores_ball", "fast/patch_distance.cpp",
     "const double cos_lim = g.cos_h * cd - g.sin_h * sd;", "const double cos_lim = g.cos_h;",
     "Gauss-map window test ignores the arc's ball radius (drops arcs holding lines)"),
    ("circle_bound_slab", "fast/circle_bound.h",
     "const double dz = std::max(0.0, std::abs(c.h) - ro * s_);", "const double dz = std::abs(c.h);",
     "closed-form circle bound forgets how far circle b tilts out of a's plane"),
    ("point_circle_sign", "fast/circle_distance.cpp",
     "const double e = rho - R;", "const double e = rho + R;",
     "circle kernel: point-circle distance to the far side (sign flip)"),
    ("parallel_nested_sign", "fast/circle_distance.cpp",
     "d2 = std::abs(Rp - Rq) - offset;", "d2 = std::abs(Rp - Rq) + offset;",
     "circle kernel: nested parallel circles, offset added (sign flip)"),
    ("skip_boundary_interior_a", "fast/patch_distance.cpp",
     "if (a_out[i]) boundary_vs_interior(c, ea_c[i], true);", "if (false) boundary_vs_interior(c, ea_c[i], true);",
     "patch kernel skips A's boundary circles against B's interior"),
    ("skip_interior_interior", "fast/patch_distance.cpp",
     "interior_vs_interior(c, disk_lb);", "",
     "patch kernel skips the interior-interior candidates (binormals, cone normals)"),
    ("degenerate_separated", "fast/patch_distance.cpp",
     "c.res.separated = !c.res.degenerate && (", "c.res.separated = (",
     "patch kernel calls a degenerate (continuum) pair separated"),
    ("hull_lower_rim", "fast/cone_hull.cpp",
     "const int i = h0 >= h1 ? 0 : 1;", "const int i = h0 >= h1 ? 1 : 0;",
     "cone hull bound: the support of a frustum taken at its lower end circle"),
    ("hull_thin_frustum", "fast/cone_hull.cpp",
     "f.r[0] = P.p0.x();", "f.r[0] = 0.5 * P.p0.x();",
     "cone hull bound: the frustum's first end circle shrunk (the hull misses part of the patch)"),
    ("kernel_budget_ignored", "fast/solid_distance.cpp",
     "const bool out_of_kernels = st.patch_pairs >= opt.max_patch_pairs;", "const bool out_of_kernels = false;",
     "work budget: patch-pair kernels not counted (near-degenerate queries run for minutes)"),
    ("binormal_far_branch", "fast/circle_binormals.cpp",
     "for (double sg : {1.0, -1.0}) {\n      double t = th[i];", "for (double sg : {1.0}) {\n      double t = th[i];",
     "binormal lines: far branch dropped"),
    ("lens_half_tree", "fast/biarc_tree.cpp",
     "f.eps = lens.hypotheses_ok ? lens.width + slack", "f.eps = lens.hypotheses_ok ? 0.5 * lens.width + slack",
     "tree builder claims half the proven lens width"),
    ("spiral_skip_kappa_prime", "fast/spiral_split.cpp",
     "for (int f = 0; f < 4; ++f) {", "for (int f = 0; f < 3; ++f) {",
     "spiral split ignores zeros of the curvature's derivative"),
    ("gauss_no_mirror", "fast/patch_distance.cpp",
     "for (const Vec2& qs : {q, Vec2(-q.x(), q.y())}) {", "for (const Vec2& qs : {q}) {",
     "Gauss-map window test forgets lines that run past the patch's axis (drops the closest binormal)"),
    ("local_balls_too_small", "fast/patch_distance.cpp",
     "const double r = bx.ball;  // every point", "const double r = 0.25 * bx.ball;  // every point",
     "local proof: balls too small to hold their boxes (first-order bound too high)"),
    ("local_no_curvature_term", "fast/patch_distance.cpp",
     "+\n                                      0.5 * lam * bx.a * bx.a - bx.rest);",
     "- bx.rest);",
     "local proof: second-order bound without its curvature terms"),
    ("local_no_interior_piece", "fast/patch_distance.cpp",
     "      if (active) {", "      if (false) {",
     "local proof: the distance to the arc's circle left out (ends only)"),
    ("descent_jet_no_azimuth", "fast/patch_distance.cpp",
     "  const double beta = w.x() / r;", "  const double beta = 0.0;",
     "the descent's closed-form Hessian leaves out the other axis's curvature (a slower, wrong Newton step)"),
    ("warm_points_unchecked", "fast/solid_distance.cpp",
     "    if (x_in && y_in) {", "    if (true) {",
     "warm start: the previous answer's points used as an upper bound without checking they lie in their solids"),
    ("warm_overlap_unchecked", "fast/solid_distance.cpp",
     "if ((x_in && in_b(x)) || (y_in && in_a(y))) return proven_overlap(shared);",
     "if (x_in || y_in) return proven_overlap(x_in ? x : y);",
     "warm start: a previous overlap taken as proven without testing its point against the other solid"),
    ("end_probe_unchecked", "fast/solid_distance.cpp",
     "    if (witness_probe(fa, fb) ||",
     "    if (true ||",
     "a bracket down to 0 at the end is taken as a proven overlap without the witness's probe"),
    ("early_probe_unchecked", "fast/solid_distance.cpp",
     "if (ub <= fx.eps + fy.eps + opt.tol) return probe_witness(fx, fy);",
     "if (ub <= fx.eps + fy.eps + opt.tol) return shared = res.point_a, true;",
     "a first witness within its fits' errors and tol of touching is taken as a proven overlap without its probe"),
    ("descent_distance_as_bound", "fast/solid_distance.cpp",
     "if (const double hull = patch_hull_bound(P, Q, Vec3(x - y), 0); hull >= *cut2) {",
     "if (const double hull = d; hull >= *cut2) {",
     "a leaf pair takes its descended pair's distance (an upper bound) as the hull's lower bound"),
    ("across_off_surface", "fast/solid_distance.cpp",
     "const double cr = std::max(c.x(), 0.0);",
     "const double cr = 1.01 * std::max(c.x(), 0.0);",
     "the overlap probe's steps across a crossing test points 1 % off the surface (not genuine)"),
    ("bound_axis_distance_cancels", "fast/circle_bound.h",
     "return {h, (d - h * n).norm()};",
     "return {h, std::sqrt(std::max(0.0, d.squaredNorm() - h * h))};",
     "the closed-form circle bound takes a centre's distance from an axis as sqrt(dd - h^2) (all digits lost near the axis)"),
    ("bound_sphere_wrong_gap", "fast/circle_bound.h",
     "return std::max({0.0, m - r, r - M});",
     "return std::max({0.0, m - r, r - m});",
     "the sphere through a circle takes the other circle's nearest point for its farthest (a bound above the distance)"),
    ("descent_each_alone_off", "fast/patch_distance.cpp",
     "if (!moved && each_alone && !convex) {",
     "if (!moved && each_alone && !convex && false) {",
     "a descent that stalls where the distance is not convex stops there (5e-5 above a bottle rim's minimum)"),
    ("centre_key_as_bound", "fast/solid_distance.cpp",
     "    e.lb = -std::numeric_limits<double>::infinity();\n    return e;",
     "    return e;",
     "a pair taken in the centre order reports its centre key as its lower bound (the queue may stop early)"),
    ("deep_probe_unchecked", "fast/solid_distance.cpp",
     "if (in_b(A.true_point(fa, patch_deep_point(P, Q, res.point_a, side, resolution))) ||",
     "if ((patch_deep_point(P, Q, res.point_a, side, resolution), true) ||",
     "a deep point of crossing patches is taken as inside the other solid without the test"),
    ("retry_without_proof", "fast/solid_distance.cpp",
     "proven = patches_at_least(S, O, cut2, round, kRetryBudget, &local, &evals, &closer);",
     "proven = true, local = cut2, evals = 0;",
     "the second local proof (after the descent) settles its pair at the lowered cut without proving it"),
    ("descent_points_unmapped", "fast/solid_distance.cpp",
     "if (d - fa.eps - fb.eps < ub) offer(A.true_point(fa, x), B.true_point(fb, y));",
     "if (d - fa.eps - fb.eps < ub) offer(x, y);",
     "the descent's pair (points of the fits' patches, up to eps off the true surfaces) offered as an upper bound"),
    ("hopeless_pair_bound_from_witness", "fast/solid_distance.cpp",
     "leave_open(quick.lower);\n            continue;",
     "lb_pair = std::min(lb_pair, left_open_at);\n            fit_lb = std::min(fit_lb, std::max(quick.lower, 0.0));\n            continue;",
     "a pair left to refinement takes its descended pair's distance (an upper bound, fit errors not taken off) as its lower bound"),
    ("quick_bound_from_upper_pair", "fast/patch_distance.cpp",
     "q.lower = std::max(q.lower, circle3_circle3_lower_bound(da, db) - ra - rb);",
     "q.lower = std::max(q.lower, circle3_circle3_upper_bound(da, db, goal->hint) - ra - rb);",
     "the quick look's skipped solve takes the filter's pair of points (an upper bound) as the bounding tori's lower bound"),
    ("spine_no_sagitta", "fast/patch_distance.cpp",
     "chord_bound(arc.a.d, arc.b.d, L2) - sag - margin;",
     "chord_bound(arc.a.d, arc.b.d, L2) - margin;",
     "the spine bound takes the chord's bound for its arc's (the sagitta between them dropped)"),
    ("spine_disk_half_tube", "fast/patch_distance.cpp",
     "patch_disk_circle(T, dc), dr, cut, margin",
     "patch_disk_circle(T, dc), 0.5 * dr, cut, margin",
     "the spine bound by the bounding disk's circle takes half the disk's radius for its tube"),
    ("fit_spine_half_tube", "fast/solid_distance.cpp",
     "spine, x.disk_r, need, round,",
     "spine, 0.5 * x.disk_r, need, round,",
     "a fit's spine bound against a smaller part takes half the part's disk radius for its tube"),
    ("sphere_zone_no_offset", "fast/solid_distance.cpp",
     "zones[(*n)++] = {centre, centre, rho + off};",
     "zones[(*n)++] = {centre, centre, 0.9999 * rho};",
     "a sphere zone's radius taken a little short (a point of the zone is within radius + offset of the centre)"),
    ("cylinder_zone_inner_radius", "fast/solid_distance.cpp",
     "const double r = std::max(a.start.x(), e.x());",
     "const double r = 0.9999 * std::min(a.start.x(), e.x());",
     "a cylinder's radius taken a little short of its distance from the axis"),
    ("spine_chord_no_half_length", "fast/patch_distance.h",
     "0.5 * (q0 + q1) - 0.25 * L2 - (L2",
     "0.5 * (q0 + q1) - (L2",
     "the spine bound's chord lemma without the L^2 / 4 of the chord's middle"),
    ("box_ball_centre_radius", "fast/patch_distance.cpp",
     "b.ball = std::sqrt(b.prof * b.prof + rbox * q.x() * dt * dt);",
     "b.ball = std::sqrt(b.prof * b.prof + q.x() * q.x() * dt * dt);",
     "a box's ball moves every point along the centre's parallel (the box's farther points move farther)"),
    ("box_radius_at_centre", "fast/patch_distance.cpp",
     "const double rbox = std::min(rmax, q.x() + b.prof);",
     "const double rbox = std::min(rmax, q.x());",
     "a box's largest distance from the axis is taken at its centre (its profile half-length left out)"),
    ("box_speed_largest_side", "fast/patch_distance.cpp",
     "b.a = std::sqrt(b.prof * b.prof + b.azi * b.azi);",
     "b.a = std::max(b.prof, b.azi);",
     "a box's path speed bound takes the larger of its two orthogonal parts for their length"),
    ("chord_height_halved", "fast/biarc_tree.cpp",
     "const double h = 0.5 * d * std::max(",
     "const double h = 0.25 * d * std::max(",
     "a flat span's chord fit claims half the lens's height over the chord"),
    ("hull_arc_ends_only", "fast/cone_hull.cpp",
     "  if (inside) h = std::max(h, P.c.dot(w) + P.rho * wn);",
     "",
     "the hull bound of toroidal patches takes an arc's support at its ends only (its bulge left out)"),
    ("hull_arc_window_flipped", "fast/cone_hull.cpp",
     "(s * cross(v0, w) >= -slack && s * cross(w, v1) >= -slack)",
     "(s * cross(v0, w) <= slack && s * cross(w, v1) <= slack)",
     "the arc support's test of the direction against the arc's window is mirrored"),
    ("hull_r_clamped", "fast/cone_hull.cpp",
     "ra[2] = {std::abs(a0.x()), std::abs(a1.x())};",
     "ra[2] = {std::max(a0.x(), 0.0), std::max(a1.x(), 0.0)};",
     "a revolved segment's hull drops the circle of an end beyond the axis"),
    ("node_hull_no_caps", "fast/solid_distance.cpp",
     "hb.seg_b) - ha.cap_r - hb.cap_r - round;",
     "hb.seg_b) - round;",
     "two parts' hull bound leaves their capsules' radii on"),
    ("exact_range_two_coeffs", "exact/solid_distance_exact.cpp",
     "const I x = hull_of(part.x, n), y = hull_of(part.y, n), w = hull_of(part.w, n);",
     "const I x = hull_of(part.x, 2), y = hull_of(part.y, 2), w = hull_of(part.w, 2);",
     "exact/: a Bezier's range over a box is the hull of two of its restricted coefficients, not all"),
    ("exact_chord_no_delta", "exact/solid_distance_exact.cpp",
     "const double d = (sqrt_nonneg(I(seg)) - I(delta)).lo();",
     "const double d = sqrt_nonneg(I(seg)).lo();",
     "exact/: the chord bound forgets how far the curve's control points lie from the chord"),
    ("exact_doubles_everywhere", "exact/solid_distance_exact.cpp",
     "if (doubles_ && (ev.lower > mpfi_below_ || (ev.rounding > 0 && ev.upper - ev.lower > kDoubleSpread * ev.rounding)))",
     "if (true)",
     "exact/: MPFI is never used, even where double rounding decides the bracket"),
    ("exact_bern_difference_form", "exact/solid_distance_exact.cpp",
     "b[j] = v * b[j] + u * b[j + 1];",
     "b[j] = b[j] + u * (b[j + 1] - b[j]);",
     "exact/: de Casteljau at a box centre uses each coefficient twice (rounding doubles per degree)"),
    ("exact_sixteen_coefficients", "exact/solid_distance_exact.cpp",
     "constexpr std::size_t kMaxCoeffs = kMaxPieceDegree + 1;",
     "constexpr std::size_t kMaxCoeffs = 16;",
     "exact/: elements of degree 16 to 32 get unbounded boxes"),
]


def run(cmd, cwd, log, timeout=None):
    with open(log, "a") as out:
        out.write("\n$ " + " ".join(cmd) + "\n")
        out.flush()
        try:
            return subprocess.run(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            return 124


def copy_tree(dst):
    files = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"], cwd=ROOT,
                           check=True, capture_output=True).stdout.decode().split("\0")
    for f in files:
        if not f or not os.path.isfile(os.path.join(ROOT, f)):
            continue
        d = os.path.join(dst, f)
        os.makedirs(os.path.dirname(d), exist_ok=True)
        if not os.path.exists(d) or open(os.path.join(ROOT, f), "rb").read() != open(d, "rb").read():
            shutil.copy2(os.path.join(ROOT, f), d)


def pattern_status(src, m):
    path = os.path.join(src, m[1])
    if not os.path.exists(path):
        return "STALE: file %s not found" % m[1]
    n = open(path).read().count(m[2])
    if n != 1:
        return "STALE: pattern %s %s in %s" % (repr(m[2]), "not found" if n == 0 else "found %d times" % n, m[1])
    return ""


def failed_tests(log_text):
    # ctest prints "  12 - Name (Failed)" lines after "The following tests FAILED:";
    # a parameterised test's name is followed by "  # GetParam() = ..." first.
    tail = log_text.split("The following tests FAILED:")[-1] if "The following tests FAILED:" in log_text else ""
    return re.findall(
        r"\d+ - (\S+)(?:\s+# GetParam\(\) = [^\n(]*)? \((?:Failed|Timeout|SEGFAULT|Subprocess aborted|Exception|Child aborted)",
        tail)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dir", default=os.environ.get("REVDIST_MUTANT_DIR", "/tmp/revdist-mutants"))
    ap.add_argument("-m", "--mutant", action="append", help="run only these mutants")
    ap.add_argument("-R", "--regex", help="ctest -R: only tests matching")
    ap.add_argument("-j", "--jobs", type=int, default=2)
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--no-baseline", action="store_true", help="skip the unmutated run (it must pass)")
    a = ap.parse_args()

    mutants = [m for m in MUTANTS if not a.mutant or m[0] in a.mutant]
    if a.list:
        for m in mutants:
            print("%-26s %-28s %s" % (m[0], m[1], pattern_status(ROOT, m) or "ok: " + m[4]))
        return 0
    # build/ inside the copy, as in a worktree, so ccache (paths relative to
    # CCACHE_BASEDIR) reuses the objects of unmutated files.
    src = os.path.join(a.dir, "src")
    build = os.path.join(src, "build")
    os.environ["CCACHE_BASEDIR"] = a.dir
    log = os.path.join(a.dir, "mutation.log")
    os.makedirs(src, exist_ok=True)
    open(log, "w").close()
    copy_tree(src)
    cfg = ["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DREVDIST_BUILD_BENCHMARKS=OFF"]
    if shutil.which("ccache"):
        cfg.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    ctest = ["ctest", "--test-dir", build, "-LE", "stress", "-j%d" % a.jobs, "--timeout", "900"]
    if a.regex:
        ctest += ["-R", a.regex]
    print("scratch tree %s, log %s" % (a.dir, log), flush=True)
    if run(cfg, src, log) != 0 or run(["cmake", "--build", build, "-j%d" % a.jobs], src, log) != 0:
        print("the unmutated tree does not build; see " + log)
        return 1
    if not a.no_baseline:
        t0 = time.time()
        if run(ctest, src, log) != 0:
            print("the unmutated tree fails its tests; see " + log)
            return 1
        print("baseline: tests pass (%.0f s)" % (time.time() - t0), flush=True)

    rows, all_caught = [], True
    for m in mutants:
        name, rel, pat, rep, what = m
        stale = pattern_status(src, m)
        if stale:
            rows.append((name, rel, stale, ""))
            all_caught = False
            print("%-26s %s" % (name, stale), flush=True)
            continue
        path = os.path.join(src, rel)
        original = open(path).read()
        open(path, "w").write(original.replace(pat, rep))
        start = len(open(log).read())
        t0 = time.time()
        try:
            if run(["cmake", "--build", build, "-j%d" % a.jobs], src, log) != 0:
                verdict, tests = "BUILD FAILED (fix the mutant)", ""
                all_caught = False
            else:
                # Without cost data ctest runs in registration order (core, fast, ...),
                # so the fast kernels' tests come early and the first failure stops the run.
                cost = os.path.join(build, "Testing", "Temporary", "CTestCostData.txt")
                if os.path.exists(cost):
                    os.remove(cost)
                rc = run(ctest + ["--stop-on-failure"], src, log)
                text = open(log).read()[start:]
                failed = failed_tests(text)
                if rc != 0:
                    verdict, tests = "caught", ", ".join(failed[:4]) + (" ..." if len(failed) > 4 else "")
                else:
                    verdict, tests = "SURVIVED", ""
                    all_caught = False
        finally:
            open(path, "w").write(original)
        rows.append((name, rel, verdict, tests))
        print("%-26s %-9s %4.0f s  %s" % (name, verdict, time.time() - t0, tests), flush=True)
    # Leave the scratch build matching the real tree again.
    run(["cmake", "--build", build, "-j%d" % a.jobs], src, log)

    print("\n| mutant | file | what it breaks | result | first failing tests |")
    print("|---|---|---|---|---|")
    whats = {m[0]: m[4] for m in MUTANTS}
    for name, rel, verdict, tests in rows:
        print("| %s | %s | %s | %s | %s |" % (name, rel, whats[name], verdict, tests))
    return 0 if all_caught else 1


if __name__ == "__main__":
    sys.exit(main())
