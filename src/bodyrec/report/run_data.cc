#include "bodyrec/report/run_data.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "bodyrec/core/error.h"

namespace bodyrec::report {
namespace {

using nlohmann::json;

// A field reader that names the file, line and field in every error.
struct Where {
  const std::string& name;
  int line;
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(name + ":" + std::to_string(line) + ": " + what);
  }
  const json& field(const json& j, const char* key) const {
    if (!j.is_object() || !j.contains(key)) fail(std::string("missing field '") + key + "'");
    return j.at(key);
  }
  double number(const json& j, const char* key) const {
    const json& v = field(j, key);
    if (!v.is_number()) fail(std::string("field '") + key + "' is not a number");
    return v.get<double>();
  }
  int integer(const json& j, const char* key) const {
    const json& v = field(j, key);
    if (!v.is_number_integer()) fail(std::string("field '") + key + "' is not an integer");
    return v.get<int>();
  }
  std::string text(const json& j, const char* key, const std::string& fallback = "") const {
    if (!j.contains(key) || j.at(key).is_null()) return fallback;
    if (!j.at(key).is_string()) fail(std::string("field '") + key + "' is not a string");
    return j.at(key).get<std::string>();
  }
  Box box(const json& j, const char* key) const {
    const json& v = field(j, key);
    if (!v.is_array() || v.size() != 4) fail(std::string("field '") + key + "' is not [x, y, w, h]");
    for (const auto& e : v)
      if (!e.is_number()) fail(std::string("field '") + key + "' is not [x, y, w, h]");
    return Box(v[0].get<double>(), v[1].get<double>(), v[2].get<double>(), v[3].get<double>());
  }
  const json& array(const json& j, const char* key) const {
    const json& v = field(j, key);
    if (!v.is_array()) fail(std::string("field '") + key + "' is not an array");
    return v;
  }
  StageTimes ms(const json& row) const {
    StageTimes out;
    if (!row.contains("ms")) return out;
    if (!row["ms"].is_object()) fail("field 'ms' is not an object");
    for (const auto& [stage, v] : row["ms"].items()) {
      if (!v.is_number()) fail("field 'ms." + stage + "' is not a number");
      out.emplace_back(stage, v.get<double>());
    }
    return out;
  }
};

GroupsFrameRow groups_row(const json& row, const Where& w) {
  GroupsFrameRow r;
  r.frame = w.integer(row, "frame");
  r.time = row.contains("time") ? w.number(row, "time") : 0.0;
  for (const auto& p : w.array(row, "people")) {
    GroupsPerson person;
    // segment and landmark lines also list "people", without track ids: not runs a report is made of.
    if (p.is_object() && !p.contains("id"))
      w.fail("a person without 'id': not a groups run (report reads the --jsonl of groups or reid, not of "
             "segment or landmark)");
    person.id = w.integer(p, "id");
    person.box = w.box(p, "box");
    person.role = w.text(p, "role", "unknown");
    person.group = p.contains("group") ? w.integer(p, "group") : -1;
    person.state = w.text(p, "state");
    r.people.push_back(person);
  }
  if (row.contains("leaders"))
    for (const auto& l : w.array(row, "leaders")) {
      GroupsLeader leader;
      leader.id = l.contains("id") ? w.integer(l, "id") : -1;
      leader.group = l.contains("group") ? w.integer(l, "group") : -1;
      leader.state = w.text(l, "state");
      if (l.contains("box")) leader.box = w.box(l, "box");
      if (l.contains("direction")) {
        leader.degrees = w.number(l["direction"], "degrees");
        leader.magnitude = w.number(l["direction"], "magnitude");
      }
      r.leaders.push_back(leader);
    }
  r.ms = w.ms(row);
  return r;
}

std::optional<int> optional_int(const json& j, const char* key, const Where& w) {
  if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
  return w.integer(j, key);
}

ReidFrameRow reid_row(const json& row, const Where& w) {
  ReidFrameRow r;
  r.frame = w.integer(row, "frame");
  r.time = row.contains("time") ? w.number(row, "time") : 0.0;
  for (const auto& b : w.array(row, "bodies")) {
    ReidBody body;
    body.track = w.integer(b, "track");
    body.user = optional_int(b, "user", w);
    body.view = w.text(b, "view");
    if (b.contains("box")) body.box = w.box(b, "box");
    r.bodies.push_back(body);
  }
  if (row.contains("events"))
    for (const auto& e : w.array(row, "events")) {
      ReidEvent event;
      event.kind = w.text(e, "kind");
      if (event.kind.empty()) w.fail("event without 'kind'");
      event.user = optional_int(e, "user", w);
      event.track = e.contains("track") && !e["track"].is_null() ? w.integer(e, "track") : -1;
      event.view = w.text(e, "view");
      if (e.contains("score") && !e["score"].is_null()) event.score = w.number(e, "score");
      r.events.push_back(event);
    }
  r.ms = w.ms(row);
  if (row.contains("arrival")) r.arrival = w.number(row, "arrival");
  if (row.contains("wall")) r.wall = w.number(row, "wall");
  if (row.contains("dropped")) r.dropped = w.integer(row, "dropped");
  if (row.contains("end")) {
    if (!row["end"].is_boolean()) w.fail("field 'end' is not true or false");
    r.end = row["end"].get<bool>();
  }
  return r;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

const char* to_string(RunKind kind) { return kind == RunKind::kGroups ? "groups" : "re-identification"; }

int RunData::frame_count() const {
  if (kind == RunKind::kGroups) return static_cast<int>(groups.size());
  return static_cast<int>(std::count_if(reid.begin(), reid.end(), [](const ReidFrameRow& r) { return !r.end; }));
}

RunData parse_run(std::istream& in, const std::string& name) {
  RunData run;
  run.name = name;
  std::string line;
  int number = 0;
  bool any = false;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const Where w{name, number};
    json row;
    try {
      row = json::parse(line);
    } catch (const json::exception& e) {
      w.fail(std::string("not JSON (") + e.what() + ")");
    }
    if (!row.is_object()) w.fail("row is not a JSON object");
    RunKind kind;
    if (row.contains("people")) kind = RunKind::kGroups;
    else if (row.contains("bodies")) kind = RunKind::kReid;
    else w.fail("neither 'people' (groups run) nor 'bodies' (re-identification run)");
    if (any && kind != run.kind)
      w.fail(std::string("a ") + to_string(kind) + " row in a " + to_string(run.kind) + " run");
    run.kind = kind;
    any = true;
    if (kind == RunKind::kGroups) run.groups.push_back(groups_row(row, w));
    else run.reid.push_back(reid_row(row, w));
  }
  if (!any) throw InputError(name + ": no JSON rows (empty run)");
  return run;
}

RunData read_run(const std::string& path) {
  std::istringstream in(slurp(path));
  return parse_run(in, path);
}

const char* to_string(EvalKind kind) {
  switch (kind) {
    case EvalKind::kReid: return "re-identification (eval reid)";
    case EvalKind::kReidStream: return "re-identification stream (eval reid-stream)";
    case EvalKind::kGroups: return "groups (eval groups)";
    case EvalKind::kLandmarks: return "landmarks (eval landmarks)";
    case EvalKind::kLandmarkErrors: return "landmark errors per person (eval landmarks --per-person)";
    case EvalKind::kTrack: return "tracking (eval track)";
    case EvalKind::kDetect: return "detection (eval detect)";
    case EvalKind::kRoles: return "roles (eval roles)";
    case EvalKind::kSegment: return "segmentation (eval segment)";
  }
  return "?";
}

EvalResult parse_eval(const std::string& text, const std::string& name) {
  EvalResult r;
  r.name = name;
  std::vector<std::pair<int, json>> objects;  // every line that is a JSON object, with its number
  std::istringstream in(text);
  std::string line;
  int number = 0, last_number = 0;
  std::string last;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    last = line;
    last_number = number;
    try {
      json j = json::parse(line);
      if (j.is_object()) objects.emplace_back(number, std::move(j));
    } catch (const json::exception&) {
    }
  }
  if (last.empty()) throw InputError(name + ": empty evaluation file");
  const Where w{name, last_number};
  if (objects.empty() || objects.back().first != last_number)
    w.fail("the last line is not the JSON object of an eval command run with --json");
  const json& j = objects.back().second;
  if (j.contains("rel_height") && j.contains("mean_px")) {  // per-person landmark errors
    r.kind = EvalKind::kLandmarkErrors;
    for (const auto& [n, row] : objects) {
      const Where wl{name, n};
      r.errors_rel_height.push_back(wl.number(row, "rel_height"));
      r.errors_px.push_back(wl.number(row, "mean_px"));
    }
    return r;
  }
  r.summary = j;
  if (j.contains("rank1") || j.contains("cmc")) {
    r.kind = EvalKind::kReid;
    if (j.contains("cmc")) {
      for (const auto& v : w.array(j, "cmc")) {
        if (!v.is_number()) w.fail("field 'cmc' holds a non-number");
        r.cmc.push_back(v.get<double>());
      }
    }
  } else if (j.contains("splits") && j.contains("merges")) {
    r.kind = EvalKind::kReidStream;
  } else if (j.contains("pair_f1")) {
    r.kind = EvalKind::kGroups;
  } else if (j.contains("mean_rel_height")) {
    r.kind = EvalKind::kLandmarks;
  } else if (j.contains("mota")) {
    r.kind = EvalKind::kTrack;
  } else if (j.contains("ap50")) {
    r.kind = EvalKind::kDetect;
  } else if (j.contains("accuracy_matched") || j.contains("confusion")) {
    r.kind = EvalKind::kRoles;
  } else if (j.contains("mean_iou")) {
    r.kind = EvalKind::kSegment;
  } else {
    w.fail("unknown evaluation (no rank1/cmc, splits, pair_f1, mean_rel_height, mota, ap50, confusion or mean_iou)");
  }
  return r;
}

EvalResult read_eval(const std::string& path) { return parse_eval(slurp(path), path); }

}  // namespace bodyrec::report
