#include "bodyrec/io/roles_csv.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"

namespace bodyrec {

std::vector<RoleLabel> read_roles_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the roles CSV");
  return read_roles_csv(in, path);
}

std::vector<RoleLabel> read_roles_csv(std::istream& in, const std::string& path) {
  std::vector<RoleLabel> labels;
  std::string line;
  static const char* const kFields[] = {"frame", "x", "y", "w", "h", "role"};
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 byte-order mark
    if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    if (labels.empty() && line.rfind("frame", 0) == 0) continue;  // header
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (fields.size() != 6)
      throw InputError(where + "expected 6 fields (frame,x,y,w,h,role), found " + std::to_string(fields.size()));
    double v[5];
    for (int i = 0; i < 5; ++i) {
      const auto parsed = parse_double(fields[i]);
      if (!parsed || !std::isfinite(*parsed))
        throw InputError(where + "field '" + kFields[i] + "' is not a number: '" + fields[i] + "'");
      v[i] = *parsed;
    }
    if (v[0] < 0 || v[0] != std::floor(v[0]) || v[0] > 1e9)
      throw InputError(where + "field 'frame' must be a non-negative integer");
    if (!(v[3] > 0 && v[4] > 0)) throw InputError(where + "the box needs a positive width and height");
    const auto role = parse_role(fields[5]);
    if (!role || *role == Role::kUnknown || *role == Role::kPotentialMember)
      throw InputError(where + "field 'role' must be leader, member or non-member, not '" + fields[5] + "'");
    labels.push_back({static_cast<int>(v[0]), Box(v[1], v[2], v[3], v[4]), *role});
  }
  return labels;
}

}  // namespace bodyrec
