// `bodyrec gallery`: inspect and manage the persistent re-identification gallery (issue 6/7): list users,
// show one, export one (right of access), forget one, purge all, prune by retention time (each erasure also
// scrubs the reid event spools the gallery lists: gallery_spools.h), list those spools; the same on an
// SQLite file and on a PostgreSQL database (issue 47). Only `init` creates a gallery: elsewhere a missing
// file or an empty database is an input error.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_export.h"
#include "bodyrec/store/gallery_json.h"
#include "command.h"
#include "gallery_options.h"
#include "gallery_spools.h"

namespace bodyrec::cli {
namespace {

struct GalleryCommand {
  GalleryCliOptions gallery;
  std::string user, dir, unseen_for, label;
  std::vector<std::string> spools;  // --events-spool: files to take the erased users' events out of
  std::vector<std::string> drop;    // gallery spools --drop: paths to take off the list
  bool json = false, yes = false, dry_run = false, scrub = false;

  Gallery open(bool read_only, bool create = false) const {
    GalleryOptions o;
    o.read_only = read_only;
    o.create = create;
    return Gallery(gallery.path, o);
  }
};

std::string erased_summary(const EraseReport& r) {
  return std::to_string(r.scans) + " scans (" + std::to_string(r.images) + " images, " + std::to_string(r.masks) +
         " masks, their features), " + std::to_string(r.events) + " events";
}

nlohmann::json erase_json(const EraseReport& r, const nlohmann::json& spools) {
  return {{"users", r.users},   {"scans", r.scans},       {"images", r.images},
          {"masks", r.masks},   {"events", r.events},     {"scrubbed", r.scrubbed},
          {"checkpointed", r.checkpointed}, {"spools", spools}};
}

// The erased users' events leave the spools named with --events-spool and those the gallery lists.
SpoolScrubs scrub_erased(Gallery& g, const GalleryCommand& c, const EraseReport& r) {
  return scrub_spools(
      g, c.spools, [&](int64_t user) { return std::find(r.users.begin(), r.users.end(), user) != r.users.end(); },
      stdout);
}

// After the command's own output: spools that could not be scrubbed make the erasure's exit code 4 (the
// users are erased; their events may still be in those files).
void check_scrubs(const SpoolScrubs& s) {
  if (s.failed > 0)
    throw ProcessingError(std::to_string(s.failed) + " event spool" + (s.failed == 1 ? "" : "s") +
                          " not scrubbed (see above); the erased users' events may still be in " +
                          (s.failed == 1 ? "it" : "them"));
}

// The erasure's JSON, then check_scrubs.
void finish_erasure(const GalleryCommand& c, const EraseReport& r, const SpoolScrubs& s) {
  if (c.json) std::printf("%s\n", json_text(erase_json(r, s.spools)).c_str());
  check_scrubs(s);
}

// "vacuumed" when the database was rewritten without the erased rows (gallery.h).
const char* vacuumed(const EraseReport& r) { return r.scrubbed ? "vacuumed" : "not vacuumed"; }

void note_scrub(const EraseReport& r) {
  if (!r.note.empty()) std::printf("note: %s\n", r.note.c_str());
}

void init(const GalleryCommand& c) {
  Gallery g = c.open(false, true);
  std::printf("%s: gallery schema version %d, %d users\n", c.gallery.path.c_str(), kGallerySchemaVersion,
              g.user_count());
}

void list(const GalleryCommand& c) {
  Gallery g = c.open(true);
  const auto users = g.users();
  std::printf("%s: %zu users\n", c.gallery.path.c_str(), users.size());
  if (!users.empty())
    std::printf("%-5s %-12s %-23s %-5s %-20s %s\n", "user", "label", "views", "scans", "first seen", "last seen");
  nlohmann::json all = nlohmann::json::array();
  for (const User& u : users) {
    std::printf("%-5lld %-12s %-23s %-5d %-20s %s\n", static_cast<long long>(u.id),
                u.label.empty() ? "-" : u.label.c_str(), views_column(u.views).c_str(), u.scans,
                format_utc(u.first_seen).c_str(), format_utc(u.last_seen).c_str());
    all.push_back(user_to_json(u));
  }
  if (c.json) std::printf("%s\n", json_text({{"gallery", c.gallery.path}, {"users", all}}).c_str());
}

void show(const GalleryCommand& c) {
  Gallery g = c.open(true);
  const UserId id = g.resolve_user(c.user);
  const User u = *g.user(id);
  const auto scans = g.user_scans(id);
  const auto events = g.events(id);
  std::printf("user %lld%s\ncreated     %s\nfirst seen  %s\nlast seen   %s\n", static_cast<long long>(id),
              u.label.empty() ? "" : (" \"" + u.label + "\"").c_str(), format_utc(u.created).c_str(),
              format_utc(u.first_seen).c_str(), format_utc(u.last_seen).c_str());
  // `time` is the source's clock, `stored`/`logged` the wall clock when the gallery wrote the row ("-":
  // written before schema 3).
  std::printf("%zu scans\n%-5s %-8s %-5s %-5s %-28s %-20s %s\n", scans.size(), "view", "quality", "image", "mask",
              "features", "time", "stored");
  nlohmann::json j = {{"user", user_to_json(u)}};
  j["scans"] = nlohmann::json::array();
  for (const StoredScan& s : scans) {
    const std::string features =
        s.descriptor + " v" + std::to_string(s.descriptor_version) + " " + describe_matrix(s.features);
    std::printf("%-5s %-8.3f %-5s %-5s %-28s %-20s %s\n", view_name(s.view), s.quality,
                s.image_png.empty() ? "no" : "yes", s.mask_png.empty() ? "no" : "yes", features.c_str(),
                format_utc(s.time).c_str(), s.stored ? format_utc(*s.stored).c_str() : "-");
    j["scans"].push_back(scan_to_json(s));
  }
  std::printf("%zu events\n", events.size());
  j["events"] = nlohmann::json::array();
  for (const Event& e : events) {
    std::string line = format_utc(e.time) + "  " + event_kind_name(e.kind);
    if (e.view) line += std::string("  view ") + view_name(*e.view);
    if (e.score) line += "  score " + json_text(*e.score);
    if (e.track) line += "  track " + std::to_string(*e.track);
    if (!e.source.empty()) line += "  source " + e.source;
    if (!e.sensor.empty()) line += "  sensor " + e.sensor;
    if (e.logged) line += "  logged " + format_utc(*e.logged);
    std::printf("%s\n", line.c_str());
    j["events"].push_back(event_to_json(e));
  }
  if (c.json) std::printf("%s\n", json_text(j).c_str());
}

void export_command(const GalleryCommand& c) {
  Gallery g = c.open(true);
  const UserId id = g.resolve_user(c.user);
  const ExportReport r = export_user(g, id, c.dir);
  std::printf("exported user %lld to %s: %d scans (%d images, %d masks, their features in user.json), %d events\n",
              static_cast<long long>(id), c.dir.c_str(), r.scans, r.images, r.masks, r.events);
  if (c.json)
    std::printf("%s\n", json_text({{"user", id}, {"dir", c.dir}, {"scans", r.scans}, {"images", r.images},
                                   {"masks", r.masks}, {"events", r.events}, {"files", r.files}})
                            .c_str());
}

void forget(const GalleryCommand& c) {
  check_given_spools(c.spools);
  Gallery g = c.open(false);
  const UserId id = g.resolve_user(c.user);
  const EraseReport r = g.forget(id);
  std::printf("forgot user %lld: erased %s; %s %s\n", static_cast<long long>(id), erased_summary(r).c_str(),
              c.gallery.path.c_str(), vacuumed(r));
  note_scrub(r);
  finish_erasure(c, r, scrub_erased(g, c, r));
}

void purge(const GalleryCommand& c) {
  check_given_spools(c.spools);
  Gallery g = c.open(false);
  if (!c.yes)
    throw UsageError("purge erases all " + std::to_string(g.user_count()) + " users of " + c.gallery.path +
                     "; run it again with --yes");
  const EraseReport r = g.purge();
  std::printf("purged %s: erased %zu users, %s; %s\n", c.gallery.path.c_str(), r.users.size(),
              erased_summary(r).c_str(), vacuumed(r));
  note_scrub(r);
  finish_erasure(c, r, scrub_erased(g, c, r));
}

void label(const GalleryCommand& c) {
  // A label is how an operator names a person for show, export and forget: it must not read as an id, and
  // it must name one user only.
  if (!c.label.empty() && c.label.find_first_not_of("0123456789") == std::string::npos)
    throw UsageError("LABEL: '" + c.label + "' reads as a user id; give a name with a letter in it");
  Gallery g = c.open(false);
  const UserId id = g.resolve_user(c.user);
  for (const User& u : g.users())
    if (u.id != id && !c.label.empty() && u.label == c.label)
      throw InputError(c.gallery.path + ": label '" + c.label + "' already names user " + std::to_string(u.id));
  g.set_label(id, c.label);
  if (c.label.empty())
    std::printf("user %lld has no label now\n", static_cast<long long>(id));
  else
    std::printf("user %lld is labelled %s\n", static_cast<long long>(id), c.label.c_str());
}

void prune(const GalleryCommand& c) {
  const auto unseen = parse_retention(c.unseen_for, "--unseen-for");
  if (unseen.count() <= 0)
    throw UsageError("--unseen-for: " + c.unseen_for + " would erase everyone; to do that, run purge --yes");
  check_given_spools(c.spools);
  Gallery g = c.open(c.dry_run);
  const GalleryTime now = GalleryClock::now();
  // "N users not seen since T: 1 2 3"
  const auto who = [&](const std::vector<UserId>& users) {
    std::string text = std::to_string(users.size()) + " users not seen since " + format_utc(now - unseen);
    for (size_t i = 0; i < users.size(); ++i) text += (i == 0 ? ": " : " ") + std::to_string(users[i]);
    return text;
  };
  if (c.dry_run) {
    const std::vector<UserId> going = g.users_unseen_since(now - unseen);
    std::printf("would prune %s (nothing erased)\n", who(going).c_str());
    if (c.json) std::printf("%s\n", json_text({{"users", going}, {"dry_run", true}}).c_str());
    return;
  }
  const EraseReport r = g.prune_unseen(unseen, now);
  std::printf("pruned %s: erased %s\n", who(r.users).c_str(), erased_summary(r).c_str());
  note_scrub(r);
  finish_erasure(c, r, scrub_erased(g, c, r));
}

// The reid event spools the gallery lists; --drop takes paths off the list, --scrub takes the events of users
// the gallery no longer has out of those on this machine (for an erasure made on another machine).
void spools(const GalleryCommand& c) {
  Gallery g = c.open(!c.scrub && c.drop.empty());
  nlohmann::json j = {{"gallery", c.gallery.path}};
  if (!c.drop.empty()) {
    int dropped = 0;
    for (const EventSpoolRecord& r : g.event_spools())
      if (std::find(c.drop.begin(), c.drop.end(), r.path) != c.drop.end() && g.drop_event_spool(r.machine, r.path)) {
        std::printf("took %s on %s off the list (the file is left as it is)\n", r.path.c_str(), r.host.c_str());
        ++dropped;
      }
    j["dropped"] = dropped;
  }
  const std::vector<EventSpoolRecord> listed = g.event_spools();
  std::printf("%s: %zu event spools\n", c.gallery.path.c_str(), listed.size());
  nlohmann::json all = nlohmann::json::array();
  for (const EventSpoolRecord& r : listed) {
    const char* place = spool_place_name(spool_place(r));
    std::printf("%s:%s  sensor %s  first used %s  last used %s  %s\n", r.host.c_str(), r.path.c_str(),
                r.sensor.empty() ? "-" : r.sensor.c_str(), format_utc(r.first_used).c_str(),
                format_utc(r.last_used).c_str(), place);
    all.push_back({{"machine", r.machine}, {"host", r.host}, {"path", r.path}, {"sensor", r.sensor},
                   {"first_used", format_utc(r.first_used)}, {"last_used", format_utc(r.last_used)}, {"place", place}});
  }
  j["spools"] = all;
  SpoolScrubs scrubs;
  if (c.scrub) {
    std::set<int64_t> users;
    for (const User& u : g.users()) users.insert(u.id);
    scrubs = scrub_spools(g, {}, [&](int64_t user) { return users.count(user) == 0; }, stdout);
    j["scrub"] = scrubs.spools;
  }
  if (c.json) std::printf("%s\n", json_text(j).c_str());
  check_scrubs(scrubs);
}

void add_spool_option(CLI::App& sub, GalleryCommand& c) {
  sub.add_option("--events-spool", c.spools,
                 "Also take the erased users' undelivered events out of this reid event spool file (repeatable), "
                 "besides the spools the gallery lists (gallery spools); one a running reid holds is left to it: "
                 "it withdraws them itself. A spool that cannot be scrubbed: exit 4, after the erasure and its output");
}

void add(CLI::App& app) {
  auto c = std::make_shared<GalleryCommand>();
  CLI::App* gallery = app.add_subcommand("gallery", "Inspect and manage the re-identification gallery (SQLite file or PostgreSQL)");
  gallery->require_subcommand(1);
  add_gallery_path_option(*gallery, c->gallery);
  gallery->footer(
      "The gallery holds, per user, at most one partial scan per view (image, mask, features) and an event\n"
      "history; see README \"What is stored where\".\n"
      "Examples: bodyrec gallery list\n"
      "          bodyrec gallery --gallery lab.db show 3 --json\n"
      "          bodyrec gallery --gallery postgresql://bodyrec_admin@db.site/bodyrec_site init\n"
      "          bodyrec gallery export 3 user3/\n"
      "          bodyrec gallery label 3 alice\n"
      "          bodyrec gallery forget alice\n"
      "          bodyrec gallery prune --unseen-for 30d\n"
      "          bodyrec gallery spools");

  CLI::App* sub = gallery->add_subcommand(
      "init", "Create the gallery: a new SQLite file, or the tables in an empty PostgreSQL database (docs/postgresql.md)");
  sub->callback([c] { init(*c); });

  sub = gallery->add_subcommand("list", "Users with the views they have, scan counts, first/last seen");
  sub->add_flag("--json", c->json, "End stdout with one JSON object {gallery, users: [{id, label, views, ...}]}");
  sub->callback([c] { list(*c); });

  sub = gallery->add_subcommand(
      "show", "One user's scans (view, quality, time, stored) and event history (time, ..., logged)");
  sub->footer("time: the source's clock (when it happened in the recording); stored/logged: the wall clock when\n"
              "bodyrec wrote it (absent in rows of galleries before schema 3)");
  sub->add_option("USER", c->user, "User id or label")->required();
  sub->add_flag("--json", c->json, "End stdout with one JSON object {user, scans, events}");
  sub->callback([c] { show(*c); });

  sub = gallery->add_subcommand("export", "Write a user's images, masks and a JSON of everything stored into DIR");
  sub->add_option("USER", c->user, "User id or label")->required();
  sub->add_option("DIR", c->dir, "Directory to write (created, mode 0700)")->required();
  sub->add_flag("--json", c->json, "End stdout with one JSON object {user, dir, scans, images, masks, events, files}");
  sub->footer("Example: bodyrec gallery export 3 user3/  (writes F-image.png, F-mask.png, ..., user.json)");
  sub->callback([c] { export_command(*c); });

  sub = gallery->add_subcommand("forget", "Erase every image, feature and event of one user (database vacuumed)");
  sub->add_option("USER", c->user, "User id or label")->required();
  add_spool_option(*sub, *c);
  sub->add_flag("--json", c->json, "End stdout with one JSON object {users, scans, images, masks, events, spools}");
  sub->callback([c] { forget(*c); });

  sub = gallery->add_subcommand("label", "Name a user (the name show, export and forget accept); an empty LABEL removes it");
  sub->add_option("USER", c->user, "User id or label")->required();
  sub->add_option("LABEL", c->label, "The name: unique in the gallery, not a number")->required();
  sub->footer("Example: bodyrec gallery label 3 alice   (then: bodyrec gallery forget alice)");
  sub->callback([c] { label(*c); });

  sub = gallery->add_subcommand("purge", "Erase every user (asks for --yes)");
  sub->add_flag("--yes", c->yes, "Really erase everything");
  add_spool_option(*sub, *c);
  sub->add_flag("--json", c->json, "End stdout with one JSON object {users, scans, images, masks, events, spools}");
  sub->callback([c] { purge(*c); });

  sub = gallery->add_subcommand("prune", "Retention: erase users not seen for a given time");
  sub->add_option("--unseen-for", c->unseen_for,
                  "Whole number with s, m, h, d or w, e.g. 30d or 12h (more than 0). Last seen is the source's clock: "
                  "a recording's time, not when it was processed")
      ->required();
  sub->add_flag("--dry-run", c->dry_run, "Only list the users it would erase");
  add_spool_option(*sub, *c);
  sub->add_flag("--json", c->json, "End stdout with one JSON object {users, scans, images, masks, events, spools}");
  sub->footer("Example: bodyrec gallery prune --unseen-for 30d");
  sub->callback([c] { prune(*c); });

  sub = gallery->add_subcommand(
      "spools", "The event spools of reid --events runs that the gallery lists (forget, purge and prune scrub them)");
  sub->add_flag("--scrub", c->scrub,
                "Take the undelivered events of users the gallery no longer has out of the listed spools on this "
                "machine (for an erasure made on another machine)");
  sub->add_option("--drop", c->drop,
                  "Take this spool path off the list, on every machine (repeatable; the file is left as it is): for "
                  "a spool on a machine that is gone");
  sub->add_flag("--json", c->json,
                "End stdout with one JSON object {gallery, spools: [{machine, host, path, sensor, first_used, "
                "last_used, place}], scrub, dropped}");
  sub->footer("A spool is listed by the reid --events run that used it, under its machine (/etc/machine-id) and\n"
              "host name; place is here, missing, unreachable (cannot be looked at from here) or elsewhere (another\n"
              "machine). An erasure scrubs the listed spools on its own machine; on others, the next reid run with\n"
              "that spool withdraws the erased users' events, or run gallery spools --scrub there.\n"
              "Exit 4 when a spool could not be scrubbed (after everything else is done and printed).");
  sub->callback([c] { spools(*c); });
}

const bool registered = register_command({"", 90, add});

}  // namespace
}  // namespace bodyrec::cli
