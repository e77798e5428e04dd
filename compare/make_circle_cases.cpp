// Writes cases/circles/<family>.json: a few pairs of every circle family as
// revdist-circles/1 files, each pair carrying its closed-form "expected"
// distance (null when none is known) for readers and tests.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "compare/circle_families.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: revdist_make_circle_cases OUTDIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  using nlohmann::json;
  auto vec = [](const revdist::Vec3& v) { return json::array({v.x(), v.y(), v.z()}); };
  auto circ = [&](const revdist::Circle3& c) {
    return json{{"center", vec(c.center)}, {"normal", vec(c.normal)}, {"radius", c.radius}};
  };
  for (const auto& family : revdist::circle_families()) {
    const auto pairs = revdist::make_circle_family(family.name, 12, 20261121);
    json list = json::array();
    for (const auto& p : pairs) {
      json j{{"a", circ(p.pair.a)}, {"b", circ(p.pair.b)}};
      j["expected"] = std::isnan(p.expected) ? json(nullptr) : json(p.expected);
      j["infinitely_many"] = p.infinitely_many;
      list.push_back(j);
    }
    const json doc{{"format", "revdist-circles/1"}, {"family", family.name},
                   {"description", family.description}, {"pairs", list}};
    std::ofstream(dir + "/" + family.name + ".json") << doc.dump(1) << "\n";
  }
  return 0;
}
