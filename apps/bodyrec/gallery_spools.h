// The event spools a gallery lists (schema 4, EventSpoolRecord): a `reid --events` run lists its spool in
// its gallery, and `gallery forget|purge|prune` take the erased users' undelivered events out of every
// listed spool on this machine, besides those named with --events-spool; `gallery spools` lists them.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bodyrec/store/gallery.h"
#include "event_options.h"

namespace bodyrec::cli {

// This machine's name as spools are listed under it (gethostname; "localhost" when it has none).
std::string this_host();

// Lists the run's spool in `gallery` (nothing without --events). A gallery that refuses the write (a
// PostgreSQL sensor role without the grant of docs/postgresql-roles.sql) costs a warning on stderr, not
// the run: the spool then has to be named to `gallery forget --events-spool`.
void list_run_spool(Gallery& gallery, const RunEvents& events);

// Takes the undelivered events of every user for whom `erased` is true out of each spool named in `given`
// (InputError before anything when one is not a file: check_given_spools) and of each spool `gallery`
// lists on this machine (EventSpool::scrub). A listed spool whose file is gone is taken off the list; one
// on another machine is only reported (its next reid run there withdraws the events itself, as does
// `gallery spools --scrub` run there). Writes one line per spool on stdout; returns
// [{path, host, status, removed}] with status "scrubbed", "in_use" (a running reid holds it and withdraws
// them itself), "missing" or "elsewhere".
nlohmann::json scrub_spools(Gallery& gallery, const std::vector<std::string>& given,
                            const std::function<bool(int64_t user)>& erased);
void check_given_spools(const std::vector<std::string>& given);

}  // namespace bodyrec::cli
