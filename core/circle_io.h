// Reading of circle-pair files, format revdist-circles/1 (SPEC section 4).
#pragma once
#include <string>
#include <vector>

#include "core/circle3.h"

namespace revdist {

struct CirclePair {
  Circle3 a;
  Circle3 b;
};

// Reads every pair of the file. Throws InputError (one line naming the file,
// the pair and the problem) on anything malformed: not JSON, wrong format tag,
// missing keys, NaN/infinity, a negative radius, a zero normal.
std::vector<CirclePair> read_circle_pairs(const std::string& path);

}  // namespace revdist
