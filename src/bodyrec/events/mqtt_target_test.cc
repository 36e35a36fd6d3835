#include "bodyrec/events/mqtt_target.h"

#include <sys/stat.h>

#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::contains;
using bodyrec::testing::usage_error;

TEST(MqttTarget, ParsesHostPortAndPrefix) {
  MqttTarget t = parse_mqtt_uri("mqtt://broker.local:1884/site/hall");
  EXPECT_FALSE(t.tls);
  EXPECT_EQ(t.host, "broker.local");
  EXPECT_EQ(t.port, 1884);
  EXPECT_EQ(t.prefix, "site/hall");
  t = parse_mqtt_uri("mqtts://10.0.0.2/bodyrec");
  EXPECT_TRUE(t.tls);
  EXPECT_EQ(t.port, 8883);
  EXPECT_EQ(parse_mqtt_uri("mqtt://h/p").port, 1883);
  t = parse_mqtt_uri("mqtt://[::1]:2000/p");
  EXPECT_EQ(t.host, "::1");
  EXPECT_EQ(t.port, 2000);
}

TEST(MqttTarget, BrokenUrisAreUsageErrors) {
  for (const char* bad : {"", "http://h/p", "mqtt://h", "mqtt://h/", "mqtt:///p", "mqtt://h:0/p", "mqtt://h:70000/p",
                          "mqtt://h:x/p", "mqtt://h:/p", "mqtt://h/a//b", "mqtt://h/a/#", "mqtt://h/+/b", "mqtt://[::1/p",
                          "mqtt://h/p/"})
    EXPECT_TRUE(contains(usage_error([&] { parse_mqtt_uri(bad); }), "--events")) << bad;
  const std::string m = usage_error([] { parse_mqtt_uri("mqtt://user:hunter2@h/p"); });
  EXPECT_TRUE(contains(m, "--events-credentials")) << m;
  EXPECT_FALSE(contains(m, "hunter2")) << m;
}

TEST(MqttTarget, CredentialsComeFromAPrivateFile) {
  bodyrec::testing::TempDir dir;
  const std::string path = (dir / "mqtt.cred").string();
  bodyrec::testing::write_text(path, "# broker account\nusername=door\npassword=p=ss word\n");
  ::chmod(path.c_str(), 0644);
  const std::string m = usage_error([&] { read_mqtt_credentials(path); });
  EXPECT_TRUE(contains(m, "readable by others (mode 644); chmod 600 it")) << m;
  ::chmod(path.c_str(), 0600);
  const MqttCredentials c = read_mqtt_credentials(path);
  EXPECT_EQ(c.username, "door");
  EXPECT_EQ(c.password, "p=ss word");
  bodyrec::testing::write_text(path, "user door\n");
  EXPECT_EQ(bodyrec::testing::input_error([&] { read_mqtt_credentials(path); }),
            path + ": line 1: expected username=NAME or password=SECRET");
  bodyrec::testing::write_text(path, "username=door\n");
  EXPECT_EQ(bodyrec::testing::input_error([&] { read_mqtt_credentials(path); }), path + ": no password= line");
  EXPECT_TRUE(contains(bodyrec::testing::input_error([&] { read_mqtt_credentials(path + ".missing"); }),
                       "cannot read credentials"));
}

TEST(MqttTarget, SensorIdsAreTopicLevels) {
  EXPECT_TRUE(valid_sensor_id("door-1.hall_B"));
  for (const char* bad : {"", "a/b", "a+b", "#", "a b", "é"}) EXPECT_FALSE(valid_sensor_id(bad)) << bad;
  EXPECT_FALSE(valid_sensor_id(std::string(65, 'a')));
  EXPECT_TRUE(valid_sensor_id(default_sensor_id()));
}

}  // namespace
}  // namespace bodyrec
