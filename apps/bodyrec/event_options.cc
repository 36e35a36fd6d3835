#include "event_options.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>

#include "bodyrec/core/error.h"
#include "bodyrec/io/json_numbers.h"
#include "option_checks.h"

namespace bodyrec::cli {

namespace {

// "2026-12-06T22:05:01.123Z"
std::string wall_time_now() {
  const auto now = std::chrono::system_clock::now();
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count();
  const std::time_t s = static_cast<std::time_t>(ms / 1000);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char text[96];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(ms % 1000));
  return text;
}

}  // namespace

void add_sensor_option(CLI::App& sub, EventCliOptions& o) {
  sub.add_option("--sensor-id", o.sensor,
                 "This sensor's name, recorded with its gallery events and in its MQTT topics and payloads "
                 "(letters, digits, '.', '_', '-')")
      ->default_str("the host name");
}

void add_event_options(CLI::App& sub, EventCliOptions& o) {
  sub.add_option("--events", o.uri,
                 "Publish events over MQTT (QoS 1) to mqtt://HOST[:PORT]/PREFIX or mqtts://... (TLS): topic "
                 "PREFIX/<sensor-id>/<command>, JSON payloads (docs/events.md). Never waits for the broker: "
                 "undelivered events wait in --events-spool");
  sub.add_option("--events-credentials", o.credentials,
                 "File with lines username=NAME and password=SECRET for the broker (mode 0600; never on the "
                 "command line)");
  sub.add_option("--events-cafile", o.cafile, "mqtts: CA certificates (PEM) to verify the broker; default: the system's");
  sub.add_option("--events-spool", o.spool,
                 "File holding events not yet delivered (kept across runs, sent first next time)")
      ->default_str("bodyrec-<sensor-id>-<command>.spool");
  sub.add_option("--events-spool-max", o.spool_max,
                 "Undelivered events the spool keeps; newer ones are dropped and counted")
      ->check(positive())
      ->capture_default_str();
  sub.add_option("--events-wait", o.wait_s,
                 "At the end, seconds to wait for undelivered events while the broker answers")
      ->check(non_negative())
      ->capture_default_str();
}

std::string sensor_id(const EventCliOptions& o) {
  if (o.sensor.empty()) return default_sensor_id();
  if (!valid_sensor_id(o.sensor))
    throw UsageError("--sensor-id: '" + o.sensor + "': use 1 to 64 letters, digits, '.', '_' or '-' (it is an MQTT topic level)");
  return o.sensor;
}

RunEvents open_events(const EventCliOptions& o, const std::string& kind) {
  RunEvents events;
  events.sensor = sensor_id(o);
  const bool given = !o.credentials.empty() || !o.cafile.empty() || !o.spool.empty();
  if (o.uri.empty()) {
    if (given) throw UsageError("--events-credentials, --events-cafile and --events-spool need --events");
    return events;
  }
  EventPublisherOptions p;
  p.target = parse_mqtt_uri(o.uri);
  if (!o.credentials.empty()) p.credentials = read_mqtt_credentials(o.credentials);
  if (!o.cafile.empty()) {
    if (!p.target.tls) throw UsageError("--events-cafile needs an mqtts:// URI");
    if (::access(o.cafile.c_str(), R_OK) != 0) throw InputError(o.cafile + ": cannot read the CA file");
    p.cafile = o.cafile;
  }
  p.spool = o.spool.empty() ? "bodyrec-" + events.sensor + "-" + kind + ".spool" : o.spool;
  p.spool_capacity = static_cast<size_t>(o.spool_max);
  p.drain_seconds = o.wait_s;
  p.client_id = "bodyrec-" + events.sensor + "-" + kind + "-" + events.ids.run_id().substr(0, 8);
  events.topic = p.target.prefix + "/" + events.sensor + "/" + kind;
  events.spool = p.spool;
  events.publisher = std::make_unique<EventPublisher>(p);
  return events;
}

void RunEvents::publish(nlohmann::json payload) {
  if (!publisher) return;
  payload["event_id"] = ids.next();
  payload["schema"] = 1;
  payload["sensor"] = sensor;
  payload["run"] = ids.run_id();
  payload["wall_time"] = wall_time_now();
  publisher->publish(topic, json_text(payload));
}

std::optional<int64_t> event_user(const std::string& payload) {
  const auto j = nlohmann::json::parse(payload, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  const auto user = j.find("user");
  if (user == j.end() || !user->is_number_integer()) return std::nullopt;
  return user->get<int64_t>();
}

size_t RunEvents::withdraw_erased(const std::function<bool(int64_t user)>& exists) {
  if (!publisher) return 0;
  return publisher->withdraw([&](const std::string& payload) {
    const std::optional<int64_t> user = event_user(payload);
    return user && !exists(*user);
  });
}

nlohmann::json RunEvents::finish() {
  if (!publisher) return nullptr;
  const PublisherStats s = publisher->close();
  if (s.dropped > 0)
    std::fprintf(stderr, "bodyrec: %zu events lost: the event spool %s was full (--events-spool-max)\n", s.dropped,
                 spool.c_str());
  if (s.pending > 0)
    std::fprintf(stderr, "bodyrec: %zu events not delivered yet (broker %s); kept in %s for the next run\n", s.pending,
                 s.connected ? "too slow" : "unreachable", spool.c_str());
  return {{"delivered", s.delivered}, {"pending", s.pending}, {"dropped", s.dropped},
          {"recovered", s.recovered}, {"withdrawn", s.withdrawn}, {"spool", spool}, {"topic", topic}};
}

}  // namespace bodyrec::cli
