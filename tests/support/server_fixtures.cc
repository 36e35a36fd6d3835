#include "server_fixtures.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <grp.h>
#include <libpq-fe.h>
#include <mosquitto.h>
#include <netinet/in.h>
#include <pwd.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace fs = std::filesystem;

namespace bodyrec::testing {

namespace {

struct Ids {
  bool drop = false;
  uid_t uid = 0;
  gid_t gid = 0;
};

// The service user to run as: only when this process is root.
Ids ids_for(const std::string& user) {
  Ids ids;
  if (user.empty() || ::geteuid() != 0) return ids;
  const passwd* pw = ::getpwnam(user.c_str());
  if (!pw) throw std::runtime_error("no system user '" + user + "' to run the server as (is its package installed?)");
  ids.drop = true;
  ids.uid = pw->pw_uid;
  ids.gid = pw->pw_gid;
  return ids;
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string tail(const std::string& path, size_t bytes = 2000) {
  const std::string s = read_all(path);
  return s.size() > bytes ? s.substr(s.size() - bytes) : s;
}

void sleep_ms(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

pid_t spawn(const std::vector<std::string>& argv, const std::string& user, const std::string& log, int death_signal) {
  const Ids ids = ids_for(user);
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(log + ": " + std::strerror(errno));
  if (ids.drop && ::fchown(fd, ids.uid, ids.gid) != 0) {
    ::close(fd);
    throw std::runtime_error(log + ": chown: " + std::strerror(errno));
  }
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fd);
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    // Only async-signal-safe calls from here to exec.
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    const int null = ::open("/dev/null", O_RDONLY);
    if (null >= 0) ::dup2(null, 0);
    ::close_range(3, ~0U, 0);
    if (ids.drop && (::setgroups(0, nullptr) != 0 || ::setgid(ids.gid) != 0 || ::setuid(ids.uid) != 0)) ::_exit(126);
    // After the credentials change (which clears it): the server dies with this process.
    if (death_signal) ::prctl(PR_SET_PDEATHSIG, death_signal);
    if (::getppid() != parent) ::_exit(125);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(fd);
  return pid;
}

int free_port() {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t n = sizeof a;
  if (::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &n) != 0) {
    ::close(s);
    throw std::runtime_error(std::string("no free port: ") + std::strerror(errno));
  }
  ::close(s);
  return ntohs(a.sin_port);
}

bool can_connect(int port) {
  const int s = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  const bool ok = ::connect(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  ::close(s);
  return ok;
}

// The newest /usr/lib/postgresql/<version>/bin holding `postgres`, or $BODYREC_PG_BIN.
std::string postgres_bin() {
  if (const char* env = std::getenv("BODYREC_PG_BIN"); env && *env) return env;
  std::string best;
  int best_version = -1;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/usr/lib/postgresql", ec)) {
    const std::string name = entry.path().filename().string();
    const int version = std::atoi(name.c_str());
    if (fs::exists(entry.path() / "bin" / "postgres") && version > best_version) {
      best_version = version;
      best = (entry.path() / "bin").string();
    }
  }
  return best;
}

}  // namespace

ServerProcess::~ServerProcess() { stop(SIGKILL, std::chrono::seconds(5)); }

void ServerProcess::start(const std::vector<std::string>& argv, const std::string& user, const std::string& log,
                          int death_signal) {
  if (pid_ > 0) throw std::runtime_error("server already running");
  pid_ = spawn(argv, user, log, death_signal);
}

bool ServerProcess::running() {
  if (pid_ <= 0) return false;
  int status = 0;
  if (::waitpid(pid_, &status, WNOHANG) == pid_) {
    pid_ = -1;
    return false;
  }
  return true;
}

void ServerProcess::stop(int signal, std::chrono::seconds wait) {
  if (pid_ <= 0) return;
  ::kill(pid_, signal);
  const auto deadline = std::chrono::steady_clock::now() + wait;
  int status = 0;
  while (::waitpid(pid_, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &status, 0);
      break;
    }
    sleep_ms(20);
  }
  pid_ = -1;
}

int run_program(const std::vector<std::string>& argv, const std::string& user, const std::string& log) {
  const pid_t pid = spawn(argv, user, log, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string make_server_folder(const std::string& prefix, const std::string& user) {
  std::string pattern = (fs::temp_directory_path() / (prefix + "XXXXXX")).string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp: " + std::string(std::strerror(errno)));
  const Ids ids = ids_for(user);
  if (ids.drop && ::chown(pattern.c_str(), ids.uid, ids.gid) != 0)
    throw std::runtime_error(pattern + ": chown: " + std::strerror(errno));
  ::chmod(pattern.c_str(), 0700);
  return pattern;
}

void remove_folder(const std::string& path) {
  std::error_code ec;
  if (!path.empty()) fs::remove_all(path, ec);
}

// ---- PostgreSQL ----

PostgresServer* PostgresServer::shared(std::string* why) {
  static std::once_flag once;
  static std::unique_ptr<PostgresServer> server;
  static std::string reason;
  std::call_once(once, [] { server = make(false, &reason); });
  if (!server && why) *why = reason;
  return server.get();
}

std::unique_ptr<PostgresServer> PostgresServer::make(bool durable, std::string* why) {
  const std::string bin = postgres_bin();
  if (bin.empty()) {
    if (why)
      *why = "PostgreSQL server programs not found under /usr/lib/postgresql/<version>/bin (scripts/install-deps "
             "installs the postgresql package; or set BODYREC_PG_BIN)";
    return nullptr;
  }
  return std::unique_ptr<PostgresServer>(new PostgresServer(bin, durable));
}

PostgresServer::PostgresServer(const std::string& bin, bool durable) : bin_(bin), durable_(durable) {
  user_ = ::geteuid() == 0 ? "postgres" : "";
  folder_ = make_server_folder("bodyrec-pg-", user_);
  const std::string log = folder_ + "/initdb.log";
  const int rc = run_program({bin_ + "/initdb", "-D", folder_ + "/data", "-U", "postgres", "-A", "trust", "-E", "UTF8",
                              "--locale=C", "--no-sync", "--no-instructions"},
                             user_, log);
  if (rc != 0) {
    const std::string message = "initdb failed (" + std::to_string(rc) + "): " + tail(log);
    remove_folder(folder_);
    throw std::runtime_error(message);
  }
  start();
}

PostgresServer::~PostgresServer() {
  stop();
  remove_folder(folder_);
}

void PostgresServer::start() {
  const std::string log = folder_ + "/server.log";
  std::vector<std::string> argv = {bin_ + "/postgres", "-D", folder_ + "/data", "-k", folder_, "-c", "listen_addresses=",
                                   "-c", "max_connections=40"};
  if (!durable_) argv.insert(argv.end(), {"-c", "fsync=off", "-c", "full_page_writes=off"});
  server_.start(argv, user_, log, SIGQUIT);
  const std::string ping = "host=" + folder_ + " dbname=postgres user=postgres connect_timeout=2";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (PQping(ping.c_str()) != PQPING_OK) {
    if (!server_.running()) throw std::runtime_error("postgres exited: " + tail(log));
    if (std::chrono::steady_clock::now() > deadline) throw std::runtime_error("postgres did not start: " + tail(log));
    sleep_ms(50);
  }
}

void PostgresServer::stop() { server_.stop(SIGINT); }

std::string PostgresServer::uri(const std::string& db, const std::string& user) const {
  return "postgresql:///" + db + "?host=" + folder_ + "&user=" + user;
}

std::string PostgresServer::query(const std::string& db, const std::string& sql) const {
  PGconn* c = PQconnectdb(("host=" + folder_ + " dbname=" + db + " user=postgres").c_str());
  if (PQstatus(c) != CONNECTION_OK) {
    const std::string message = PQerrorMessage(c);
    PQfinish(c);
    throw std::runtime_error("connect " + db + ": " + message);
  }
  PQsetNoticeProcessor(c, [](void*, const char*) {}, nullptr);
  PGresult* r = PQexec(c, sql.c_str());
  const ExecStatusType status = PQresultStatus(r);
  const std::string message = PQresultErrorMessage(r);
  std::string value;
  if (status == PGRES_TUPLES_OK && PQntuples(r) > 0 && PQnfields(r) > 0) value = PQgetvalue(r, 0, 0);
  PQclear(r);
  PQfinish(c);
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) throw std::runtime_error(sql + ": " + message);
  return value;
}

void PostgresServer::exec(const std::string& db, const std::string& sql) const { query(db, sql); }

std::string PostgresServer::create_database(const std::string& prefix) {
  const std::string name = prefix + "_" + std::to_string(::getpid()) + "_" + std::to_string(++databases_);
  exec("postgres", "CREATE DATABASE " + name);
  return uri(name);
}

std::string PostgresServer::dump(const std::string& db) const {
  const std::string out = folder_ + "/dump-" + db + ".sql", log = folder_ + "/pg_dump.log";
  const int rc = run_program({bin_ + "/pg_dump", "-h", folder_, "-U", "postgres", "-f", out, db}, "", log);
  if (rc != 0) throw std::runtime_error("pg_dump failed: " + tail(log));
  std::string text = read_all(out);
  fs::remove(out);
  return text;
}

std::string PostgresServer::table_files_bytes(const std::string& db) const {
  const std::string oid = query("postgres", "SELECT oid FROM pg_database WHERE datname = '" + db + "'");
  if (oid.empty()) throw std::runtime_error("no database " + db);
  std::string all;
  for (const auto& entry : fs::directory_iterator(fs::path(folder_) / "data" / "base" / oid))
    if (entry.is_regular_file()) all += read_all(entry.path().string());
  return all;
}

// ---- Mosquitto ----

MosquittoServer* MosquittoServer::shared(std::string* why) {
  static std::once_flag once;
  static std::unique_ptr<MosquittoServer> server;
  static std::string reason;
  std::call_once(once, [] { server = make({}, &reason); });
  if (!server && why) *why = reason;
  return server.get();
}

std::unique_ptr<MosquittoServer> MosquittoServer::make(const Options& options, std::string* why) {
  if (!fs::exists("/usr/sbin/mosquitto")) {
    if (why) *why = "/usr/sbin/mosquitto not found (scripts/install-deps installs the mosquitto package)";
    return nullptr;
  }
  return std::unique_ptr<MosquittoServer>(new MosquittoServer(options));
}

MosquittoServer::MosquittoServer(const Options& options) : options_(options) {
  user_ = ::geteuid() == 0 ? "mosquitto" : "";
  folder_ = make_server_folder("bodyrec-mqtt-", user_);
  port_ = free_port();
  // A private copy of a file the broker reads after it dropped root.
  const auto own_copy = [&](const std::string& from, const std::string& name) {
    const std::string copy = folder_ + "/" + name;
    fs::copy_file(from, copy);
    const Ids ids = ids_for(user_);
    if (ids.drop && ::chown(copy.c_str(), ids.uid, ids.gid) != 0) throw std::runtime_error("chown " + copy);
    ::chmod(copy.c_str(), 0600);
    return copy;
  };
  std::string config = "listener " + std::to_string(port_) + " 127.0.0.1\n";
  if (!options_.tls_cafile.empty())
    config += "cafile " + own_copy(options_.tls_cafile, "ca.pem") + "\ncertfile " +
              own_copy(options_.tls_certfile, "server.pem") + "\nkeyfile " + own_copy(options_.tls_keyfile, "server.key") +
              "\n";
  if (options_.password_file.empty()) {
    config += "allow_anonymous true\n";
  } else {
    config += "allow_anonymous false\npassword_file " + own_copy(options_.password_file, "passwords") + "\n";
  }
  config += "persistence true\npersistence_location " + folder_ + "/\nautosave_interval 0\n";
  config += "log_dest stderr\nlog_type error\nlog_type warning\nlog_type notice\nlog_type information\n";
  std::ofstream(folder_ + "/mosquitto.conf") << config;
  ::chmod((folder_ + "/mosquitto.conf").c_str(), 0644);
  start();
}

MosquittoServer::~MosquittoServer() {
  stop();
  remove_folder(folder_);
}

std::string MosquittoServer::uri(const std::string& prefix) const {
  return "mqtt://127.0.0.1:" + std::to_string(port_) + "/" + prefix;
}

void MosquittoServer::start() {
  const std::string log = folder_ + "/mosquitto.log";
  server_.start({"/usr/sbin/mosquitto", "-c", folder_ + "/mosquitto.conf"}, user_, log, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!can_connect(port_)) {
    if (!server_.running()) throw std::runtime_error("mosquitto exited: " + tail(log));
    if (std::chrono::steady_clock::now() > deadline) throw std::runtime_error("mosquitto did not start: " + tail(log));
    sleep_ms(20);
  }
}

void MosquittoServer::stop() { server_.stop(SIGTERM); }

// ---- subscriber ----

MqttSubscriber::MqttSubscriber(int port, const std::string& topic, const std::string& client_id) : topic_(topic) {
  static std::once_flag once;
  std::call_once(once, [] { mosquitto_lib_init(); });
  client_ = mosquitto_new(client_id.c_str(), false, this);
  if (!client_) throw std::runtime_error("mosquitto_new failed");
  mosquitto_connect_callback_set(client_, on_connect);
  mosquitto_subscribe_callback_set(client_, on_subscribe);
  mosquitto_message_callback_set(client_, on_message);
  mosquitto_reconnect_delay_set(client_, 1, 1, false);
  if (mosquitto_connect(client_, "127.0.0.1", port, 10) != MOSQ_ERR_SUCCESS)
    throw std::runtime_error("subscriber cannot connect to 127.0.0.1:" + std::to_string(port));
  mosquitto_loop_start(client_);
}

MqttSubscriber::~MqttSubscriber() {
  mosquitto_disconnect(client_);
  mosquitto_loop_stop(client_, true);
  mosquitto_destroy(client_);
}

void MqttSubscriber::on_connect(mosquitto* client, void* self, int rc) {
  auto* s = static_cast<MqttSubscriber*>(self);
  if (rc != 0) return;
  {
    std::lock_guard<std::mutex> lock(s->mutex_);
    s->subscribed_ = false;
  }
  mosquitto_subscribe(client, nullptr, s->topic_.c_str(), 1);
}

void MqttSubscriber::on_subscribe(mosquitto*, void* self, int, int, const int*) {
  auto* s = static_cast<MqttSubscriber*>(self);
  std::lock_guard<std::mutex> lock(s->mutex_);
  s->subscribed_ = true;
}

void MqttSubscriber::on_message(mosquitto*, void* self, const mosquitto_message* m) {
  auto* s = static_cast<MqttSubscriber*>(self);
  std::lock_guard<std::mutex> lock(s->mutex_);
  s->messages_.push_back({m->topic, std::string(static_cast<const char*>(m->payload), static_cast<size_t>(m->payloadlen))});
}

bool MqttSubscriber::subscribed(std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (subscribed_) return true;
    }
    sleep_ms(20);
  }
  return false;
}

std::vector<MqttSubscriber::Message> MqttSubscriber::messages() {
  std::lock_guard<std::mutex> lock(mutex_);
  return messages_;
}

std::vector<MqttSubscriber::Message> MqttSubscriber::wait_for(size_t count, std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    auto m = messages();
    if (m.size() >= count || std::chrono::steady_clock::now() > deadline) return m;
    sleep_ms(20);
  }
}

}  // namespace bodyrec::testing

namespace bodyrec::testing {

bool servers_required() {
  const char* v = std::getenv("BODYREC_REQUIRE_SERVERS");
  return v && std::string(v) == "1";
}

}  // namespace bodyrec::testing
