// Profile validation: Bezier segments reproduce the pieces; accept/reject decisions are
// invariant under scaling by powers of two and under reversing the profile.
#include "core/profile_check.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/case_io.h"
#include "core/curve_eval.h"
#include "core/input_error.h"

namespace revdist {
namespace {

const std::string kSource = REVDIST_SOURCE_DIR;
const char* kModels[] = {"pawn", "cup", "bottle", "table", "lightmil", "torus", "sphere", "can"};

Profile model(const std::string& name) {
  return read_case(kSource + "/cases/models/" + name + ".json").solids.at(0).keyframes.at(0);
}

// The Bezier segments trace the same curve: each segment point lies on its piece. For
// bspline and bezier pieces at the same parameter; arcs are reparametrised, so on the circle.
TEST(ProfileCheck, BezierSegmentsTraceThePieces) {
  for (const char* name : kModels) {
    for (const Piece& p : model(name).pieces) {
      for (const BezierSegment& s : piece_bezier_segments(p)) {
        const Piece as_bezier{PieceKind::bezier, s.degree(), s.points, s.weights, {}};
        for (double t : {0.0, 0.3, 0.5, 0.9, 1.0}) {
          const Vec2 q = piece_point(as_bezier, t);
          if (p.kind == PieceKind::arc) {
            const ArcGeometry g = arc_geometry(p);
            EXPECT_NEAR((q - g.center).norm(), g.radius, 1e-14) << name;
          } else {
            const Vec2 r = piece_point(p, (1 - t) * s.u0 + t * s.u1);
            EXPECT_NEAR((q - r).norm(), 0.0, 1e-14) << name;
          }
        }
      }
    }
  }
}

Profile transformed(Profile p, double scale, bool reverse) {
  for (Piece& piece : p.pieces)
    for (Vec2& q : piece.points) q *= scale;
  if (reverse) {
    std::reverse(p.pieces.begin(), p.pieces.end());
    for (Piece& piece : p.pieces) {
      std::reverse(piece.points.begin(), piece.points.end());
      std::reverse(piece.weights.begin(), piece.weights.end());
      if (piece.kind == PieceKind::bspline) {
        const double a = piece.knots.front(), b = piece.knots.back();
        std::reverse(piece.knots.begin(), piece.knots.end());
        for (double& k : piece.knots) k = a + b - k;
      }
    }
  }
  return p;
}

TEST(ProfileCheck, ModelsAcceptedUnderScaleAndReversal) {
  for (const char* name : kModels)
    for (double scale : {std::ldexp(1.0, -20), 1.0, std::ldexp(1.0, 20)})
      for (bool rev : {false, true}) {
        const Profile p = transformed(model(name), scale, rev);
        EXPECT_NO_THROW(check_profile(p, name)) << name << " scale " << scale << " reversed " << rev;
      }
}

TEST(ProfileCheck, CrossingRejectedUnderScaleAndReversal) {
  Profile p;
  const Vec2 v[] = {{0, 0}, {1, 0}, {1, 1}, {0.2, 0.5}, {1.5, 0.7}, {0, 2}};
  for (int i = 0; i < 5; ++i) p.pieces.push_back({PieceKind::line, 1, {v[i], v[i + 1]}, {}, {}});
  for (double scale : {std::ldexp(1.0, -20), 1.0, std::ldexp(1.0, 20)})
    for (bool rev : {false, true}) EXPECT_THROW(check_profile(transformed(p, scale, rev), "x"), InputError);
}

TEST(ProfileCheck, NearTouchWithinToleranceIsRejectedAndBeyondIsAccepted) {
  // A slot: the profile comes back to within `gap` of its own bottom line.
  auto slot = [](double gap) {
    Profile p;
    const Vec2 v[] = {{0, 0}, {1, 0}, {1, 1}, {0.3, 1}, {0.3, gap}, {0.2, gap}, {0.2, 1.5}, {0, 1.5}};
    for (int i = 0; i < 7; ++i) p.pieces.push_back({PieceKind::line, 1, {v[i], v[i + 1]}, {}, {}});
    return p;
  };
  EXPECT_NO_THROW(check_profile(slot(1e-6), "slot"));
  EXPECT_THROW(check_profile(slot(1e-10), "slot"), InputError);  // tolerance ~1.8e-9
}

TEST(ProfileCheck, SmoothClosedLoopOfOneBezier) {
  // A closed rational quadratic pair would need two pieces; a single cubic loop p0 == p3 is one piece.
  Profile p;
  p.pieces.push_back({PieceKind::bezier, 3, {{1, 0}, {2, 1}, {0.5, 1}, {1, 0}}, {}, {}});
  p.closed_loop = true;
  EXPECT_NO_THROW(check_profile(p, "drop"));
}

// A cusp: the quartic through (0, 0), (2, 1), (0, 1), (2, 0), (0, 2) stops at
// t = 1/2, at (1, 0.75), and leaves back in the direction it came from. Its
// branches meet only there, so the self-intersection test passes it; its fits
// had no tangent there and stayed unproven (a query answered no finite
// bracket). Refused, at every scale and either way round, as a B-spline too
// (the same quartic as one span); a stop at an end (a repeated end control
// point) is no cusp and passes.
TEST(ProfileCheck, CurveThatStopsInsideAPieceIsRefused) {
  const std::vector<Vec2> cusp = {{0, 0}, {2, 1}, {0, 1}, {2, 0}, {0, 2}};
  Profile bez, spl;
  bez.pieces.push_back({PieceKind::bezier, 4, cusp, {}, {}});
  spl.pieces.push_back({PieceKind::bspline, 4, cusp, {}, {0, 0, 0, 0, 0, 3, 3, 3, 3, 3}});
  for (const Profile* p : {&bez, &spl})
    for (double scale : {std::ldexp(1.0, -20), 1.0, std::ldexp(1.0, 20)})
      for (bool rev : {false, true}) {
        try {
          check_profile(transformed(*p, scale, rev), "x");
          ADD_FAILURE() << "a cusp passed, scale " << scale << " reversed " << rev;
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("the curve stops at parameter"), std::string::npos) << e.what();
        }
      }
  Profile end_stop;  // (0, 0) twice: speed 0 at t = 0 only
  end_stop.pieces.push_back({PieceKind::bezier, 3, {{0, 0}, {0, 0}, {2, 1}, {0, 2}}, {}, {}});
  EXPECT_NO_THROW(check_profile(end_stop, "end stop"));
}

TEST(ProfileCheck, MorphIsValidAtEveryTime) {
  const SolidDef s = read_case(kSource + "/cases/models/morph.json").solids.at(0);
  for (int i = 0; i <= 160; ++i) {
    const double t = i / 40.0;
    EXPECT_NO_THROW(check_profile(profile_at(s, t), "morph at " + std::to_string(t)));
  }
}

}  // namespace
}  // namespace revdist
