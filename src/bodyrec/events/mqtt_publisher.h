// Events over MQTT (issue 47): a run publishes its events as JSON with QoS 1 without ever waiting for the
// broker. Every event goes through the spool (event_spool.h) first; a thread of this object delivers the
// spool's events one at a time, in order, each removed only once the broker acknowledged it (PUBACK), and
// reconnects (every 0.2 s doubling to 2 s) when the broker goes away. Events that could not be delivered
// by the end of the run stay in the spool and go first in the next run that uses it. An event is lost
// only when the spool is full; those are counted (stats().dropped).
//
//   EventPublisher events(options);                       // connects in the background
//   events.publish("site/door/reid", payload_json);       // never blocks on the broker
//   const PublisherStats s = events.close();              // waits up to drain_seconds while it can deliver
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>

#include "bodyrec/events/event_spool.h"
#include "bodyrec/events/mqtt_target.h"

struct mosquitto;

namespace bodyrec {

struct EventPublisherOptions {
  MqttTarget target;
  std::optional<MqttCredentials> credentials;
  std::string cafile;            // mqtts: CA certificates (PEM); empty: the system's, /etc/ssl/certs
  std::string spool;             // the spool file (required)
  size_t spool_capacity = 10000;  // undelivered events kept; more are dropped and counted
  std::string client_id;         // MQTT client id; empty: bodyrec-<random>
  double drain_seconds = 5;      // close(): longest wait for undelivered events while the broker answers
  int keepalive_s = 30;
};

struct PublisherStats {
  size_t delivered = 0;  // acknowledged by the broker (this run's and recovered ones)
  size_t pending = 0;    // still in the spool (delivered by a later run)
  size_t dropped = 0;    // lost: the spool was full, or its file held unreadable lines
  size_t recovered = 0;  // undelivered events of an earlier run found in the spool at the start
  size_t withdrawn = 0;  // taken back before delivery (withdraw)
  bool connected = false;  // the broker answered at least once during the run
};

class EventPublisher {
 public:
  // Opens the spool (ProcessingError when it cannot be written) and starts delivering.
  explicit EventPublisher(const EventPublisherOptions& options);
  ~EventPublisher();  // close()
  EventPublisher(const EventPublisher&) = delete;
  EventPublisher& operator=(const EventPublisher&) = delete;

  // Queues one event (QoS 1); returns at once. ProcessingError when the spool file cannot be written.
  void publish(const std::string& topic, const std::string& payload);
  // Takes back every undelivered event whose payload `unwanted` names (e.g. a user erased from the gallery
  // meanwhile): removed from the spool and its file, never delivered. The one event on its way to the
  // broker, if any, cannot be taken back. Returns how many were removed.
  size_t withdraw(const std::function<bool(const std::string& payload)>& unwanted);
  // Waits while events are undelivered and the broker answers, at most drain_seconds (not at all when
  // the broker refused or could not be reached since close was called), then disconnects. Idempotent.
  PublisherStats close();
  PublisherStats stats() const;

 private:
  void run();
  bool connect();
  PublisherStats stats_unlocked() const;
  void disconnect();
  static void on_connect(mosquitto*, void* self, int rc);
  static void on_disconnect(mosquitto*, void* self, int rc);
  static void on_publish(mosquitto*, void* self, int mid);

  EventPublisherOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  EventSpool spool_;
  mosquitto* client_ = nullptr;  // the thread's only
  bool connected_ = false, ever_connected_ = false, refused_ = false;
  bool stopping_ = false, failed_since_stop_ = false, spool_error_ = false;
  std::chrono::steady_clock::time_point deadline_;
  std::optional<int> inflight_;  // mid of the front event, sent and not acknowledged
  bool sending_front_ = false;    // the front event is being handed to the broker (inflight_ not yet set)
  size_t delivered_ = 0, withdrawn_ = 0;
  std::thread thread_;
  bool closed_ = false;
};

// Unique event ids (issue 47: subscribers drop repeats by it): 32 hex digits drawn once per object
// (per run), then "-" and a sequence number, e.g. "3f2a...9c-17".
class EventIds {
 public:
  EventIds();
  std::string next();
  const std::string& run_id() const { return run_; }

 private:
  std::string run_;
  uint64_t next_ = 1;
};

}  // namespace bodyrec
