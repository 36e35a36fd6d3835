#include "gallery_spools.h"

#include <filesystem>
#include <fstream>
#include <set>

#include "bodyrec/core/error.h"
#include "bodyrec/events/event_spool.h"
#include "bodyrec/events/mqtt_target.h"

namespace bodyrec::cli {

namespace fs = std::filesystem;

namespace {

// One line to `out` (none when it is null).
template <typename... Args>
void say(std::FILE* out, const char* format, Args... args) {
  if (out) std::fprintf(out, format, args...);
}

// Absolute, with symbolic links resolved as far as the path exists: the file a spool's lock and rename
// act on, and the one name compared to tell a listed spool from one given with --events-spool.
std::string real_path(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  const fs::path real = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal().string() : real.string();
}

nlohmann::json scrub_one(const std::string& path, const std::string& host,
                         const std::function<bool(int64_t)>& erased, std::FILE* out, int& failed) {
  nlohmann::json j = {{"path", path}, {"host", host}, {"removed", 0}};
  try {
    const SpoolScrub s = EventSpool::scrub(path, [&](const SpooledEvent& e) {
      const std::optional<int64_t> user = event_user(e.payload);
      return user && erased(*user);
    });
    switch (s.state) {
      case SpoolScrub::State::kScrubbed:
        say(out, "events spool %s: withdrew %zu undelivered events of erased users\n", path.c_str(), s.removed);
        j["status"] = "scrubbed";
        j["removed"] = s.removed;
        break;
      case SpoolScrub::State::kInUse:
        say(out, "events spool %s: in use by a running reid, which withdraws erased users' events itself\n",
                     path.c_str());
        j["status"] = "in_use";
        break;
      case SpoolScrub::State::kOtherOwner:
        say(out, "events spool %s: another user's file, left as it is; run the erasure as its owner or root\n",
                     path.c_str());
        j["status"] = "other_owner";
        break;
    }
  } catch (const Error& e) {
    say(out, "events spool %s: not scrubbed: %s\n", path.c_str(), e.what());
    j["status"] = "error";
    j["error"] = e.what();
    ++failed;
  }
  return j;
}

}  // namespace

std::string this_machine() {
  // Read once: it does not change while the process runs, and every listed spool asks.
  static const std::string machine = [] {
    std::ifstream in("/etc/machine-id");
    std::string id;
    if (in >> id && !id.empty()) return id;
    return "host:" + host_name();
  }();
  return machine;
}

const char* spool_place_name(SpoolPlace place) {
  switch (place) {
    case SpoolPlace::kHere: return "here";
    case SpoolPlace::kMissing: return "missing";
    case SpoolPlace::kUnreachable: return "unreachable";
    case SpoolPlace::kElsewhere: return "elsewhere";
  }
  return "";
}

SpoolPlace spool_place(const EventSpoolRecord& spool, std::string* error) {
  if (spool.machine != this_machine()) return SpoolPlace::kElsewhere;
  std::error_code ec;
  const fs::file_status status = fs::status(spool.path, ec);
  if (status.type() == fs::file_type::not_found) {
    // Gone only when its folder is there to say so (not an unmounted disk).
    const fs::file_status parent = fs::status(fs::path(spool.path).parent_path(), ec);
    if (parent.type() == fs::file_type::directory) return SpoolPlace::kMissing;
  }
  if (status.type() == fs::file_type::regular) return SpoolPlace::kHere;
  if (error) *error = ec ? ec.message() : "not a file";
  return SpoolPlace::kUnreachable;
}

void list_run_spool(Gallery& gallery, const RunEvents& events) {
  if (!events.publisher) return;
  EventSpoolRecord r;
  r.machine = this_machine();
  r.host = host_name();
  r.path = real_path(events.spool);
  r.sensor = events.sensor;
  try {
    gallery.note_event_spool(r);
  } catch (const ProcessingError& e) {
    std::fprintf(stderr,
                 "bodyrec: %s does not list the event spool %s (%s): name it to gallery forget with --events-spool "
                 "(docs/events.md)\n",
                 gallery.path().c_str(), r.path.c_str(), e.what());
  }
}

void check_given_spools(const std::vector<std::string>& given) {
  for (const std::string& path : given)
    if (!fs::is_regular_file(path)) throw InputError(path + ": no event spool there (--events-spool)");
}

SpoolScrubs scrub_spools(Gallery& gallery, const std::vector<std::string>& given,
                         const std::function<bool(int64_t user)>& erased, std::FILE* out) {
  const std::string host = host_name();
  SpoolScrubs result;
  std::set<std::string> done;
  for (const std::string& path : given) {
    const std::string real = real_path(path);
    if (done.insert(real).second) result.spools.push_back(scrub_one(real, host, erased, out, result.failed));
  }
  for (const EventSpoolRecord& r : gallery.event_spools()) {
    std::string error;
    const SpoolPlace place = spool_place(r, &error);
    if (place == SpoolPlace::kElsewhere) {
      say(out,
                   "events spool %s on %s: not on this machine; its next reid run there withdraws erased users' "
                   "events, or run gallery spools --scrub there\n",
                   r.path.c_str(), r.host.c_str());
      result.spools.push_back({{"path", r.path}, {"host", r.host}, {"status", "elsewhere"}, {"removed", 0}});
      continue;
    }
    if (!done.insert(r.path).second) continue;
    if (place == SpoolPlace::kMissing) {
      gallery.drop_event_spool(r.machine, r.path);
      say(out, "events spool %s: no longer there; taken off the gallery's list\n", r.path.c_str());
      result.spools.push_back({{"path", r.path}, {"host", r.host}, {"status", "missing"}, {"removed", 0}});
    } else if (place == SpoolPlace::kUnreachable) {
      say(out, "events spool %s: not scrubbed: %s\n", r.path.c_str(), error.c_str());
      result.spools.push_back({{"path", r.path}, {"host", r.host}, {"status", "error"}, {"removed", 0}, {"error", error}});
      ++result.failed;
    } else {
      result.spools.push_back(scrub_one(r.path, host, erased, out, result.failed));
    }
  }
  return result;
}

}  // namespace bodyrec::cli
