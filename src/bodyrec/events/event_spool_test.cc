#include "bodyrec/events/event_spool.h"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <future>
#include <thread>

#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::read_text;
using bodyrec::testing::TempDir;

SpooledEvent ev(int i) { return {"site/door/reid", "{\"n\":" + std::to_string(i) + "}"}; }

std::vector<std::string> drain(EventSpool& s, size_t n) {
  std::vector<std::string> out;
  for (size_t i = 0; i < n && !s.empty(); ++i) {
    out.push_back(s.front().payload);
    s.pop();
  }
  return out;
}

TEST(EventSpool, KeepsOrderAcrossRunsAndForgetsWhatWasDelivered) {
  TempDir dir;
  const std::string path = (dir / "events.spool").string();
  {
    EventSpool s(path, 100);
    EXPECT_EQ(s.recovered(), 0u);
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(s.push(ev(i)));
    EXPECT_EQ(drain(s, 2), std::vector<std::string>({"{\"n\":0}", "{\"n\":1}"}));
  }  // the run ends with 3 undelivered
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  {
    EventSpool s(path, 100);
    EXPECT_EQ(s.recovered(), 3u);
    s.push(ev(5));
    EXPECT_EQ(drain(s, 10), std::vector<std::string>({"{\"n\":2}", "{\"n\":3}", "{\"n\":4}", "{\"n\":5}"}));
    EXPECT_TRUE(s.empty());
  }
  EXPECT_EQ(read_text(path), "");  // all delivered: the file starts again empty
  EventSpool s(path, 100);
  EXPECT_EQ(s.recovered(), 0u);
}

// Withdrawn events leave the queue and the file (their bytes too); the front one may be kept (in flight).
TEST(EventSpool, EraseIfRemovesEventsFromTheQueueAndTheFile) {
  TempDir dir;
  const std::string path = (dir / "events.spool").string();
  {
    EventSpool s(path, 100);
    for (int i = 0; i < 6; ++i) s.push(ev(i));
    drain(s, 1);  // n 0 delivered
    const auto even = [](const SpooledEvent& e) { return (e.payload[5] - '0') % 2 == 0; };
    EXPECT_EQ(s.erase_if(even, /*keep_front=*/false), 2u);  // n 2 and 4
    EXPECT_EQ(s.size(), 3u);
    EXPECT_EQ(read_text(path).find("\\\"n\\\":2"), std::string::npos) << read_text(path);
    EXPECT_NE(read_text(path).find("\\\"n\\\":3"), std::string::npos) << read_text(path);
    EXPECT_EQ(s.erase_if([](const SpooledEvent&) { return true; }, /*keep_front=*/true), 2u);  // n 3 and 5
    EXPECT_EQ(drain(s, 10), std::vector<std::string>({"{\"n\":1}"}));
  }
  EventSpool again(path, 100);
  EXPECT_EQ(again.recovered(), 0u);
}

TEST(EventSpool, AFullSpoolDropsNewEventsAndCountsThem) {
  TempDir dir;
  EventSpool s((dir / "s").string(), 3);
  for (int i = 0; i < 5; ++i) s.push(ev(i));
  EXPECT_EQ(s.size(), 3u);
  EXPECT_EQ(s.dropped(), 2u);
  EXPECT_EQ(drain(s, 1), std::vector<std::string>({"{\"n\":0}"}));
  EXPECT_TRUE(s.push(ev(9)));
  EXPECT_EQ(drain(s, 5), std::vector<std::string>({"{\"n\":1}", "{\"n\":2}", "{\"n\":9}"}));
}

TEST(EventSpool, ABrokenOrTruncatedLineIsDroppedAndCounted) {
  TempDir dir;
  const std::string path = (dir / "s").string();
  bodyrec::testing::write_text(path, "{\"topic\":\"a\",\"payload\":\"1\"}\nnot json\n{\"topic\":1,\"payload\":\"x\"}\n"
                                     "{\"topic\":\"a\",\"payload\":\"2\"}\n{\"topic\":\"a\",\"pay");
  EventSpool s(path, 10);
  EXPECT_EQ(s.recovered(), 2u);
  EXPECT_EQ(s.dropped(), 3u);
  EXPECT_EQ(drain(s, 5), std::vector<std::string>({"1", "2"}));
}

TEST(EventSpool, ManyDeliveriesCompactTheFile) {
  TempDir dir;
  const std::string path = (dir / "s").string();
  {
    EventSpool s(path, 5000);
    for (int i = 0; i < 3000; ++i) s.push(ev(i));
    drain(s, 2000);
    // Compacted at the 1501st delivery (more delivered than waiting): the file then held the 1499 waiting
    // lines, of which 499 more were delivered since.
    EXPECT_EQ(bodyrec::testing::lines_of(read_text(path)).size(), 1499u);
    EXPECT_EQ(read_text(path + ".sent"), "499\n");
  }
  EventSpool again(path, 5000);
  EXPECT_EQ(again.recovered(), 1000u);
  EXPECT_EQ(again.front().payload, "{\"n\":2000}");
}

// One process at a time: a second opening fails while the first holds the spool, and works after it.
TEST(EventSpool, ASpoolInUseCannotBeOpenedAgain) {
  TempDir dir;
  const std::string path = (dir / "s").string();
  {
    EventSpool s(path, 10);
    s.push(ev(1));
    EXPECT_THROW(EventSpool(path, 10, 0.0), SpoolInUse);
    EXPECT_THROW(EventSpool(path, 10, 0.2), SpoolInUse);
  }
  EventSpool again(path, 10);
  EXPECT_EQ(again.recovered(), 1u);
}

// A lock held for a moment (a `gallery forget` scrubbing the spool) does not stop a run that opens it.
TEST(EventSpool, ARunWaitsForALockHeldForAMoment) {
  TempDir dir;
  const std::string path = (dir / "s").string();
  std::promise<void> held;
  std::thread scrubber([&] {
    EventSpool s(path, 10);
    s.push(ev(1));
    held.set_value();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  });
  held.get_future().wait();
  EventSpool run(path, 10);  // waits up to 2 s
  EXPECT_EQ(run.recovered(), 1u);
  scrubber.join();
}

// Run as root (a system service's spool scrubbed by `sudo bodyrec gallery forget`): the rewritten files go
// back to their owner. Another user's spool is left alone by a process that is not root, and a spool that
// cannot be read is never taken for an empty one.
TEST(EventSpool, ScrubKeepsTheOwnerAndLeavesOtherUsersSpools) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to give files to another user";
  TempDir dir;
  const std::string path = (dir / "s").string();
  {
    EventSpool s(path, 10);
    s.push(ev(1));
    s.push(ev(2));
  }
  const uid_t nobody = 65534;
  for (const std::string& file : {path, path + ".sent", path + ".lock"}) ASSERT_EQ(::chown(file.c_str(), nobody, nobody), 0);
  const auto two = [](const SpooledEvent& e) { return e.payload == "{\"n\":2}"; };
  const SpoolScrub done = EventSpool::scrub(path, two);
  EXPECT_EQ(done.state, SpoolScrub::State::kScrubbed);
  EXPECT_EQ(done.removed, 1u);
  for (const std::string& file : {path, path + ".sent", path + ".lock"}) {
    struct stat st {};
    ASSERT_EQ(::stat(file.c_str(), &st), 0) << file;
    EXPECT_EQ(st.st_uid, nobody) << file;
    EXPECT_EQ(st.st_gid, nobody) << file;
  }
  // As another user (effective uid only, switched back below).
  const std::string mine = (dir / "root.spool").string();
  {
    EventSpool s(mine, 10);
    s.push(ev(3));
  }
  ASSERT_EQ(::chmod(dir.path().c_str(), 0777), 0);
  ASSERT_EQ(::chmod((mine + ".lock").c_str(), 0666), 0);  // so that the read is what fails below
  ASSERT_EQ(::seteuid(nobody), 0);
  const SpoolScrub other = EventSpool::scrub(mine, two);
  bool unreadable = false;
  try {
    EventSpool open(mine, 10, 0.0);
  } catch (const ProcessingError& e) {
    unreadable = std::string(e.what()).find("cannot read the event spool") != std::string::npos;
  }
  ASSERT_EQ(::seteuid(0), 0);
  EXPECT_EQ(other.state, SpoolScrub::State::kOtherOwner);
  EXPECT_TRUE(unreadable);
  EXPECT_EQ(bodyrec::testing::lines_of(read_text(mine)).size(), 1u);
}

// What `gallery forget --events-spool` does: the unwanted events and the delivered lines leave the file;
// a spool held by a running process is left to it.
TEST(EventSpool, ScrubRemovesUnwantedAndDeliveredLinesFromAClosedSpool) {
  TempDir dir;
  const std::string path = (dir / "s").string();
  const auto two_or_four = [](const SpooledEvent& e) { return e.payload == "{\"n\":2}" || e.payload == "{\"n\":4}"; };
  {
    EventSpool s(path, 100);
    for (int i = 0; i < 6; ++i) s.push(ev(i));
    drain(s, 1);  // n 0 delivered: its line stays in the file until compaction
    EXPECT_NE(read_text(path).find("\\\"n\\\":0"), std::string::npos);
    const SpoolScrub busy = EventSpool::scrub(path, two_or_four);
    EXPECT_EQ(busy.state, SpoolScrub::State::kInUse);
    EXPECT_EQ(busy.removed, 0u);
    EXPECT_EQ(bodyrec::testing::lines_of(read_text(path)).size(), 6u);
  }
  const SpoolScrub done = EventSpool::scrub(path, two_or_four);
  EXPECT_EQ(done.state, SpoolScrub::State::kScrubbed);
  EXPECT_EQ(done.removed, 2u);
  const std::string text = read_text(path);
  EXPECT_EQ(bodyrec::testing::lines_of(text).size(), 3u) << text;
  for (const char* gone : {"\\\"n\\\":0", "\\\"n\\\":2", "\\\"n\\\":4"})
    EXPECT_EQ(text.find(gone), std::string::npos) << text;
  EventSpool again(path, 100);
  EXPECT_EQ(drain(again, 10), std::vector<std::string>({"{\"n\":1}", "{\"n\":3}", "{\"n\":5}"}));
  EXPECT_THROW(EventSpool::scrub((dir / "none").string(), two_or_four), InputError);
}

TEST(EventSpool, AnUnwritableSpoolIsAProcessingError) {
  EXPECT_THROW(EventSpool("/nonexistent-dir/x.spool", 10), ProcessingError);
  EXPECT_THROW(EventSpool("/tmp/x.spool", 0), UsageError);
}

}  // namespace
}  // namespace bodyrec
