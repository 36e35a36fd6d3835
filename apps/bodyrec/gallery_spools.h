// The event spools a gallery lists (schema 4, EventSpoolRecord): a `reid --events` run lists its spool in
// its gallery, and `gallery forget|purge|prune` (and `reid --prune-unseen-for`) take the erased users'
// undelivered events out of every listed spool on this machine, besides those named with --events-spool;
// `gallery spools` lists them.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bodyrec/store/gallery.h"
#include "event_options.h"

namespace bodyrec::cli {

// This machine as spools are listed under it: /etc/machine-id (host names repeat: two sensors may both be
// "raspberrypi"), or "host:NAME" where there is none (some containers).
std::string this_machine();

// Where a listed spool is, seen from this machine.
enum class SpoolPlace { kHere, kMissing, kUnreachable, kElsewhere };
const char* spool_place_name(SpoolPlace place);  // "here", "missing", "unreachable", "elsewhere"
// kUnreachable: on this machine, but its status cannot be read (a directory this user may not enter, a
// disk not mounted): it may still hold events, so it stays listed. `error` says why.
SpoolPlace spool_place(const EventSpoolRecord& spool, std::string* error = nullptr);

// Lists the run's spool in `gallery` (nothing without --events). A gallery that refuses the write (a
// PostgreSQL sensor role without the grant of docs/postgresql-roles.sql) costs a line on stderr, not the
// run: the spool then has to be named to `gallery forget --events-spool`.
void list_run_spool(Gallery& gallery, const RunEvents& events);

// InputError naming the first path in `given` that is not a file (--events-spool), before anything is erased.
void check_given_spools(const std::vector<std::string>& given);

struct SpoolScrubs {
  nlohmann::json spools = nlohmann::json::array();  // [{path, host, status, removed[, error]}]
  int failed = 0;                                   // spools with status "error"
};

// Takes the undelivered events of every user for whom `erased` is true out of each spool named in `given`
// and of each spool `gallery` lists on this machine (EventSpool::scrub), writing one line per spool to
// `out` (null: none). Status per spool: "scrubbed"; "in_use" (a running reid holds it and withdraws them itself);
// "other_owner" (another user's file: run the erasure as its owner or root); "missing" (listed, file gone:
// taken off the list); "elsewhere" (listed on another machine: its next reid run withdraws them, or
// `gallery spools --scrub` there); "error" (could not be read or rewritten: the message is kept, the
// other spools are still scrubbed, and the caller reports the failure after its own output).
SpoolScrubs scrub_spools(Gallery& gallery, const std::vector<std::string>& given,
                         const std::function<bool(int64_t user)>& erased, std::FILE* out);

}  // namespace bodyrec::cli
