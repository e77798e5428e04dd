// Certified fit errors (exact/fit_audit.h): exact fits certify at rounding level,
// biarc fits certify within the fitter's lens bound and never below a dense
// sampled Hausdorff distance, wrong fits are caught, and every leaf of every
// bundled model's biarc tree is certified within its claimed eps.
#include "exact/fit_audit.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "core/case_io.h"
#include "core/curve_eval.h"
#include "fast/biarc_fit.h"
#include "fast/biarc_tree.h"
#include "fast/spiral_split.h"
#include "tests/fast/biarc_test_util.h"

namespace revdist {
namespace {

using testing_util::arc_piece;
using testing_util::bezier_piece;
using testing_util::line_piece;
using testing_util::sampled_hausdorff;

// Rounding-level tolerance for exact fits: the stored arcs carry a few ulp of the
// coordinates (scale ~ 1 here); 64 ulp is the fitter's own allowance.
constexpr double kExactTol = 64 * 2.220446049250313e-16;

Piece bspline_piece(int degree, std::vector<double> knots, std::vector<Vec2> pts, std::vector<double> w = {}) {
  Piece p;
  p.kind = PieceKind::bspline;
  p.degree = degree;
  p.knots = std::move(knots);
  p.points = std::move(pts);
  p.weights = std::move(w);
  return p;
}

struct Fit {
  double u0, u1;
  Biarc biarc;
  double claimed;  // lens width + the tree's rounding slack
};

SpanEnds ends_of(const Piece& piece, double u0, double u1) {
  SpanEnds e;
  e.p0 = piece_tangent(piece, u0, +1, &e.t0, &e.k0);
  e.p1 = piece_tangent(piece, u1, -1, &e.t1, &e.k1);
  return e;
}

// The spirals of a one-piece profile, each cut into 2^depth equal parameter parts,
// fitted by fast/biarc_fit.h.
std::vector<Fit> fits_of(const Piece& piece, int depth) {
  Profile prof;
  prof.pieces = {piece};
  std::vector<SpiralSpan> spans;
  split_into_spirals(prof, spans);
  std::vector<Fit> out;
  for (const SpiralSpan& s : spans) {
    const int parts = 1 << depth;
    for (int i = 0; i < parts; ++i) {
      const double a = s.u0 + (s.u1 - s.u0) * i / parts, b = s.u0 + (s.u1 - s.u0) * (i + 1) / parts;
      const SpanEnds e = ends_of(piece, a, b);
      const LensBound lens = lens_bound(e);
      // A part of a spiral is a spiral: failing hypotheses is a split bug, not a case to skip.
      EXPECT_TRUE(lens.hypotheses_ok) << "span [" << a << ", " << b << "] of a spiral fails the lens hypotheses";
      if (!lens.hypotheses_ok) continue;
      const Biarc bi = fit_curve_biarc(piece, a, b, e, piece_point(piece, 0.5 * (a + b)));
      out.push_back({a, b, bi, lens.width + 64 * 2.220446049250313e-16 * 2.0});
    }
  }
  EXPECT_FALSE(out.empty()) << "no fit to audit";
  return out;
}

// The certificate brackets the truth: lower_bound <= sampled <= certified <= claimed.
void expect_brackets(const Piece& piece, const Fit& f, const char* what) {
  const FitAudit a = audit_fit(piece, f.u0, f.u1, f.biarc.arc, 2, f.claimed);
  ASSERT_TRUE(a.certified) << what << ": " << a.reason;
  const double sampled = sampled_hausdorff(piece, f.u0, f.u1, f.biarc.arc, 2, 400);
  // 1e-13: the sampled value is computed in double (a few ulp of the coordinates).
  EXPECT_GE(a.certified_error, sampled - 1e-13) << what << " [" << f.u0 << ", " << f.u1 << "]";
  EXPECT_LE(a.lower_bound, sampled + 1e-13) << what;
  EXPECT_LE(a.certified_error, f.claimed) << what << " [" << f.u0 << ", " << f.u1 << "]";
}

TEST(FitAudit, QuarterCircleRationalBezierByExactArc) {
  // w1 = cos(45 deg) rounded: the conic is a circle up to ~1e-17.
  const Piece q = bezier_piece({{1, 0}, {1, 1}, {0, 1}}, {1, std::sqrt(0.5), 1});
  Arc2 arc;
  arc.start = Vec2(1, 0);
  arc.tangent = Vec2(0, 1);
  arc.curvature = 1.0;
  arc.length = M_PI / 2;
  const FitAudit a = audit_fit(q, 0.0, 1.0, &arc, 1, 1e-15);
  ASSERT_TRUE(a.certified) << a.reason;
  EXPECT_LE(a.certified_error, 1e-15);
  std::printf("quarter circle: certified %.3g, nodes %d\n", a.certified_error, a.nodes);
  // The same arc against half of the curve: the curve lies on the arc (forward
  // distance 0) but half of the arc is far from the curve (the reverse direction).
  const FitAudit b = audit_fit(q, 0.0, 0.5, &arc, 1, 1e-15);
  ASSERT_TRUE(b.certified) << b.reason;
  EXPECT_LE(b.lower_bound, 1e-15);
  EXPECT_GT(b.certified_error, 0.5);
}

TEST(FitAudit, LinePieceBySegment) {
  const Piece l = line_piece({0.1, 0.3}, {0.7, 1.9});
  for (const auto& [u0, u1] : {std::pair{0.0, 1.0}, std::pair{0.25, 0.75}, std::pair{0.0, 0.1}}) {
    Arc2 seg;
    seg.start = piece_point(l, u0);
    const Vec2 end = piece_point(l, u1);
    seg.tangent = (end - seg.start).normalized();
    seg.length = (end - seg.start).norm();
    const FitAudit a = audit_fit(l, u0, u1, &seg, 1, 0.0);
    ASSERT_TRUE(a.certified) << a.reason;
    EXPECT_LE(a.certified_error, 8 * 2.220446049250313e-16) << u0 << " " << u1;
  }
  // The arcs of a straight fit in the tree's form: one segment and a zero-length arc.
  Arc2 two[2];
  two[0].start = l.points[0];
  two[0].tangent = (l.points[1] - l.points[0]).normalized();
  two[0].length = (l.points[1] - l.points[0]).norm();
  two[1] = Arc2{two[0].end(), two[0].tangent, 0.0, 0.0};
  const FitAudit a = audit_fit(l, 0.0, 1.0, two, 2, 0.0);
  ASSERT_TRUE(a.certified) << a.reason;
  EXPECT_LE(a.certified_error, kExactTol);
}

TEST(FitAudit, ArcPieceSpansByExactArcs) {
  // The paper's ball: a half circle, split into quarter-circle spans.
  Profile ball;
  ball.pieces = {arc_piece({0, -1}, {1, 0}, {0, 1})};
  const BiarcTree tree = build_biarc_tree(ball, 1e-4);
  const std::vector<FitLeaf> leaves = biarc_tree_leaves(ball, tree);
  ASSERT_FALSE(leaves.empty());
  std::vector<FitAudit> per;
  const TreeAudit t = audit_leaves(leaves, &per);
  EXPECT_EQ(t.certified, t.leaves) << t.first_problem_reason;
  EXPECT_EQ(t.violations, 0);
  EXPECT_EQ(t.unconfirmed, 0);
  EXPECT_LE(t.max_certified_error, kExactTol);
  // An arc of 300 degrees with a far-off position, as one part: enclosed in several quadratics.
  const Piece big = arc_piece({3, 5}, {3 + std::sqrt(3.0) / 2, 5.5}, {3, 4});
  const ArcGeometry g = arc_geometry(big);
  Arc2 arc;
  arc.start = piece_point(big, 0.25);
  Vec2 d[2];
  piece_derivatives(big, 0.25, 1, d);
  arc.tangent = d[1].normalized();
  arc.curvature = (g.sweep > 0 ? 1.0 : -1.0) / g.radius;
  arc.length = g.radius * std::abs(g.sweep) * 0.25;
  const FitAudit a = audit_fit(big, 0.25, 0.5, &arc, 1, 0.0);
  ASSERT_TRUE(a.certified) << a.reason;
  EXPECT_LE(a.certified_error, kExactTol);
}

// A nearly straight input arc (radius ~ 1.25e7, curvature 8e-8): split at its
// r extreme (u = 0.5) by the fitter. The audit's circle form has no far-away
// centre to lose digits to, so it certifies the first half at rounding level.
Profile nearly_straight_arc() {
  Profile prof;
  prof.pieces = {arc_piece({0.5, 0}, {0.5 + 1e-8, 0.5}, {0.5, 1})};
  return prof;
}

TEST(FitAudit, NearlyStraightArcPiece) {
  const Profile prof = nearly_straight_arc();
  const BiarcTree tree = build_biarc_tree(prof, 1e-5);
  const std::vector<FitLeaf> leaves = biarc_tree_leaves(prof, tree);
  ASSERT_GE(leaves.size(), 2u);  // exact arcs are halved down to 1/8 of the profile's extent at this eps
  std::vector<FitAudit> per;
  const TreeAudit t = audit_leaves(leaves, &per, true);
  EXPECT_EQ(t.certified, t.leaves) << t.first_problem_reason;
  // Every leaf starts at a double point of the arc computed along the chord
  // from p0: on the exact circle to rounding, although the centre is 1.25e7 away.
  for (const FitAudit& a : per) {
    EXPECT_GE(a.certified_error, a.lower_bound);
    EXPECT_LE(a.certified_error, kExactTol);
  }
}

// Regression (found by this audit): leaf [0.5, 1] claimed 64 ulp x (coordinate
// scale) = 1.4e-14 but its start point was off the exact arc by a proven
// 6.9e-10, because arc points were evaluated as centre + R (cos, sin) with a
// centre 1.25e7 away. core/curve_eval now walks the chord from p0.
TEST(FitAudit, NearlyStraightArcPieceWithinClaim) {
  const Profile prof = nearly_straight_arc();
  const BiarcTree tree = build_biarc_tree(prof, 1e-5);
  const TreeAudit t = audit_leaves(biarc_tree_leaves(prof, tree));
  EXPECT_EQ(t.violations, 0) << "leaf " << t.first_problem;
  EXPECT_EQ(t.unconfirmed, 0) << "leaf " << t.first_problem;
}

TEST(FitAudit, ScalingByAPowerOfTwoScalesTheBound) {
  // Every quantity scales exactly (k L is unchanged), so the certificate does too.
  const Piece p = bezier_piece({{0, 0}, {1.2, 0.3}, {0.2, 1.1}, {0.9, 1.6}, {0, 2}}, {1, 2, 0.5, 3, 1});
  for (const Fit& f : fits_of(p, 2)) {
    const FitAudit a = audit_fit(p, f.u0, f.u1, f.biarc.arc, 2, 0.0);
    for (double s : {0x1p-20, 0x1p+20}) {
      Piece q = p;
      for (Vec2& v : q.points) v *= s;
      Arc2 arcs[2] = {f.biarc.arc[0], f.biarc.arc[1]};
      for (Arc2& a2 : arcs) {
        a2.start *= s;
        a2.curvature /= s;
        a2.length *= s;
      }
      const FitAudit b = audit_fit(q, f.u0, f.u1, arcs, 2, 0.0);
      ASSERT_TRUE(a.certified && b.certified) << a.reason << b.reason;
      EXPECT_NEAR(b.certified_error / s, a.certified_error, 1e-12 * a.certified_error) << s;
    }
  }
}

TEST(FitAudit, DeformableProfileAtAFractionalTime) {
  const std::filesystem::path file = std::filesystem::path(REVDIST_SOURCE_DIR) / "cases" / "models" / "morph.json";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
  const Case c = read_case(file.string());
  for (const SolidDef& s : c.solids) {
    if (!s.deformable()) continue;
    for (double time : {0.25, 0.5, 0.8125}) {
      const Profile prof = profile_at(s, time * static_cast<double>(s.keyframes.size() - 1));
      const BiarcTree tree = build_biarc_tree(prof, 1e-4);
      const TreeAudit t = audit_leaves(biarc_tree_leaves(prof, tree));
      EXPECT_EQ(t.violations, 0) << s.name << " t=" << time << " leaf " << t.first_problem;
      EXPECT_EQ(t.unconfirmed, 0) << s.name << " t=" << time << " leaf " << t.first_problem;
      EXPECT_EQ(t.certified, t.leaves) << s.name << " t=" << time << ": " << t.first_problem_reason;
    }
  }
}

TEST(FitAudit, CubicBezierBiarcsWithinLensAndAboveSampled) {
  const Piece p = bezier_piece({{0, 0}, {1, 0.5}, {1, 1.5}, {0, 2}});
  for (int depth : {0, 3}) {
    for (const Fit& f : fits_of(p, depth)) expect_brackets(p, f, "cubic");
  }
  const Piece r = bezier_piece({{0, 0}, {1.2, 0.3}, {0.2, 1.1}, {0.9, 1.6}, {0, 2}}, {1, 2, 0.5, 3, 1});
  for (int depth : {1, 3}) {
    for (const Fit& f : fits_of(r, depth)) expect_brackets(r, f, "rational quartic");
  }
}

TEST(FitAudit, TightOnAWellFittedSpan) {
  // Not a contract, a regression guard on the method: the bound should be close
  // to the truth (the lens bound itself is ~3x the truth).
  const Piece p = bezier_piece({{0, 0}, {1, 0.5}, {1, 1.5}, {0, 2}});
  for (const Fit& f : fits_of(p, 3)) {
    const FitAudit a = audit_fit(p, f.u0, f.u1, f.biarc.arc, 2, 0.0);
    ASSERT_TRUE(a.certified) << a.reason;
    const double sampled = sampled_hausdorff(p, f.u0, f.u1, f.biarc.arc, 2, 400);
    EXPECT_LE(a.certified_error, 1.1 * sampled + 1e-15) << f.u0;
    EXPECT_GE(a.lower_bound, 0.9 * sampled) << f.u0;
  }
}

TEST(FitAudit, ShiftedBiarcIsCaught) {
  const Piece p = bezier_piece({{0, 0}, {1, 0.5}, {1, 1.5}, {0, 2}});
  const std::vector<Fit> fits = fits_of(p, 4);
  ASSERT_FALSE(fits.empty());
  for (const Fit& f : fits) {
    Fit g = f;
    const Vec2 n(-g.biarc.arc[0].tangent.y(), g.biarc.arc[0].tangent.x());
    for (Arc2& a : g.biarc.arc) a.start += 1e-3 * n;
    const FitAudit a = audit_fit(p, g.u0, g.u1, g.biarc.arc, 2, g.claimed);
    ASSERT_TRUE(a.certified) << a.reason;
    // The true distance is >= 1e-3 - (the fit's own error, < claimed).
    EXPECT_GE(a.certified_error, 1e-3 - f.claimed);
    EXPECT_GE(a.lower_bound, 1e-3 - 2 * f.claimed);
    EXPECT_GT(a.certified_error, g.claimed);  // a violation, as it should be
  }
}

TEST(FitAudit, NurbsSpansAcrossKnots) {
  // The SPEC's vase: rational cubic with an interior knot that is not a split
  // point (C2 there), so some spans contain it.
  const Piece v = bspline_piece(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {{0, 0}, {1, 0.2}, {0.4, 1}, {0.9, 1.6}, {0, 2}},
                                {1, 1, 2, 1, 1});
  for (int depth : {0, 3}) {
    for (const Fit& f : fits_of(v, depth)) expect_brackets(v, f, "vase");
  }
  // Parts that contain the knot: two Bezier segments in the audit.
  for (double h : {0.05, 0.01, 0.002}) {
    const SpanEnds e = ends_of(v, 0.5 - h, 0.5 + h / 3);
    const LensBound lens = lens_bound(e);
    ASSERT_TRUE(lens.hypotheses_ok) << h;
    const Fit f{0.5 - h, 0.5 + h / 3, fit_curve_biarc(v, 0.5 - h, 0.5 + h / 3, e, piece_point(v, 0.5 - h / 3)),
                lens.width + 64 * 2.220446049250313e-16 * 2.0};
    expect_brackets(v, f, "vase across the knot");
  }
  // A quadratic B-spline (only C1 at its knots).
  const Piece q = bspline_piece(2, {2, 2, 2, 3, 3.5, 4.5, 5, 5, 5},
                                {{0, 0}, {1, 0}, {1.3, 1}, {2, 1.2}, {1.5, 2}, {0, 2}});
  for (const Fit& f : fits_of(q, 2)) expect_brackets(q, f, "quadratic bspline");
}

TEST(FitAudit, RandomPiecesTrees) {
  const std::uint64_t seed = testing_util::test_seed(20240611);
  std::printf("seed %llu (REVDIST_SEED overrides)\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 12; ++trial) {
    Profile prof;
    prof.pieces = {trial % 3 == 2 ? testing_util::random_bspline(rng, 3, 7, trial % 2 == 0)
                                  : testing_util::random_bezier(rng, trial % 2 == 1)};
    const BiarcTree tree = build_biarc_tree(prof, 1e-4);
    std::vector<FitAudit> per;
    const std::vector<FitLeaf> leaves = biarc_tree_leaves(prof, tree);
    const TreeAudit t = audit_leaves(leaves, &per);
    EXPECT_EQ(t.violations, 0) << "trial " << trial << " leaf " << t.first_problem;
    EXPECT_EQ(t.unconfirmed, 0) << "trial " << trial << " leaf " << t.first_problem;
    for (std::size_t i = 0; i < per.size(); ++i) {
      // The fitter proves every leaf of a spiral split (BuildStats::unproven = 0 expected).
      EXPECT_TRUE(std::isfinite(leaves[i].claimed)) << "trial " << trial << " leaf " << i << " unproven";
      if (!std::isfinite(leaves[i].claimed)) continue;
      EXPECT_TRUE(per[i].certified) << "trial " << trial << " leaf " << i << ": " << per[i].reason;
      if (i % 7 == 0 && per[i].certified) {
        const double s = sampled_hausdorff(*leaves[i].piece, leaves[i].u0, leaves[i].u1, leaves[i].arcs,
                                           leaves[i].n_arcs, 1000);
        EXPECT_GE(per[i].certified_error, s - 1e-13) << "trial " << trial << " leaf " << i;
      }
    }
  }
}

// Long random run: REVDIST_AUDIT_TRIALS=N (skipped when unset). Random cubic and
// quartic, polynomial and rational, Bezier and B-spline pieces at eps 1e-3 ..
// 1e-6, tight audits: every leaf the fitter proved must certify within its claim.
TEST(FitAudit, RandomStress) {
  const char* env = std::getenv("REVDIST_AUDIT_TRIALS");
  const int trials = env ? std::atoi(env) : 0;
  if (trials <= 0) GTEST_SKIP() << "set REVDIST_AUDIT_TRIALS";
  const std::uint64_t seed = testing_util::test_seed(7);
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  long long leaves = 0;
  double worst_ratio = 0.0;
  for (int trial = 0; trial < trials; ++trial) {
    Profile prof;
    const int kind = trial % 4;
    prof.pieces = {kind < 2 ? testing_util::random_bezier(rng, kind == 1)
                            : testing_util::random_bspline(rng, kind == 2 ? 3 : 4, 8, trial % 8 >= 4)};
    const double eps = std::pow(10.0, -3.0 - trial % 4);
    const BiarcTree tree = build_biarc_tree(prof, eps);
    const std::vector<FitLeaf> lv = biarc_tree_leaves(prof, tree);
    std::vector<FitAudit> per;
    const TreeAudit t = audit_leaves(lv, &per, true);
    leaves += t.leaves;
    for (std::size_t i = 0; i < per.size(); ++i) {
      if (!std::isfinite(lv[i].claimed)) continue;
      EXPECT_TRUE(per[i].certified) << "trial " << trial << " leaf " << i << ": " << per[i].reason;
      EXPECT_LE(per[i].certified_error, lv[i].claimed)
          << "trial " << trial << " leaf " << i << " [" << lv[i].u0 << ", " << lv[i].u1 << "] lower "
          << per[i].lower_bound;
      if (per[i].certified) worst_ratio = std::max(worst_ratio, per[i].certified_error / lv[i].claimed);
    }
  }
  std::printf("%d trials, %lld leaves, max certified/claimed %.3f\n", trials, leaves, worst_ratio);
}

// Every leaf of every bundled model at three eps: no violations. Prints the
// worst certified error and the time per leaf.
TEST(FitAudit, BundledModelsHaveNoViolations) {
  const std::filesystem::path dir = std::filesystem::path(REVDIST_SOURCE_DIR) / "cases" / "models";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no " << dir;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& [eps, tight] : {std::pair{1e-3, false}, std::pair{1e-4, false}, std::pair{1e-5, false},
                                   std::pair{1e-3, true}, std::pair{1e-5, true}}) {
    long long leaves = 0, nodes = 0;
    int violations = 0, uncertified = 0;
    double worst = 0.0, worst_ratio = 0.0, ms = 0.0;
    for (const auto& file : files) {
      const Case c = read_case(file.string());
      for (const SolidDef& s : c.solids) {
        for (std::size_t k = 0; k < s.keyframes.size(); ++k) {
          const Profile& prof = s.keyframes[k];
          const BiarcTree tree = build_biarc_tree(prof, eps);
          const std::vector<FitLeaf> lv = biarc_tree_leaves(prof, tree);
          std::vector<FitAudit> per;
          const TreeAudit t = audit_leaves(lv, &per, tight);
          leaves += t.leaves;
          nodes += t.nodes;
          ms += t.time_ms;
          violations += t.violations + t.unconfirmed;
          for (std::size_t i = 0; i < per.size(); ++i) {
            if (!per[i].certified && std::isfinite(lv[i].claimed)) {
              ++uncertified;
              ADD_FAILURE() << file.filename() << " solid " << s.name << " keyframe " << k << " leaf " << i
                            << " [" << lv[i].u0 << ", " << lv[i].u1 << "]: " << per[i].reason;
            }
            if (per[i].certified && per[i].certified_error > lv[i].claimed) {
              ADD_FAILURE() << "violation: " << file.filename() << " solid " << s.name << " keyframe " << k
                            << " leaf " << i << " piece " << (lv[i].piece - prof.pieces.data()) << " ["
                            << lv[i].u0 << ", " << lv[i].u1 << "] claimed " << lv[i].claimed << " certified "
                            << per[i].certified_error << " (lower " << per[i].lower_bound << ")";
            }
            if (per[i].certified) {
              worst = std::max(worst, per[i].certified_error);
              if (lv[i].claimed > 0) worst_ratio = std::max(worst_ratio, per[i].certified_error / lv[i].claimed);
            }
          }
        }
      }
    }
    std::printf("eps %.0e%s: %lld leaves, %d violations, %d uncertified, max certified %.3g, max certified/claimed "
                "%.3f, %.1f ms (%.0f us/leaf, %.1f nodes/leaf)\n",
                eps, tight ? " tight" : "", leaves, violations, uncertified, worst, worst_ratio, ms, 1e3 * ms / std::max(1LL, leaves),
                static_cast<double>(nodes) / std::max(1LL, leaves));
    EXPECT_EQ(violations, 0);
    EXPECT_EQ(uncertified, 0);
  }
}

TEST(FitAudit, BadInputIsDataNotACrash) {
  const Piece p = bezier_piece({{0, 0}, {1, 0.5}, {1, 1.5}, {0, 2}});
  Arc2 a;
  EXPECT_FALSE(audit_fit(p, 0.0, 1.0, nullptr, 0, 1e-3).certified);
  EXPECT_FALSE(audit_fit(p, 0.5, 0.5, &a, 1, 1e-3).certified);
  EXPECT_FALSE(audit_fit(p, -0.5, 0.5, &a, 1, 1e-3).certified);
  a.length = NAN;
  const FitAudit r = audit_fit(p, 0.0, 1.0, &a, 1, 1e-3);
  EXPECT_FALSE(r.certified);
  EXPECT_FALSE(r.reason.empty());
  EXPECT_TRUE(std::isinf(r.certified_error));
}

}  // namespace
}  // namespace revdist
