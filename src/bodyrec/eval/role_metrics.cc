#include "bodyrec/eval/role_metrics.h"

#include "bodyrec/tracking/assignment.h"

namespace bodyrec {

void RoleEvaluator::add_frame(const std::vector<RoleBox>& labelled, const std::vector<RoleBox>& system) {
  ++s_.frames;
  s_.boxes += static_cast<int>(labelled.size());
  std::vector<std::vector<double>> overlap(labelled.size(), std::vector<double>(system.size()));
  for (size_t i = 0; i < labelled.size(); ++i)
    for (size_t j = 0; j < system.size(); ++j) overlap[i][j] = iou(labelled[i].box, system[j].box);
  std::vector<int> match(labelled.size(), -1);
  for (const auto& [i, j] : max_score_assignment(overlap, iou_threshold_)) match[i] = j;
  for (size_t i = 0; i < labelled.size(); ++i) {
    const Role truth = labelled[i].role;
    Role said = match[i] < 0 ? Role::kUnknown : system[match[i]].role;
    if (said == Role::kPotentialMember) said = Role::kMember;
    s_.confusion[to_string(truth)][match[i] < 0 ? "missed" : to_string(said)]++;
    if (match[i] < 0) continue;
    ++s_.matched;
    if (said != truth) continue;
    if (truth == Role::kLeader) ++s_.leader_correct;
    else if (truth == Role::kMember || truth == Role::kNonMember) ++s_.member_correct;
  }
}

RoleScores RoleEvaluator::scores() const {
  RoleScores s = s_;
  const double correct = s.leader_correct + s.member_correct;
  s.accuracy = s.boxes ? correct / s.boxes : 0.0;
  s.accuracy_matched = s.matched ? correct / s.matched : 0.0;
  return s;
}

}  // namespace bodyrec
