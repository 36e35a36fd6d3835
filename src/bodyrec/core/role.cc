#include "bodyrec/core/role.h"

#include <cctype>

namespace bodyrec {

std::string to_string(Role role) {
  switch (role) {
    case Role::kMember: return "member";
    case Role::kNonMember: return "non-member";
    case Role::kLeader: return "leader";
    case Role::kPotentialMember: return "potential-member";
    case Role::kUnknown: break;
  }
  return "unknown";
}

std::optional<Role> parse_role(const std::string& text) {
  std::string t;
  for (char c : text)
    if (c != ' ' && c != '\t' && c != '\r') t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "leader") return Role::kLeader;
  if (t == "member") return Role::kMember;
  if (t == "non-member" || t == "non_member" || t == "nonmember") return Role::kNonMember;
  if (t == "potential-member" || t == "potential_member" || t == "potential") return Role::kPotentialMember;
  if (t == "unknown") return Role::kUnknown;
  return std::nullopt;
}

}  // namespace bodyrec
