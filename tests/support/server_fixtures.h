// Private PostgreSQL and Mosquitto servers for the tests and benchmarks that need real ones (ctest label
// `server`). Each lives in its own temporary folder, is started by this process and stopped when it
// ends, also when a test fails; each server process gets a parent-death signal, so a crashed test
// program leaves no server running either.
//  - PostgreSQL: initdb in the folder, a Unix socket there and no TCP port (listen_addresses=''), trust
//    authentication for local connections. Run as the `postgres` system user when this process is root
//    (the server refuses root), the folder then owned by it.
//  - Mosquitto: 127.0.0.1 on a free port, the configuration written here, persistence in the folder only.
//    Run as the `mosquitto` system user when root.
// No gtest here: the benchmarks use it too.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

struct mosquitto;
struct mosquitto_message;

namespace bodyrec::testing {

// A server program run as a child process, with its log in a file.
class ServerProcess {
 public:
  ServerProcess() = default;
  ~ServerProcess();
  // Forks and execs argv (as `user` when this process is root and user is not empty), stdout and stderr
  // to `log`; the child gets `death_signal` when this process dies.
  void start(const std::vector<std::string>& argv, const std::string& user, const std::string& log,
             int death_signal);
  // Sends `signal`, waits up to `wait` for the exit, then SIGKILL. No-op when not running.
  void stop(int signal, std::chrono::seconds wait = std::chrono::seconds(30));
  bool running();
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
};

// Runs a program to completion as `user` (when root), output to `log`; returns its exit status (-1 when
// killed by a signal).
int run_program(const std::vector<std::string>& argv, const std::string& user, const std::string& log);

// A new temporary folder (mode 0700) owned by `user` when root; removed by remove_folder.
std::string make_server_folder(const std::string& prefix, const std::string& user);
void remove_folder(const std::string& path);

class PostgresServer {
 public:
  // The server shared by this test program, started at the first call and stopped at exit. Null, with
  // `why` saying what is missing, when PostgreSQL's server programs are not installed (set
  // BODYREC_PG_BIN to their folder when they are elsewhere than /usr/lib/postgresql/<version>/bin).
  static PostgresServer* shared(std::string* why);
  // A server of one's own. `durable`: fsync on, as a production server (the benchmarks); the tests'
  // servers run with fsync off (a machine crash is not what they test; a server restart keeps every
  // commit either way). Null with `why` when the server programs are missing.
  static std::unique_ptr<PostgresServer> make(bool durable, std::string* why);

  // A new empty database on the server; returns its connection URI (as the superuser `postgres`).
  std::string create_database(const std::string& prefix = "t");
  // The URI of database `db` as role `user`.
  std::string uri(const std::string& db, const std::string& user = "postgres") const;
  // SQL as the superuser on database `db` (throws std::runtime_error with the server's message).
  void exec(const std::string& db, const std::string& sql) const;
  // pg_dump of `db` in plain SQL text.
  std::string dump(const std::string& db) const;
  // Every byte of database `db`'s files (base/<oid>: its tables, their TOAST, indexes, free space maps);
  // not the WAL.
  std::string table_files_bytes(const std::string& db) const;
  // The first column of the first row of `sql` on `db`, as text ("" when no row).
  std::string query(const std::string& db, const std::string& sql) const;

  void stop();     // fast shutdown (clients are disconnected); waits
  void start();    // same folder, same socket
  void restart() { stop(); start(); }

  const std::string& folder() const { return folder_; }
  const std::string& bin() const { return bin_; }
  ~PostgresServer();

 private:
  PostgresServer(const std::string& bin, bool durable);
  std::string bin_, folder_, user_;
  bool durable_ = false;
  ServerProcess server_;
  int databases_ = 0;
};

class MosquittoServer {
 public:
  struct Options {
    std::string password_file;  // empty: anonymous clients allowed
    // TLS on the listener when all three are given (PEM files, copied into the broker's folder).
    std::string tls_cafile, tls_certfile, tls_keyfile;
  };
  // The broker shared by this test program (anonymous clients), started at the first call, stopped at
  // exit. Null, with `why`, when /usr/sbin/mosquitto is not installed.
  static MosquittoServer* shared(std::string* why);
  // A broker of one's own; null with `why` when mosquitto is not installed.
  static std::unique_ptr<MosquittoServer> make(const Options& options, std::string* why);

  int port() const { return port_; }
  // mqtt://127.0.0.1:PORT/PREFIX
  std::string uri(const std::string& prefix) const;
  void stop();   // SIGTERM: the broker saves its sessions (in the folder) and exits; waits
  void start();  // same port, same folder
  const std::string& folder() const { return folder_; }
  ~MosquittoServer();

 private:
  MosquittoServer(const Options& options);
  Options options_;
  std::string folder_, user_;
  int port_ = 0;
  ServerProcess server_;
};

// A test subscriber: a persistent session (clean session off, fixed client id) subscribed with QoS 1
// to `topic`, so that messages the broker took while it was away reach it after it reconnects.
class MqttSubscriber {
 public:
  struct Message {
    std::string topic, payload;
  };
  MqttSubscriber(int port, const std::string& topic, const std::string& client_id);
  ~MqttSubscriber();
  // Waits up to `timeout` for at least `count` messages; returns what arrived (also when fewer).
  std::vector<Message> wait_for(size_t count, std::chrono::seconds timeout);
  std::vector<Message> messages();
  // Whether the subscription has been acknowledged (since the last connection).
  bool subscribed(std::chrono::seconds timeout);

 private:
  static void on_connect(mosquitto*, void* self, int rc);
  static void on_subscribe(mosquitto*, void* self, int mid, int count, const int* granted);
  static void on_message(mosquitto*, void* self, const mosquitto_message* message);
  mosquitto* client_ = nullptr;
  std::string topic_;
  std::mutex mutex_;
  std::vector<Message> messages_;
  bool subscribed_ = false;
};

}  // namespace bodyrec::testing

// BODYREC_REQUIRE_SERVERS=1 (set by .ci/run): a missing server program fails the test instead of
// skipping it.
namespace bodyrec::testing {
bool servers_required();
}

// In a gtest test body: `BODYREC_REQUIRE_POSTGRES(pg);` declares PostgresServer* pg, or skips the test
// naming what is missing (fails under BODYREC_REQUIRE_SERVERS=1). Likewise BODYREC_REQUIRE_MOSQUITTO.
// `BODYREC_OWN_MOSQUITTO(broker, options);` declares std::unique_ptr<MosquittoServer> broker, a broker of
// the test's own (it may stop and start it), or skips / fails likewise.
#define BODYREC_SKIP_WITHOUT_SERVER(var)                                                \
  if (!var) {                                                                           \
    if (::bodyrec::testing::servers_required()) FAIL() << var##_why;                    \
    GTEST_SKIP() << var##_why;                                                          \
  }
#define BODYREC_REQUIRE_SERVER(var, type)                                               \
  std::string var##_why;                                                                \
  type* var = type::shared(&var##_why);                                                 \
  BODYREC_SKIP_WITHOUT_SERVER(var)
#define BODYREC_OWN_MOSQUITTO(var, options)                                             \
  std::string var##_why;                                                                \
  auto var = ::bodyrec::testing::MosquittoServer::make(options, &var##_why);            \
  BODYREC_SKIP_WITHOUT_SERVER(var)
#define BODYREC_REQUIRE_POSTGRES(var) BODYREC_REQUIRE_SERVER(var, ::bodyrec::testing::PostgresServer)
#define BODYREC_REQUIRE_MOSQUITTO(var) BODYREC_REQUIRE_SERVER(var, ::bodyrec::testing::MosquittoServer)
