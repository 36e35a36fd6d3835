#include "bodyrec/events/mqtt_publisher.h"

#include <mosquitto.h>

#include <chrono>
#include <cstdio>

#include "bodyrec/core/error.h"

namespace bodyrec {

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kFirstRetry = std::chrono::milliseconds(200);
constexpr auto kLastRetry = std::chrono::seconds(2);
constexpr auto kConnectTimeout = std::chrono::seconds(10);
constexpr int kLoopMs = 50;

std::string random_hex(int digits) {
  static const char* hex = "0123456789abcdef";
  std::random_device rd;
  std::string out;
  while (static_cast<int>(out.size()) < digits) {
    uint32_t v = rd();
    for (int i = 0; i < 8 && static_cast<int>(out.size()) < digits; ++i, v >>= 4) out += hex[v & 15];
  }
  return out;
}

}  // namespace

EventIds::EventIds() : run_(random_hex(32)) {}

std::string EventIds::next() { return run_ + "-" + std::to_string(next_++); }

EventPublisher::EventPublisher(const EventPublisherOptions& options)
    : options_(options), spool_(options.spool, options.spool_capacity) {
  static std::once_flag once;
  std::call_once(once, [] { mosquitto_lib_init(); });
  if (options_.client_id.empty()) options_.client_id = "bodyrec-" + random_hex(12);
  thread_ = std::thread([this] { run(); });
}

EventPublisher::~EventPublisher() { close(); }

void EventPublisher::publish(const std::string& topic, const std::string& payload) {
  std::lock_guard<std::mutex> lock(mutex_);
  spool_.push({topic, payload});
}

size_t EventPublisher::withdraw(const std::function<bool(const std::string& payload)>& unwanted) {
  std::lock_guard<std::mutex> lock(mutex_);
  const size_t n = spool_.erase_if([&](const SpooledEvent& e) { return unwanted(e.payload); },
                                   inflight_.has_value() || sending_front_);
  withdrawn_ += n;
  return n;
}

PublisherStats EventPublisher::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_unlocked();
}

PublisherStats EventPublisher::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return stats_unlocked();
    stopping_ = true;
    deadline_ = Clock::now() + std::chrono::milliseconds(static_cast<int64_t>(options_.drain_seconds * 1000));
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  closed_ = true;
  return stats_unlocked();
}

PublisherStats EventPublisher::stats_unlocked() const {
  PublisherStats s;
  s.delivered = delivered_;
  s.pending = spool_.size();
  s.dropped = spool_.dropped();
  s.recovered = spool_.recovered();
  s.withdrawn = withdrawn_;
  s.connected = ever_connected_;
  return s;
}

bool EventPublisher::connect() {
  client_ = mosquitto_new(options_.client_id.c_str(), true, this);
  if (!client_) return false;
  mosquitto_connect_callback_set(client_, on_connect);
  mosquitto_disconnect_callback_set(client_, on_disconnect);
  mosquitto_publish_callback_set(client_, on_publish);
  mosquitto_int_option(client_, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V311);
  bool ok = true;
  if (options_.credentials)
    ok = mosquitto_username_pw_set(client_, options_.credentials->username.c_str(),
                                   options_.credentials->password.c_str()) == MOSQ_ERR_SUCCESS;
  if (ok && options_.target.tls)
    ok = mosquitto_tls_set(client_, options_.cafile.empty() ? nullptr : options_.cafile.c_str(),
                           options_.cafile.empty() ? "/etc/ssl/certs" : nullptr, nullptr, nullptr,
                           nullptr) == MOSQ_ERR_SUCCESS;
  if (ok)
    ok = mosquitto_connect_async(client_, options_.target.host.c_str(), options_.target.port, options_.keepalive_s) ==
         MOSQ_ERR_SUCCESS;
  if (!ok) disconnect();
  return ok;
}

void EventPublisher::disconnect() {
  if (!client_) return;
  mosquitto_disconnect(client_);
  mosquitto_destroy(client_);
  client_ = nullptr;
  std::lock_guard<std::mutex> lock(mutex_);
  connected_ = false;
  refused_ = false;
  inflight_.reset();  // resent after reconnecting: a repeat at worst
}

void EventPublisher::on_connect(mosquitto*, void* self, int rc) {
  auto* p = static_cast<EventPublisher*>(self);
  std::lock_guard<std::mutex> lock(p->mutex_);
  if (rc == 0) {
    p->connected_ = p->ever_connected_ = true;
  } else {
    p->refused_ = true;  // e.g. bad credentials: the broker closes the connection
  }
}

void EventPublisher::on_disconnect(mosquitto*, void* self, int) {
  auto* p = static_cast<EventPublisher*>(self);
  std::lock_guard<std::mutex> lock(p->mutex_);
  p->connected_ = false;
}

// Called by mosquitto_loop on the delivery thread when the broker acknowledged a QoS 1 message.
void EventPublisher::on_publish(mosquitto*, void* self, int mid) {
  auto* p = static_cast<EventPublisher*>(self);
  std::lock_guard<std::mutex> lock(p->mutex_);
  if (!p->inflight_ || *p->inflight_ != mid) return;
  p->inflight_.reset();
  try {
    p->spool_.pop();
  } catch (const Error& e) {
    // The event left the queue; only its record on disk failed (a later run may send it again).
    if (!p->spool_error_) std::fprintf(stderr, "bodyrec: %s\n", e.what());
    p->spool_error_ = true;
  }
  ++p->delivered_;
}

void EventPublisher::run() {
  std::chrono::milliseconds retry = kFirstRetry;
  auto next_attempt = Clock::now();
  Clock::time_point connecting_since;
  for (;;) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto now = Clock::now();
    if (stopping_ && (spool_.empty() || failed_since_stop_ || now >= deadline_)) break;
    if (!client_) {
      if (now < next_attempt) {
        wake_.wait_until(lock, stopping_ ? std::min(next_attempt, deadline_) : next_attempt);
        continue;
      }
      lock.unlock();
      const bool started = connect();
      lock.lock();
      if (started) {
        connecting_since = Clock::now();
      } else {
        if (stopping_) failed_since_stop_ = true;
        next_attempt = Clock::now() + retry;
        retry = std::min<std::chrono::milliseconds>(retry * 2, kLastRetry);
      }
      continue;
    }
    std::optional<SpooledEvent> send;
    if (connected_ && !inflight_ && !spool_.empty()) {
      send = spool_.front();
      sending_front_ = true;  // withdraw() keeps it until it is in flight or back in the queue
    }
    const bool stalled = !connected_ && (refused_ || Clock::now() - connecting_since > kConnectTimeout);
    lock.unlock();
    int rc = MOSQ_ERR_SUCCESS;
    if (send) {
      int mid = 0;
      rc = mosquitto_publish(client_, &mid, send->topic.c_str(), static_cast<int>(send->payload.size()),
                             send->payload.data(), 1, false);
      lock.lock();
      if (rc == MOSQ_ERR_SUCCESS) inflight_ = mid;
      sending_front_ = false;
      lock.unlock();
    }
    if (rc == MOSQ_ERR_SUCCESS && !stalled) rc = mosquitto_loop(client_, kLoopMs, 1);
    if (rc != MOSQ_ERR_SUCCESS || stalled) {
      disconnect();
      lock.lock();
      if (stopping_) failed_since_stop_ = true;
      next_attempt = Clock::now() + retry;
      retry = std::min<std::chrono::milliseconds>(retry * 2, kLastRetry);
    } else {
      lock.lock();
      if (connected_) retry = kFirstRetry;
    }
  }
  disconnect();
}

}  // namespace bodyrec
