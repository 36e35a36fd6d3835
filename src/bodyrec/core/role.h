// The roles a group-leader tracker gives the people it sees (thesis Ch4, Table 4.1): vocabulary shared by
// the groups stage, the role labels it is scored against (io/roles_csv.h), the metrics and the report.
#pragma once

#include <optional>
#include <string>

namespace bodyrec {

// The thesis's tags: 1 member, 2 non-member, 3 leader are permanent, 4 potential member is transient.
// kUnknown: not assigned yet (no leader found so far).
enum class Role { kUnknown = 0, kMember = 1, kNonMember = 2, kLeader = 3, kPotentialMember = 4 };

// "unknown", "member", "non-member", "leader", "potential-member".
std::string to_string(Role role);
// The inverse, also accepting "non_member"/"nonmember" and "potential"; nullopt for anything else.
std::optional<Role> parse_role(const std::string& text);

}  // namespace bodyrec
