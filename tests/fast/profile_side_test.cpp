// profile_side descends the biarc tree instead of scanning every leaf: where
// the scan decides, the descent must give the same answer. The scan is the
// same test on a copy of the tree whose capsules below the root are infinite,
// so that nothing inside the root's capsule is pruned. (The descent may decide
// where the scan cannot: a pruned capsule's true part is known not to cross
// the ray, while the scan asks every biarc to keep eps from the point.)
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "core/case_io.h"
#include "fast/case_model.h"
#include "fast/profile_side.h"
#include "solid_test_util.h"

namespace revdist {
namespace {

using solid_test::source_path;
using solid_test::test_seed;

TEST(ProfileSide, TreeDescentAgreesWithFullScan) {
  const std::uint64_t seed = test_seed(20261123, "ProfileSide.TreeDescentAgreesWithFullScan");
  std::mt19937_64 rng(seed);
  int checked = 0, inside = 0, outside = 0, unknown = 0;
  for (const char* file : {"cases/models/paper_pairs.json", "cases/distance/linked_tori.json",
                           "cases/distance/nested.json", "cases/distance/curved_pieces.json"}) {
    const Case c = read_case(source_path(file));
    for (double eps : {1e-3, 1e-5}) {
      const CaseModel m = build_case_model(c, eps);
      for (const auto& shape : m.shapes) {
        const BiarcTree& tree = shape->tree;
        BiarcTree flat = tree;
        // Below the root (which sets the size the test's rounding allowance follows).
        for (std::size_t i = 1; i < flat.nodes.size(); ++i) flat.nodes[i].radius = std::numeric_limits<double>::infinity();
        const BiarcNode& root = tree.nodes[0];
        const double size = std::max(root.seg_a.norm(), root.seg_b.norm()) + root.radius;
        std::uniform_real_distribution<double> U(-1.2 * size, 1.2 * size);
        std::uniform_int_distribution<std::size_t> pick(0, tree.fits.size() - 1);
        std::normal_distribution<double> N(0.0, 1.0);
        for (int k = 0; k < 400; ++k) {
          Vec2 q(std::abs(U(rng)), U(rng));
          if (k % 2) {
            // Near the profile: a point of a fit pushed off by a few eps to 1e-2 of the size.
            const Arc2& a = tree.fits[pick(rng)].arc[0];
            const double s = std::uniform_real_distribution<double>(0, a.length)(rng);
            const double off = std::pow(10.0, std::uniform_real_distribution<double>(-6, -2)(rng)) * size;
            q = a.point(s) + off * Vec2(N(rng), N(rng)).normalized();
            q.x() = std::abs(q.x());
          }
          const double margin = 1e-9 * size;
          BiarcTreeView view(tree, shape->profile), flat_view(flat, shape->profile);
          const Side got = profile_side(view, q, margin), want = profile_side(flat_view, q, margin);
          if (want != Side::unknown) {
            ASSERT_EQ(got, want) << file << " eps " << eps << " q = (" << q.x() << ", " << q.y() << ")";
          }
          ++checked;
          inside += got == Side::inside, outside += got == Side::outside, unknown += got == Side::unknown;
        }
      }
    }
  }
  // Both answers must occur, or the comparison says little.
  EXPECT_GT(inside, checked / 20);
  EXPECT_GT(outside, checked / 20);
  std::printf("checked %d points: %d inside, %d outside, %d unknown\n", checked, inside, outside, unknown);
}

}  // namespace
}  // namespace revdist
