// Two `reid` processes at once on one gallery (issue 47), each with a recording of the same people on its
// own paths (synth --looks-seed): one user per person, whichever process met them first (ctest label
// `server`; the SQLite case needs no server). End to end only: whether the two decide in the same instant
// is up to the scheduler; src/bodyrec/reid/reid_sites_suite_test.cc pins that moment down.
#include <thread>

#include <gtest/gtest.h>

#include "server_fixtures.h"
#include "test_support.h"

namespace bodyrec::testing {
namespace {

void two_sensors_at_once(const std::string& gallery) {
  const std::string a = synth_recording({"--people", "3", "--seed", "11", "--frames", "240", "--scenario", "visits"})
                            .string();
  const std::string b = synth_recording({"--people", "3", "--seed", "12", "--looks-seed", "11", "--frames", "240",
                                         "--scenario", "visits"})
                            .string();
  RunResult ra, rb;
  std::thread door([&] { ra = run_bodyrec({"reid", a, "--gallery", gallery, "--sensor-id", "door", "--json", "-q"}); });
  std::thread hall([&] { rb = run_bodyrec({"reid", b, "--gallery", gallery, "--sensor-id", "hall", "--json", "-q"}); });
  door.join();
  hall.join();
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  const auto ja = last_json_line(ra.out), jb = last_json_line(rb.out);
  EXPECT_EQ(ja["enrolled"].get<int>() + jb["enrolled"].get<int>(), 3) << ra.out << rb.out;
  EXPECT_EQ(jb["users"], 3);
  const RunResult list = run_bodyrec({"gallery", "--gallery", gallery, "list", "--json"});
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_EQ(last_json_line(list.out)["users"].size(), 3u) << list.out;
}

TEST(SitesProcesses, TwoReidProcessesAtOnceOnPostgresMakeOneUserPerPerson) {
  BODYREC_REQUIRE_POSTGRES(pg);
  const std::string uri = pg->create_database("two");
  ASSERT_EQ(run_bodyrec({"gallery", "--gallery", uri, "init"}).exit_code, 0);
  two_sensors_at_once(uri);
}

TEST(SitesProcesses, TwoReidProcessesAtOnceOnOneSqliteFileMakeOneUserPerPerson) {
  TempDir dir;
  const std::string file = (dir / "g.db").string();
  ASSERT_EQ(run_bodyrec({"gallery", "--gallery", file, "init"}).exit_code, 0);
  two_sensors_at_once(file);
}

}  // namespace
}  // namespace bodyrec::testing
