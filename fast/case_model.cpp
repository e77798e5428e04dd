// Posed solids of a case, one tree per distinct (solid, time).
#include "fast/case_model.h"

#include <chrono>
#include <map>
#include <utility>

#include "core/case_io.h"

namespace revdist {

CaseModel build_case_model(const Case& c, double eps, bool lazy, bool defer_trees) {
  CaseModel m;
  // (solid, time) -> shape: a scan over the shapes made 100000 instances at
  // distinct times quadratic.
  std::map<std::pair<std::size_t, double>, std::size_t> index;
  for (const Instance& inst : c.instances) {
    const double time = c.solids[inst.solid].deformable() ? inst.time : 0.0;
    const auto [it, added] = index.try_emplace({inst.solid, time}, m.shapes.size());
    if (added) {
      auto s = std::make_unique<CaseModel::Shape>();
      s->solid = inst.solid;
      s->time = time;
      s->profile = profile_at(c.solids[inst.solid], time);
      if (!defer_trees) {
        const auto t0 = std::chrono::steady_clock::now();
        rebuild_biarc_tree(s->profile, eps, s->tree, &s->stats, lazy);
        s->build_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
      }
      m.shapes.push_back(std::move(s));
    }
    m.shape_of.push_back(it->second);
  }
  for (std::size_t i = 0; i < c.instances.size(); ++i) {
    const CaseModel::Shape& s = *m.shapes[m.shape_of[i]];
    PosedSolid p;
    p.profile = &s.profile;
    p.tree = &s.tree;
    p.R = c.instances[i].pose.rotation();
    p.t = c.instances[i].pose.translation;
    m.instances.push_back(p);
  }
  return m;
}

}  // namespace revdist
