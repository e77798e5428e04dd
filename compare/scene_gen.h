// Scene cases for `revdist scene` (issue 8): an interlocked ring mesh in motion
// like the paper's Figure 1, and a shelf of mixed solids, as revdist/1 documents.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>

namespace revdist {

// A square mesh of flat rings (axis z, major radius 1) joined by upright
// connector rings through the holes of each pair of grid neighbours: about
// `rings` instances (n^2 + 2n(n-1) for the n that comes closest). Static
// clearances: a connector is 0.26 from each ring it links, neighbouring flat
// rings 0.16 apart. Motion: the mesh falls (common acceleration), a wave runs
// along it and every ring turns slowly (seeded), so pair distances change from
// frame to frame. No "queries" member: the broad phase finds the pairs.
nlohmann::json ring_mesh_case(int rings, std::uint64_t seed);

// Shelves of flat boards with mixed solids (ball, can, cone, vase, ring,
// goblet) standing on them with small gaps; some slide or tip over the frames.
// About `items` instances.
nlohmann::json shelf_case(int items, std::uint64_t seed);

}  // namespace revdist
