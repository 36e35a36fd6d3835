// Several sensors of a site (issue 47) as a user meets them, on private servers (tests/support/server_fixtures.h,
// ctest label `server`): `reid` and `gallery` and `report` on a PostgreSQL gallery, events of `reid` and
// `groups` over MQTT, a broker that is down, a PostgreSQL restart in the middle of a run, and the
// refusal of passwords on the command line.
#include <sys/stat.h>

#include <filesystem>
#include <map>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "server_fixtures.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

const fs::path& reenter() {
  return synth_recording({"--people", "3", "--seed", "11", "--frames", "240", "--scenario", "reenter"});
}

// The events of a reid JSONL file, in order: "kind user track".
std::vector<std::string> jsonl_events(const std::string& path) {
  std::vector<std::string> out;
  for (const std::string& line : lines_of(read_text(path))) {
    const auto frame = nlohmann::json::parse(line);
    for (const auto& e : frame["events"])
      out.push_back(e["kind"].get<std::string>() + " " + std::to_string(e["user"].get<long long>()) + " " +
                    std::to_string(e["track"].get<long long>()));
  }
  return out;
}

// MQTT payloads after dropping repeats by event_id, as a subscriber does.
std::vector<nlohmann::json> unique_payloads(const std::vector<MqttSubscriber::Message>& messages) {
  std::set<std::string> seen;
  std::vector<nlohmann::json> out;
  for (const auto& m : messages) {
    auto j = nlohmann::json::parse(m.payload);
    if (seen.insert(j["event_id"].get<std::string>()).second) out.push_back(std::move(j));
  }
  return out;
}

std::vector<std::string> described(const std::vector<nlohmann::json>& payloads) {
  std::vector<std::string> out;
  for (const auto& j : payloads)
    out.push_back(j["kind"].get<std::string>() + " " + std::to_string(j["user"].get<long long>()) + " " +
                  std::to_string(j["track"].get<long long>()));
  return out;
}

// The same recording and options give the same decisions on either database.
TEST(SitesCli, ReidOnPostgresDecidesAsOnSqliteAndGalleryAndReportReadIt) {
  BODYREC_REQUIRE_POSTGRES(pg);
  TempDir dir;
  const std::string uri = pg->create_database("reid");
  const std::string sqlite = (dir / "g.db").string(), on_sqlite = (dir / "s.jsonl").string(),
                    on_pg = (dir / "p.jsonl").string();
  RunResult r = run_bodyrec({"reid", reenter().string(), "--gallery", sqlite, "--jsonl", on_sqlite, "-q", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_bodyrec({"reid", reenter().string(), "--gallery", uri, "--sensor-id", "door", "--jsonl", on_pg, "-q", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = last_json_line(r.out);
  EXPECT_EQ(j["enrolled"], 3);
  EXPECT_EQ(j["users"], 3);
  EXPECT_EQ(j["sensor"], "door");
  EXPECT_TRUE(j["events"].is_null());
  ASSERT_GE(jsonl_events(on_pg).size(), 9u);
  EXPECT_EQ(jsonl_events(on_pg), jsonl_events(on_sqlite));
  // A second sensor on the same gallery recognises everyone.
  r = run_bodyrec({"reid", reenter().string(), "--gallery", uri, "--sensor-id", "hall", "-q", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = last_json_line(r.out);
  EXPECT_EQ(j["enrolled"], 0);
  EXPECT_GE(j["recognised"].get<int>(), 6);
  r = run_bodyrec({"gallery", "--gallery", uri, "list", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, uri + ": 3 users")) << r.out;
  r = run_bodyrec({"gallery", "--gallery", uri, "show", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "enrolled  view ")) << r.out;
  EXPECT_TRUE(contains(r.out, "sensor door")) << r.out;
  EXPECT_TRUE(contains(r.out, "sensor hall")) << r.out;
  const auto shown = last_json_line(r.out);
  EXPECT_EQ(shown["events"][0]["sensor"], "door");
  r = run_bodyrec({"gallery", "--gallery", uri, "export", "1", (dir / "u1").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "u1" / "user.json"));
  r = run_bodyrec({"report", on_pg, "--gallery", uri, "--out", (dir / "r.html").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "3 gallery users")) << r.out;
  r = run_bodyrec({"gallery", "--gallery", uri, "forget", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "forgot user 1: erased ")) << r.out;
  EXPECT_TRUE(contains(r.out, uri + " vacuumed")) << r.out;
  EXPECT_TRUE(last_json_line(r.out)["scrubbed"].get<bool>());
  r = run_bodyrec({"gallery", "--gallery", uri, "prune", "--unseen-for", "1s"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "pruned 2 users")) << r.out;
  r = run_bodyrec({"gallery", "--gallery", uri, "purge", "--yes"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "erased 0 users")) << r.out;
}

TEST(SitesCli, GalleryInitAndErrorsNameTheDatabase) {
  BODYREC_REQUIRE_POSTGRES(pg);
  const std::string uri = pg->create_database("init");
  RunResult r = run_bodyrec({"gallery", "--gallery", uri, "list"});
  expect_one_line_error(r, 3, uri + ": empty database, not a bodyrec gallery");
  r = run_bodyrec({"gallery", "--gallery", uri, "init"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, uri + ": gallery schema version 4, 0 users\n");
  EXPECT_EQ(run_bodyrec({"gallery", "--gallery", uri, "list"}).exit_code, 0);
  const std::string missing = pg->uri("missing_db");
  expect_one_line_error(run_bodyrec({"gallery", "--gallery", missing, "list"}), 3, missing + ": cannot connect: ");
  r = run_bodyrec({"reid", reenter().string(), "--gallery", "postgresql://door:hunter2@db.site/site"});
  expect_one_line_error(r, 2, "PGPASSFILE");
  EXPECT_FALSE(contains(r.err, "hunter2"));
  r = run_bodyrec({"gallery", "--gallery", "postgresql:///site?password=hunter2", "list"});
  expect_one_line_error(r, 2, "Put the password in a password file");
  EXPECT_FALSE(contains(r.err, "hunter2"));
}

// A PostgreSQL restart in the middle of a run: the run stops with one clear line (exit 4), and every user
// whose enrolment it reported is in the gallery, with the scans committed before.
TEST(SitesCli, APostgresRestartStopsTheRunAndLosesNoReportedEnrolment) {
  BODYREC_REQUIRE_POSTGRES(pg);
  TempDir dir;
  const std::string uri = pg->create_database("restart"), lines = (dir / "r.jsonl").string();
  const fs::path& rec = synth_recording({"--people", "3", "--seed", "12", "--frames", "480", "--scenario", "reenter"});
  RunResult r;
  std::thread run([&] { r = run_bodyrec({"reid", rec.string(), "--gallery", uri, "--jsonl", lines, "-q"}); });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!contains(read_text(lines), "\"enrolled\"") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  pg->restart();
  run.join();
  expect_one_line_error(r, 4, uri + ": lost the connection to the PostgreSQL server");
  std::set<long long> enrolled;
  for (const std::string& e : jsonl_events(lines))
    if (e.rfind("enrolled ", 0) == 0) enrolled.insert(std::stoll(e.substr(9)));
  ASSERT_FALSE(enrolled.empty());
  r = run_bodyrec({"gallery", "--gallery", uri, "list", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::set<long long> stored;
  const auto list = last_json_line(r.out);
  for (const auto& u : list["users"]) {
    stored.insert(u["id"].get<long long>());
    EXPECT_GE(u["scans"].get<int>(), 1);
  }
  for (long long u : enrolled) EXPECT_TRUE(stored.count(u)) << "reported user " << u << " lost";
  // A new run carries on from what was committed.
  r = run_bodyrec({"reid", reenter().string(), "--gallery", uri, "-q", "--json", "--max-frames", "30"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Issue 47: reid's events arrive over MQTT with QoS 1, in the order the run made them.
TEST(SitesCli, ReidEventsArriveOverMqttInOrder) {
  BODYREC_REQUIRE_MOSQUITTO(broker);
  TempDir dir;
  MqttSubscriber sub(broker->port(), "site/#", "sites-reid");
  ASSERT_TRUE(sub.subscribed(std::chrono::seconds(20)));
  const std::string lines = (dir / "r.jsonl").string();
  const RunResult r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "g.db").string(), "--sensor-id",
                                   "door", "--events", broker->uri("site"), "--events-spool",
                                   (dir / "door.spool").string(), "--jsonl", lines, "-q", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto j = last_json_line(r.out);
  const auto expected = jsonl_events(lines);
  ASSERT_GE(expected.size(), 9u);
  EXPECT_EQ(j["events"]["delivered"], expected.size());
  EXPECT_EQ(j["events"]["pending"], 0);
  EXPECT_EQ(j["events"]["dropped"], 0);
  EXPECT_EQ(j["events"]["topic"], "site/door/reid");
  const auto messages = sub.wait_for(expected.size(), std::chrono::seconds(30));
  for (const auto& m : messages) EXPECT_EQ(m.topic, "site/door/reid");
  const auto payloads = unique_payloads(messages);
  EXPECT_EQ(described(payloads), expected);
  std::set<std::string> runs;
  for (const auto& p : payloads) {
    EXPECT_EQ(p["sensor"], "door");
    EXPECT_EQ(p["schema"], 1);
    EXPECT_EQ(p["source"], reenter().string());
    for (const char* key : {"frame", "time", "wall_time", "view", "score", "run"}) EXPECT_TRUE(p.contains(key)) << key;
    runs.insert(p["run"].get<std::string>());
  }
  EXPECT_EQ(runs.size(), 1u);
  EXPECT_EQ(payloads.back()["end"], true);  // the departures at the end of the recording
}

// Issue 47: the broker stops in the middle of a run and starts again: every event arrives, in order, none
// twice after dropping repeats by event_id.
TEST(SitesCli, ABrokerRestartInTheMiddleOfARunLosesNoEvent) {
  BODYREC_OWN_MOSQUITTO(broker, MosquittoServer::Options{});
  TempDir dir;
  MqttSubscriber sub(broker->port(), "mid/#", "sites-mid");
  ASSERT_TRUE(sub.subscribed(std::chrono::seconds(20)));
  const fs::path& rec = synth_recording({"--people", "3", "--seed", "12", "--frames", "480", "--scenario", "reenter"});
  const std::string lines = (dir / "r.jsonl").string();
  RunResult r;
  std::thread run([&] {
    r = run_bodyrec({"reid", rec.string(), "--gallery", (dir / "g.db").string(), "--sensor-id", "door", "--events",
                     broker->uri("mid"), "--events-spool", (dir / "door.spool").string(), "--jsonl", lines, "-q",
                     "--json"});
  });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (sub.messages().empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  broker->stop();
  std::this_thread::sleep_for(std::chrono::seconds(2));
  broker->start();
  run.join();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["events"]["pending"], 0) << "the run ended before the broker came back";
  const auto expected = jsonl_events(lines);
  EXPECT_EQ(j["events"]["delivered"], expected.size());
  EXPECT_EQ(described(unique_payloads(sub.wait_for(expected.size(), std::chrono::seconds(60)))), expected);
}

// The broker is down for a whole run: the run does not wait, says what it kept, and the next run delivers
// those events first; an overflowing spool says how many it lost.
TEST(SitesCli, WithTheBrokerDownEventsWaitInTheSpoolForTheNextRun) {
  BODYREC_OWN_MOSQUITTO(broker, MosquittoServer::Options{});
  TempDir dir;
  const std::string spool = (dir / "door.spool").string(), gallery = (dir / "g.db").string();
  broker->stop();
  const std::vector<std::string> common = {"--gallery", gallery, "--sensor-id", "door", "--events", broker->uri("down"),
                                           "--events-spool", spool, "-q", "--json"};
  std::vector<std::string> args = {"reid", reenter().string(), "--jsonl", (dir / "a.jsonl").string()};
  args.insert(args.end(), common.begin(), common.end());
  RunResult r = run_bodyrec(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto first = jsonl_events((dir / "a.jsonl").string());
  auto j = last_json_line(r.out);
  EXPECT_EQ(j["events"]["delivered"], 0);
  EXPECT_EQ(j["events"]["pending"], first.size());
  EXPECT_EQ(r.err, "bodyrec: " + std::to_string(first.size()) + " events not delivered yet (broker unreachable); kept in " +
                       spool + " for the next run\n");
  EXPECT_EQ(fs::status(spool).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);

  broker->start();
  MqttSubscriber sub(broker->port(), "down/#", "sites-down");
  ASSERT_TRUE(sub.subscribed(std::chrono::seconds(20)));
  args = {"reid", reenter().string(), "--max-frames", "60", "--jsonl", (dir / "b.jsonl").string()};
  args.insert(args.end(), common.begin(), common.end());
  r = run_bodyrec(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto expected = first;
  for (const auto& e : jsonl_events((dir / "b.jsonl").string())) expected.push_back(e);
  j = last_json_line(r.out);
  EXPECT_EQ(j["events"]["recovered"], first.size());
  EXPECT_EQ(j["events"]["pending"], 0);
  EXPECT_EQ(described(unique_payloads(sub.wait_for(expected.size(), std::chrono::seconds(30)))), expected);

  broker->stop();
  args = {"reid", reenter().string(), "--events-spool-max", "3"};
  args.insert(args.end(), common.begin(), common.end());
  r = run_bodyrec(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = last_json_line(r.out);
  EXPECT_EQ(j["events"]["pending"], 3);
  EXPECT_GT(j["events"]["dropped"].get<int>(), 0);
  EXPECT_TRUE(contains(r.err, "bodyrec: " + j["events"]["dropped"].dump() + " events lost: the event spool " + spool +
                                  " was full (--events-spool-max)\n"))
      << r.err;
}

// A sensor role with the grants of docs/postgresql-roles.sql lists its run's event spool in the gallery, and
// the admin's forget scrubs it. Without the schema-4 grant (a site that upgraded and has not run it yet) the
// run says so on stderr and goes on.
TEST(SitesCli, ASensorListsItsEventSpoolOrWarnsWithoutTheGrant) {
  BODYREC_REQUIRE_POSTGRES(pg);
  TempDir dir;
  const std::string uri = pg->create_database("spools");
  const std::string db = uri.substr(std::string("postgresql:///").size(), uri.find('?') - std::string("postgresql:///").size());
  const std::string roles = read_text(source_dir() + "/docs/postgresql-roles.sql");
  const size_t part2 = roles.find("-- Part 2");
  pg->exec(db, roles.substr(0, part2));
  const std::string admin = pg->uri(db, "bodyrec_admin"), sensor = pg->uri(db, "bodyrec_sensor");
  ASSERT_EQ(run_bodyrec({"gallery", "--gallery", admin, "init"}).exit_code, 0);
  pg->exec(db, roles.substr(part2));
  pg->exec(db, "REVOKE ALL ON event_spools FROM bodyrec_sensor");
  const std::string spool = (dir / "door.spool").string();
  const std::vector<std::string> run = {"reid", reenter().string(), "--gallery", sensor, "--sensor-id", "door", "-q",
                                        "--events", "mqtt://127.0.0.1:1/site", "--events-spool", spool,
                                        "--events-wait", "0"};
  RunResult r = run_bodyrec(run);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "bodyrec: " + sensor + " does not list the event spool " + spool)) << r.err;
  EXPECT_TRUE(contains(r.err, "permission denied")) << r.err;
  r = run_bodyrec({"gallery", "--gallery", admin, "spools"});
  EXPECT_TRUE(contains(r.out, ": 0 event spools")) << r.out;

  pg->exec(db, "GRANT SELECT, INSERT, UPDATE, DELETE ON event_spools TO bodyrec_sensor");
  r = run_bodyrec(run);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(contains(r.err, "warning")) << r.err;
  r = run_bodyrec({"gallery", "--gallery", admin, "spools", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  ASSERT_EQ(j["spools"].size(), 1u) << j;
  EXPECT_EQ(j["spools"][0]["path"], spool);
  EXPECT_EQ(j["spools"][0]["sensor"], "door");
  const std::string user1 = "\\\"user\\\":1,";  // as the spool holds a payload: JSON in a JSON string
  ASSERT_TRUE(contains(read_text(spool), user1));
  r = run_bodyrec({"gallery", "--gallery", admin, "forget", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "events spool " + spool + ": withdrew ")) << r.out;
  EXPECT_FALSE(contains(r.out, ": withdrew 0 ")) << r.out;
  EXPECT_FALSE(contains(read_text(spool), user1)) << "user 1's events are still in the spool";
}

TEST(SitesCli, EventOptionErrorsAreUsageErrorsWithoutSecrets) {
  TempDir dir;
  RunResult r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "g.db").string(), "--events",
                             "mqtt://door:hunter2@broker/site"});
  expect_one_line_error(r, 2, "--events-credentials");
  EXPECT_FALSE(contains(r.err, "hunter2"));
  const std::string cred = (dir / "door.cred").string();
  write_text(cred, "username=door\npassword=hunter2\n");
  ::chmod(cred.c_str(), 0644);
  r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "g.db").string(), "--events", "mqtt://broker/site",
                   "--events-credentials", cred});
  expect_one_line_error(r, 2, cred + ": credentials file is readable by others (mode 644); chmod 600 it");
  r = run_bodyrec({"reid", reenter().string(), "--sensor-id", "door/1", "--gallery", (dir / "g.db").string()});
  expect_one_line_error(r, 2, "--sensor-id: 'door/1'");
  r = run_bodyrec({"groups", vtest_path().string(), "--events-spool", (dir / "s").string()});
  expect_one_line_error(r, 2, "need --events");
  r = run_bodyrec({"groups", vtest_path().string(), "--events", "mqtt://h/p", "--events-cafile", cred});
  expect_one_line_error(r, 2, "--events-cafile needs an mqtts:// URI");
}

// groups' events: leader found/lost and group formed/dissolved, consistent with each other.
TEST(SitesCli, GroupsEventsArriveOverMqtt) {
  BODYREC_REQUIRE_MOSQUITTO(broker);
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  MqttSubscriber sub(broker->port(), "hall/#", "sites-groups");
  ASSERT_TRUE(sub.subscribed(std::chrono::seconds(20)));
  const RunResult r = run_bodyrec({"groups", vtest_path().string(), "--fps", "7", "--max-frames", "300", "--sensor-id",
                                   "cam1", "--events", broker->uri("hall"), "--events-spool",
                                   (dir / "cam1.spool").string(), "--jsonl", (dir / "g.jsonl").string(), "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  const size_t delivered = j["events"]["delivered"].get<size_t>();
  const auto payloads = unique_payloads(sub.wait_for(delivered, std::chrono::seconds(30)));
  ASSERT_EQ(payloads.size(), delivered);
  std::map<std::string, int> kinds;
  std::map<int, bool> group_open, leader_open;
  int last_frame = -1;
  for (const auto& p : payloads) {
    const std::string kind = p["kind"];
    const int g = p["group"];
    ++kinds[kind];
    EXPECT_GE(p["frame"].get<int>(), last_frame);
    last_frame = p["frame"];
    EXPECT_EQ(p["sensor"], "cam1");
    if (kind == "group_formed") {
      EXPECT_FALSE(group_open[g]) << "group " << g << " formed twice";
      group_open[g] = true;
    } else if (kind == "group_dissolved") {
      EXPECT_TRUE(group_open[g]) << "group " << g << " dissolved before it formed";
      group_open[g] = false;
    } else if (kind == "leader_found") {
      EXPECT_TRUE(group_open[g]) << "a leader for group " << g << ", which has not formed";
      leader_open[g] = true;
    } else if (kind == "leader_lost") {
      EXPECT_TRUE(leader_open[g]) << "group " << g << " lost a leader it had not found";
      leader_open[g] = false;
    } else {
      ADD_FAILURE() << "unknown kind " << kind;
    }
  }
  for (const char* kind : {"group_formed", "group_dissolved", "leader_found", "leader_lost"})
    EXPECT_GT(kinds[kind], 0) << kind;
  // The end of the run dissolves every group still there.
  for (const auto& [g, open] : group_open) EXPECT_FALSE(open) << "group " << g << " still open after the end";
}

}  // namespace
}  // namespace bodyrec::testing
