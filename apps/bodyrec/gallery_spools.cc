#include "gallery_spools.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <set>

#include "bodyrec/core/error.h"
#include "bodyrec/events/event_spool.h"

namespace bodyrec::cli {

namespace {

std::string absolute_path(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec);
  return ec ? std::filesystem::absolute(path).lexically_normal().string() : p.string();
}

nlohmann::json scrub_one(const std::string& path, const std::string& host,
                         const std::function<bool(int64_t)>& erased) {
  const SpoolScrub s = EventSpool::scrub(path, [&](const SpooledEvent& e) {
    const std::optional<int64_t> user = event_user(e.payload);
    return user && erased(*user);
  });
  if (s.in_use)
    std::printf("events spool %s: in use by a running reid, which withdraws these users' events itself\n", path.c_str());
  else
    std::printf("events spool %s: withdrew %zu undelivered events of these users\n", path.c_str(), s.removed);
  return {{"path", path}, {"host", host}, {"status", s.in_use ? "in_use" : "scrubbed"}, {"removed", s.removed}};
}

}  // namespace

std::string this_host() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || !name[0]) return "localhost";
  return name;
}

void list_run_spool(Gallery& gallery, const RunEvents& events) {
  if (!events.publisher) return;
  EventSpoolRecord r;
  r.host = this_host();
  r.path = absolute_path(events.spool);
  r.sensor = events.sensor;
  try {
    gallery.note_event_spool(r);
  } catch (const ProcessingError& e) {
    std::fprintf(stderr,
                 "bodyrec: warning: %s does not list the event spool %s (%s): name it to gallery forget with "
                 "--events-spool (docs/events.md)\n",
                 gallery.path().c_str(), r.path.c_str(), e.what());
  }
}

void check_given_spools(const std::vector<std::string>& given) {
  for (const std::string& path : given)
    if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": no event spool there (--events-spool)");
}

nlohmann::json scrub_spools(Gallery& gallery, const std::vector<std::string>& given,
                            const std::function<bool(int64_t user)>& erased) {
  const std::string host = this_host();
  nlohmann::json out = nlohmann::json::array();
  std::set<std::string> done;
  for (const std::string& path : given)
    if (done.insert(absolute_path(path)).second) out.push_back(scrub_one(path, host, erased));
  for (const EventSpoolRecord& r : gallery.event_spools()) {
    if (r.host != host) {
      std::printf("events spool %s on %s: not on this machine; its next reid run there withdraws these users' "
                  "events, or run gallery spools --scrub there\n",
                  r.path.c_str(), r.host.c_str());
      out.push_back({{"path", r.path}, {"host", r.host}, {"status", "elsewhere"}, {"removed", 0}});
      continue;
    }
    if (!done.insert(absolute_path(r.path)).second) continue;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(r.path, ec)) {
      gallery.drop_event_spool(r.host, r.path);
      std::printf("events spool %s: no longer there; taken off the gallery's list\n", r.path.c_str());
      out.push_back({{"path", r.path}, {"host", r.host}, {"status", "missing"}, {"removed", 0}});
      continue;
    }
    out.push_back(scrub_one(r.path, host, erased));
  }
  return out;
}

}  // namespace bodyrec::cli
