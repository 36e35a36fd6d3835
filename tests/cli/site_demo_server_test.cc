// scripts/site-demo (issue 47): a whole site on one machine, PostgreSQL gallery, Mosquitto broker and two
// sensors, on a fixed seed: its JSON and its targets (ctest label `server`).
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "server_fixtures.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

std::set<std::string> site_folders() {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
    if (e.path().filename().string().rfind("bodyrec-site-", 0) == 0) out.insert(e.path().string());
  return out;
}

TEST(SiteDemo, SensorBRecognisesSensorAsPeopleWithoutDuplicatesAndCleansUp) {
  // The demo starts servers of its own; these only say whether the programs are installed.
  BODYREC_REQUIRE_POSTGRES(pg);
  BODYREC_REQUIRE_MOSQUITTO(broker);
  const std::set<std::string> before = site_folders();
  // run_bodyrec puts the program after the prefix: python3 scripts/site-demo ... --bodyrec BIN.
  const RunResult r = run_bodyrec({}, {"python3", source_dir() + "/scripts/site-demo", "--people", "4", "--seed", "21",
                                       "--bodyrec"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  for (const char* key : {"people", "mode", "enrolled_a", "recognised_b_first", "duplicates", "merges", "users",
                          "events_published", "events_received"})
    EXPECT_TRUE(j.contains(key)) << key << " in " << r.out;
  EXPECT_EQ(j["people"], 4);
  EXPECT_EQ(j["mode"], "a_then_b");
  EXPECT_EQ(j["enrolled_a"], 4);
  EXPECT_GE(j["recognised_b_first"].get<double>(), 0.90);
  EXPECT_EQ(j["duplicates"], 0);
  EXPECT_EQ(j["merges"], 0);
  EXPECT_EQ(j["users"], 4);
  EXPECT_GT(j["events_published"].get<int>(), 0);
  EXPECT_EQ(j["events_received"], j["events_published"]);
  EXPECT_EQ(site_folders(), before) << "the demo left its temporary folder";
}

}  // namespace
}  // namespace bodyrec::testing
