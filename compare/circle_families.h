// Families of circle pairs for tests, stress runs and the bundled cases in
// cases/circles/: random pairs and every named degenerate configuration of the
// circle layer, with the closed-form distance where one exists.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/circle_io.h"

namespace revdist {

struct CircleFamilyPair {
  CirclePair pair;
  // Closed-form distance of the pair as constructed in exact arithmetic before
  // the double rounding of the rigid motion; NaN when no closed form is known.
  double expected = 0.0;
  bool infinitely_many = false;  // the closed form says the closest pairs form a continuum
  double scale = 1.0;            // max(r_a, r_b, |c_a - c_b|)
};

struct CircleFamily {
  std::string name;
  std::string description;
  // True when the pairs are near-degenerate or degenerate (accuracy target 1e-10 * scale),
  // false for generic random pairs (target 1e-13 * scale).
  bool degenerate = true;
};

// Every family, random first.
const std::vector<CircleFamily>& circle_families();

// n pairs of the named family from the seed; throws std::invalid_argument on an unknown name.
std::vector<CircleFamilyPair> make_circle_family(const std::string& name, int n, std::uint64_t seed);

// Pair `index` of the named family from its own seed (no stream shared with
// other indices, so any slice of indices can be made alone: stress shards).
CircleFamilyPair make_circle_family_pair(const std::string& name, long index, std::uint64_t seed);

double circle_pair_scale(const CirclePair& p);

}  // namespace revdist
