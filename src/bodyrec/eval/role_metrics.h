// The thesis's role accuracy (digest Ch4, evaluation): on sampled frames, (leader correct + member
// correct) / boxes, where "member correct" includes non-members correctly called non-members. Labelled
// boxes are matched one-to-one to the system's boxes by IoU (optimal assignment); an unmatched labelled
// box counts as wrong. A potential member counts as a member.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "bodyrec/core/geometry.h"
#include "bodyrec/core/role.h"

namespace bodyrec {

struct RoleBox {
  Box box;
  Role role = Role::kUnknown;
};

struct RoleScores {
  int frames = 0;
  int boxes = 0;            // labelled boxes
  int matched = 0;          // labelled boxes matched to a system box
  int leader_correct = 0;   // labelled leaders called leader
  int member_correct = 0;   // labelled members called member, and non-members called non-member
  double accuracy = 0;          // (leader_correct + member_correct) / boxes
  double accuracy_matched = 0;  // ... / matched (the detector's misses left out)
  std::map<std::string, std::map<std::string, int>> confusion;  // labelled role -> system role -> count
};

class RoleEvaluator {
 public:
  explicit RoleEvaluator(double iou_threshold = 0.5) : iou_threshold_(iou_threshold) {}
  void add_frame(const std::vector<RoleBox>& labelled, const std::vector<RoleBox>& system);
  RoleScores scores() const;

 private:
  double iou_threshold_;
  RoleScores s_;
};

}  // namespace bodyrec
