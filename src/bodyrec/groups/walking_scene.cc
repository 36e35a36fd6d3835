#include "bodyrec/groups/walking_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"

namespace bodyrec {
namespace {

std::ifstream open_text(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": no such file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open");
  return in;
}

// obsmat stores integers as floats ("7.8000000e+02"); they must still be whole and non-negative.
int parse_index(const std::string& text, const std::string& where, const char* field) {
  const double v = parse_finite_field(text, where, field);
  if (v < 0 || v != std::floor(v) || v > 1e9)
    throw InputError(where + ": field '" + field + "' is not a non-negative integer: '" + text + "'");
  return static_cast<int>(v);
}

}  // namespace

std::vector<ObsmatRow> read_obsmat(const std::string& path) {
  std::ifstream in = open_text(path);
  return read_obsmat(in, path);
}

std::vector<ObsmatRow> read_obsmat(std::istream& in, const std::string& path) {
  static const char* const kFields[] = {"frame", "ped", "pos_x", "pos_z", "pos_y", "v_x", "v_z", "v_y"};
  std::vector<ObsmatRow> rows;
  std::set<std::pair<int, int>> seen;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream s(line);
    std::vector<std::string> f;
    for (std::string field; s >> field;) f.push_back(field);
    if (f.empty()) continue;
    const std::string where = path + ":" + std::to_string(number);
    if (f.size() != 8)
      throw InputError(where + ": expected 8 fields (frame ped pos_x pos_z pos_y v_x v_z v_y), got " +
                       std::to_string(f.size()));
    double v[8];
    for (int i = 2; i < 8; ++i) v[i] = parse_finite_field(f[i], where, kFields[i]);
    ObsmatRow r;
    r.frame = parse_index(f[0], where, kFields[0]);
    r.person = parse_index(f[1], where, kFields[1]);
    r.position = {v[2], v[4]};
    r.velocity = {v[5], v[7]};
    if (!seen.insert({r.frame, r.person}).second)
      throw InputError(where + ": person " + std::to_string(r.person) + " appears twice in frame " +
                       std::to_string(r.frame));
    rows.push_back(r);
  }
  if (in.bad()) throw InputError(path + ": read error");
  if (rows.empty()) throw InputError(path + ": no trajectory rows");
  std::sort(rows.begin(), rows.end(), [](const ObsmatRow& a, const ObsmatRow& b) {
    return a.frame != b.frame ? a.frame < b.frame : a.person < b.person;
  });
  return rows;
}

std::vector<std::vector<int>> read_groups(const std::string& path) {
  std::ifstream in = open_text(path);
  return read_groups(in, path);
}

std::vector<std::vector<int>> read_groups(std::istream& in, const std::string& path) {
  std::vector<std::vector<int>> groups;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream s(line);
    std::vector<int> ids;
    const std::string where = path + ":" + std::to_string(number);
    for (std::string field; s >> field;) {
      char* end = nullptr;
      const long id = std::strtol(field.c_str(), &end, 10);
      if (*end != '\0' || id < 0 || id > 1000000000)
        throw InputError(where + ": person id is not a non-negative integer: '" + field + "'");
      if (std::find(ids.begin(), ids.end(), static_cast<int>(id)) == ids.end()) ids.push_back(static_cast<int>(id));
    }
    if (!ids.empty()) groups.push_back(ids);
  }
  if (in.bad()) throw InputError(path + ": read error");
  return groups;
}

bool WalkingScene::together(int a, int b) const {
  for (const auto& g : groups)
    if (std::find(g.begin(), g.end(), a) != g.end() && std::find(g.begin(), g.end(), b) != g.end())
      return true;
  return false;
}

double estimate_seconds_per_frame(const std::vector<ObsmatRow>& rows, const std::string& where) {
  std::map<int, const ObsmatRow*> last;  // person -> previous row (rows are in frame order)
  std::vector<double> ratios;
  for (const auto& r : rows) {
    auto it = last.find(r.person);
    if (it != last.end()) {
      const ObsmatRow& p = *it->second;
      const double speed = std::hypot(r.velocity.x, r.velocity.y);
      const int gap = r.frame - p.frame;
      // Positions or velocities near the double range overflow to inf (and inf / inf to NaN): such a sample
      // says nothing about the frame period, and a NaN would break the median's ordering.
      const double ratio = cv::norm(r.position - p.position) / (speed * gap);
      if (speed > 0.3 && gap > 0 && std::isfinite(ratio)) ratios.push_back(ratio);
    }
    last[r.person] = &r;
  }
  if (ratios.size() < 10)
    throw InputError(where + ": too few moving samples (" + std::to_string(ratios.size()) +
                     ") to estimate the frame period; give it explicitly");
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  const double period = ratios[ratios.size() / 2];
  // A period of 0 would put every frame at time 0 (positions that stay put while the velocities say the
  // people move).
  if (!(period > 0))
    throw InputError(where + ": the frame period estimated from " + std::to_string(ratios.size()) +
                     " moving samples is 0 (positions do not change while velocities say they do); give it explicitly");
  return period;
}

WalkingScene read_walking_scene(const std::string& dir, double seconds_per_frame) {
  const std::filesystem::path root(dir);
  if (!std::filesystem::is_directory(root)) throw InputError(dir + ": not a scene folder");
  WalkingScene scene;
  scene.name = std::filesystem::absolute(root).lexically_normal().filename().string();
  if (scene.name.empty()) scene.name = std::filesystem::absolute(root).lexically_normal().parent_path().filename().string();
  scene.rows = read_obsmat((root / "obsmat.txt").string());
  for (auto& g : read_groups((root / "groups.txt").string()))
    if (g.size() >= 2) scene.groups.push_back(std::move(g));
  scene.seconds_per_frame = seconds_per_frame > 0
                                ? seconds_per_frame
                                : estimate_seconds_per_frame(scene.rows, (root / "obsmat.txt").string());
  return scene;
}

}  // namespace bodyrec
