#include "bodyrec/events/event_spool.h"

#include <sys/stat.h>

#include <fstream>

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
  EventSpool s(path, 5000);
  for (int i = 0; i < 3000; ++i) s.push(ev(i));
  drain(s, 2000);
  // Compacted at the 1501st delivery (more delivered than waiting): the file then held the 1499 waiting
  // lines, of which 499 more were delivered since.
  EXPECT_EQ(bodyrec::testing::lines_of(read_text(path)).size(), 1499u);
  EXPECT_EQ(read_text(path + ".sent"), "499\n");
  EventSpool again(path, 5000);
  EXPECT_EQ(again.recovered(), 1000u);
  EXPECT_EQ(again.front().payload, "{\"n\":2000}");
}

TEST(EventSpool, AnUnwritableSpoolIsAProcessingError) {
  EXPECT_THROW(EventSpool("/nonexistent-dir/x.spool", 10), ProcessingError);
  EXPECT_THROW(EventSpool("/tmp/x.spool", 0), UsageError);
}

}  // namespace
}  // namespace bodyrec
