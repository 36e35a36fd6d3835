// Events over MQTT for `reid` and `groups` (issue 47): --sensor-id, --events and its security and spool
// options, the publisher they open, and the summary a run ends with. The payloads are documented in
// docs/events.md.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bodyrec/events/mqtt_publisher.h"

namespace bodyrec::cli {

struct EventCliOptions {
  std::string sensor;       // --sensor-id; "" = default_sensor_id() (the host name)
  std::string uri;          // --events; "" = no events
  std::string credentials;  // --events-credentials FILE
  std::string cafile;       // --events-cafile FILE
  std::string spool;        // --events-spool FILE; "" = bodyrec-<sensor>-<kind>.spool in the working directory
  int spool_max = 10000;    // --events-spool-max
  double wait_s = 5;        // --events-wait
};

// --sensor-id.
void add_sensor_option(CLI::App& sub, EventCliOptions& options);
// --events, --events-credentials, --events-cafile, --events-spool, --events-spool-max, --events-wait.
void add_event_options(CLI::App& sub, EventCliOptions& options);

// The sensor id in effect: as given (UsageError unless it is a valid topic level), else the host name.
std::string sensor_id(const EventCliOptions& options);

// The run's events: topic PREFIX/<sensor>/<kind>, ids, publisher. Null publisher without --events.
struct RunEvents {
  std::string topic, sensor, spool;
  EventIds ids;
  std::unique_ptr<EventPublisher> publisher;

  // Adds event_id, schema, sensor, run and wall_time to `payload` and publishes it (no-op without --events).
  void publish(nlohmann::json payload);
  // Takes back the undelivered events (this run's and those an earlier run left in the spool) of every user
  // for whom `exists` is false: a user erased from the gallery is never published afterwards. Returns how
  // many were taken back (0 without --events).
  size_t withdraw_erased(const std::function<bool(int64_t user)>& exists);
  // Closes the publisher; returns the summary for the run's --json ({delivered, pending, dropped, recovered,
  // withdrawn, spool}, null without --events) and writes a line on stderr when events were dropped or wait undelivered.
  nlohmann::json finish();
};

// The gallery user an event payload is about (its integer "user"), or nothing.
std::optional<int64_t> event_user(const std::string& payload);

// Checks the options (UsageError, InputError for an unreadable credentials or CA file) and starts the
// publisher of `kind` ("reid" or "groups").
RunEvents open_events(const EventCliOptions& options, const std::string& kind);

}  // namespace bodyrec::cli
