// The posed solids of a case: one profile and biarc tree per distinct
// (solid, time), shared by the instances that use it, and each instance's pose.
#pragma once
#include <memory>
#include <vector>

#include "core/profile.h"
#include "fast/biarc_tree.h"
#include "fast/solid_distance.h"

namespace revdist {

struct CaseModel {
  struct Shape {
    std::size_t solid = 0;
    double time = 0.0;
    Profile profile;
    BiarcTree tree;
    BuildStats stats;
    double build_us = 0.0;
  };
  // Stable addresses: PosedSolid points into the shapes.
  std::vector<std::unique_ptr<Shape>> shapes;
  std::vector<std::size_t> shape_of;   // per instance
  std::vector<PosedSolid> instances;   // per instance
};

// Builds the trees of every instance of the case at eps (lazy: see fast/biarc_tree.h).
// With defer_trees, the shapes' trees are left empty for the caller to build
// when a query first needs one (fast/scene/scene.h: a scene of 100000 distinct
// shapes whose queries touch a few dozen).
CaseModel build_case_model(const Case& c, double eps, bool lazy = false, bool defer_trees = false);

}  // namespace revdist
