#include "bodyrec/reid/visit_separability.h"

#include <limits>
#include <map>
#include <set>

namespace bodyrec {

void VisitSeparability::add(int person, uint64_t visit, std::vector<float> descriptor) {
  entries_.push_back({person, visit, std::move(descriptor)});
}

VisitSeparability::Score VisitSeparability::score() const {
  std::map<int, std::set<uint64_t>> visits;
  for (const Entry& e : entries_) visits[e.person].insert(e.visit);
  Score s;
  int right = 0, above = 0;
  for (const Entry& p : entries_) {
    if (visits[p.person].size() < 2) continue;
    double best = -std::numeric_limits<double>::infinity(), same = best;
    int best_person = -1;
    for (const Entry& g : entries_) {
      if (g.visit == p.visit && g.person == p.person) continue;
      const double sim = matcher_.similarity(p.d, g.d);
      if (sim > best) best = sim, best_person = g.person;
      if (g.person == p.person) same = std::max(same, sim);
    }
    ++s.probes;
    if (best_person == p.person) ++right;
    if (same > matcher_.threshold()) ++above;
  }
  if (s.probes > 0) {
    s.nn_accuracy = static_cast<double>(right) / s.probes;
    s.above_threshold = static_cast<double>(above) / s.probes;
  }
  return s;
}

}  // namespace bodyrec
