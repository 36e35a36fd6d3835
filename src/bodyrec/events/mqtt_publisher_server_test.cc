// The publisher against a real Mosquitto broker (tests/support/server_fixtures.h, ctest label `server`): QoS 1
// delivery in order, a broker that stops and comes back in the middle, spool overflow, credentials.
#include <sys/stat.h>

#include <set>

#include <gtest/gtest.h>

#include "bodyrec/events/mqtt_publisher.h"
#include "server_fixtures.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::MosquittoServer;
using bodyrec::testing::MqttSubscriber;

std::string payload(int n) { return "{\"event_id\":\"e-" + std::to_string(n) + "\",\"n\":" + std::to_string(n) + "}"; }

// The payloads' numbers in arrival order after dropping repeats (by event id), as a subscriber does.
std::vector<int> deduplicated(const std::vector<MqttSubscriber::Message>& messages) {
  std::set<std::string> seen;
  std::vector<int> out;
  for (const auto& m : messages) {
    const auto j = nlohmann::json::parse(m.payload);
    if (seen.insert(j["event_id"].get<std::string>()).second) out.push_back(j["n"].get<int>());
  }
  return out;
}

std::vector<int> range(int from, int to) {
  std::vector<int> v;
  for (int i = from; i < to; ++i) v.push_back(i);
  return v;
}

EventPublisherOptions options_for(const MosquittoServer& broker, const bodyrec::testing::TempDir& dir,
                                  const std::string& prefix) {
  EventPublisherOptions o;
  o.target = parse_mqtt_uri(broker.uri(prefix));
  o.spool = (dir / "events.spool").string();
  o.drain_seconds = 60;
  return o;
}

TEST(EventPublisherServer, EventsArriveWithQos1InOrder) {
  BODYREC_REQUIRE_MOSQUITTO(broker);
  bodyrec::testing::TempDir dir;
  MqttSubscriber sub(broker->port(), "order/#", "sub-order");
  ASSERT_TRUE(sub.subscribed(std::chrono::seconds(20)));
  EventPublisher p(options_for(*broker, dir, "order"));
  for (int i = 0; i < 200; ++i) p.publish("order/door/reid", payload(i));
  const PublisherStats s = p.close();
  EXPECT_EQ(s.delivered, 200u);
  EXPECT_EQ(s.pending, 0u);
  EXPECT_EQ(s.dropped, 0u);
  const auto got = sub.wait_for(200, std::chrono::seconds(30));
  ASSERT_EQ(got.size(), 200u);  // no repeats without an outage
  EXPECT_EQ(got[0].topic, "order/door/reid");
  EXPECT_EQ(deduplicated(got), range(0, 200));
}

// Issue 47: the broker stops in the middle of a run and comes back; every event arrives, in order, and
// after dropping repeats by event_id none twice.
TEST(EventPublisherServer, ABrokerOutageInTheMiddleLosesNothingAndKeepsTheOrder) {
  BODYREC_OWN_MOSQUITTO(broker, MosquittoServer::Options{});
  bodyrec::testing::TempDir dir;
  MqttSubscriber sub(broker->port(), "outage/#", "sub-outage");
  ASSERT_TRUE(sub.subscribed(std::chrono::seconds(20)));
  EventPublisher p(options_for(*broker, dir, "outage"));
  for (int i = 0; i < 100; ++i) p.publish("outage/door/reid", payload(i));
  sub.wait_for(100, std::chrono::seconds(30));
  broker->stop();
  for (int i = 100; i < 200; ++i) p.publish("outage/door/reid", payload(i));  // never blocks
  EXPECT_GE(p.stats().pending, 90u);
  broker->start();
  for (int i = 200; i < 300; ++i) p.publish("outage/door/reid", payload(i));
  const PublisherStats s = p.close();
  EXPECT_EQ(s.pending, 0u);
  EXPECT_EQ(s.dropped, 0u);
  EXPECT_EQ(deduplicated(sub.wait_for(300, std::chrono::seconds(60))), range(0, 300));
}

TEST(EventPublisherServer, AnOverflowIsCountedAndTheSpoolGoesFirstInTheNextRun) {
  BODYREC_REQUIRE_MOSQUITTO(broker);
  bodyrec::testing::TempDir dir;
  EventPublisherOptions o = options_for(*broker, dir, "overflow");
  o.spool_capacity = 10;
  {
    EventPublisherOptions down = o;
    down.target.port = 1;  // nothing listens there
    EventPublisher p(down);
    for (int i = 0; i < 25; ++i) p.publish("overflow/door/reid", payload(i));
    const PublisherStats s = p.close();
    EXPECT_EQ(s.pending, 10u);
    EXPECT_EQ(s.dropped, 15u);
  }
  MqttSubscriber sub(broker->port(), "overflow/#", "sub-overflow");
  ASSERT_TRUE(sub.subscribed(std::chrono::seconds(20)));
  o.spool_capacity = 100;  // room for this run's event behind the 10 waiting
  EventPublisher p(o);
  p.publish("overflow/door/reid", payload(100));
  const PublisherStats s = p.close();
  EXPECT_EQ(s.recovered, 10u);
  EXPECT_EQ(s.delivered, 11u);
  std::vector<int> expected = range(0, 10);
  expected.push_back(100);
  EXPECT_EQ(deduplicated(sub.wait_for(11, std::chrono::seconds(30))), expected);
}

TEST(EventPublisherServer, CredentialsFromTheFileAreUsedAndWrongOnesDeliverNothing) {
  if (!std::filesystem::exists("/usr/bin/mosquitto_passwd")) GTEST_SKIP() << "mosquitto_passwd not installed";
  bodyrec::testing::TempDir dir;
  const std::string passwords = (dir / "passwords").string();
  ASSERT_EQ(bodyrec::testing::run_program({"/usr/bin/mosquitto_passwd", "-c", "-b", passwords, "door", "s3cret"}, "",
                                          (dir / "passwd.log").string()),
            0);
  MosquittoServer::Options options;
  options.password_file = passwords;
  BODYREC_OWN_MOSQUITTO(broker, options);
  EventPublisherOptions o = options_for(*broker, dir, "auth");
  o.credentials = MqttCredentials{"door", "wrong"};
  o.drain_seconds = 3;
  {
    EventPublisher p(o);
    p.publish("auth/door/reid", payload(1));
    const PublisherStats s = p.close();
    EXPECT_EQ(s.delivered, 0u);
    EXPECT_EQ(s.pending, 1u);
  }
  o.credentials = MqttCredentials{"door", "s3cret"};
  o.drain_seconds = 60;
  EventPublisher p(o);
  const PublisherStats s = p.close();
  EXPECT_EQ(s.delivered, 1u);
  EXPECT_EQ(s.pending, 0u);
}

// mqtts://: the broker's certificate is checked against --events-cafile; without it, against the system's
// CAs, which do not know this test's CA, so nothing is delivered.
TEST(EventPublisherServer, TlsDeliversOnlyToABrokerTheCaVouchesFor) {
  if (!std::filesystem::exists("/usr/bin/openssl")) GTEST_SKIP() << "openssl not installed";
  bodyrec::testing::TempDir dir;
  const auto path = [&](const char* name) { return (dir / name).string(); };
  const std::string log = path("openssl.log");
  bodyrec::testing::write_text(path("san.ext"), "subjectAltName=IP:127.0.0.1\n");
  const std::vector<std::vector<std::string>> steps = {
      {"/usr/bin/openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", path("ca.key"), "-out",
       path("ca.pem"), "-days", "2", "-subj", "/CN=bodyrec test CA"},
      {"/usr/bin/openssl", "req", "-newkey", "rsa:2048", "-nodes", "-keyout", path("server.key"), "-out",
       path("server.csr"), "-subj", "/CN=127.0.0.1"},
      {"/usr/bin/openssl", "x509", "-req", "-in", path("server.csr"), "-CA", path("ca.pem"), "-CAkey", path("ca.key"),
       "-CAcreateserial", "-out", path("server.pem"), "-days", "2", "-extfile", path("san.ext")}};
  for (const auto& step : steps) ASSERT_EQ(bodyrec::testing::run_program(step, "", log), 0) << bodyrec::testing::read_text(log);
  MosquittoServer::Options options;
  options.tls_cafile = path("ca.pem");
  options.tls_certfile = path("server.pem");
  options.tls_keyfile = path("server.key");
  BODYREC_OWN_MOSQUITTO(broker, options);
  EventPublisherOptions o;
  o.target = parse_mqtt_uri("mqtts://127.0.0.1:" + std::to_string(broker->port()) + "/tls");
  o.spool = path("events.spool");
  o.drain_seconds = 3;
  {
    EventPublisher p(o);  // the system's CAs: the broker is not trusted
    p.publish("tls/door/reid", payload(1));
    const PublisherStats s = p.close();
    EXPECT_EQ(s.delivered, 0u);
    EXPECT_EQ(s.pending, 1u);
  }
  o.cafile = path("ca.pem");
  o.drain_seconds = 60;
  EventPublisher p(o);
  p.publish("tls/door/reid", payload(2));
  const PublisherStats s = p.close();
  EXPECT_EQ(s.delivered, 2u);
  EXPECT_EQ(s.pending, 0u);
}

}  // namespace
}  // namespace bodyrec
