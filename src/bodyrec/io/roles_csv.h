// Hand-labelled roles for `eval roles`: CSV rows frame,x,y,w,h,role (frame 0-based, box in pixels, role
// leader | member | non-member). A first line starting with "frame" is a header; '#' lines are comments.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "bodyrec/core/geometry.h"
#include "bodyrec/core/role.h"

namespace bodyrec {

struct RoleLabel {
  int frame = 0;
  Box box;
  Role role = Role::kUnknown;
};

// Throws InputError "<file>:<line>: ..." naming the field for a missing file, a wrong field count, a
// non-numeric or negative value, an empty box or an unknown role.
std::vector<RoleLabel> read_roles_csv(const std::string& path);
// The same from a stream; `name` names the source in messages.
std::vector<RoleLabel> read_roles_csv(std::istream& in, const std::string& name);

}  // namespace bodyrec
