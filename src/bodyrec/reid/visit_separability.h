// How well a matcher's descriptors tell people apart across visits (diagnosis of the colour path, with
// true bodies): descriptors are added per true person and per visit (a tracking id: the person in view
// without a break); each descriptor of a person seen in at least two visits is matched to its nearest
// neighbour among the descriptors of every other visit (all people), and counts as right when that
// neighbour is the same person. Same-visit descriptors are left out: they would match trivially.
//
//   VisitSeparability sep(matcher);
//   sep.add(identity, tracking_id, matcher.describe(image));   // per clear scan
//   const VisitSeparability::Score s = sep.score();             // s.nn_accuracy over s.probes
#pragma once

#include <cstdint>
#include <vector>

#include "bodyrec/reid/appearance_matcher.h"

namespace bodyrec {

class VisitSeparability {
 public:
  // `matcher` must outlive this object.
  explicit VisitSeparability(const AppearanceMatcher& matcher) : matcher_(matcher) {}
  void add(int person, uint64_t visit, std::vector<float> descriptor);

  struct Score {
    int probes = 0;             // descriptors of people seen in at least two visits
    double nn_accuracy = 0;     // share of probes whose nearest other-visit descriptor is the same person
    double above_threshold = 0; // share of probes whose best same-person other-visit similarity > threshold
  };
  Score score() const;

 private:
  struct Entry {
    int person;
    uint64_t visit;
    std::vector<float> d;
  };
  const AppearanceMatcher& matcher_;
  std::vector<Entry> entries_;
};

}  // namespace bodyrec
