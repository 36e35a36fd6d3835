// The publisher without a broker: a run never waits for it, keeps every event in the spool, and says so.
// Delivery to a real broker is in mqtt_publisher_server_test.cc.
#include "bodyrec/events/mqtt_publisher.h"

#include <chrono>
#include <set>

#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec {
namespace {

TEST(EventPublisher, WithoutABrokerEventsWaitInTheSpoolAndNothingBlocks) {
  bodyrec::testing::TempDir dir;
  EventPublisherOptions o;
  o.target = parse_mqtt_uri("mqtt://127.0.0.1:1/site");  // nothing listens on port 1
  o.spool = (dir / "events.spool").string();
  o.spool_capacity = 50;
  o.drain_seconds = 30;  // not waited for: the broker refuses
  const auto t0 = std::chrono::steady_clock::now();
  {
    EventPublisher p(o);
    for (int i = 0; i < 60; ++i) p.publish("site/door/reid", "{\"n\":" + std::to_string(i) + "}");
    const PublisherStats s = p.close();
    EXPECT_EQ(s.delivered, 0u);
    EXPECT_EQ(s.pending, 50u);
    EXPECT_EQ(s.dropped, 10u);
    EXPECT_FALSE(s.connected);
  }
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(10));
  EventPublisher again(o);
  EXPECT_EQ(again.close().recovered, 50u);
}

TEST(EventIds, AreUniqueWithinARunAndAcrossRuns) {
  std::set<std::string> seen;
  for (int r = 0; r < 10; ++r) {
    EventIds ids;
    EXPECT_EQ(ids.run_id().size(), 32u);
    for (int i = 0; i < 100; ++i) EXPECT_TRUE(seen.insert(ids.next()).second);
  }
  EventIds ids;
  EXPECT_EQ(ids.next(), ids.run_id() + "-1");
  EXPECT_EQ(ids.next(), ids.run_id() + "-2");
}

}  // namespace
}  // namespace bodyrec
