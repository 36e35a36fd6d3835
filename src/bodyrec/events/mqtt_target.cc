#include "bodyrec/events/mqtt_target.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"

namespace bodyrec {

namespace {

bool valid_prefix(const std::string& prefix) {
  if (prefix.empty()) return false;
  size_t level = 0;
  for (size_t i = 0; i <= prefix.size(); ++i) {
    if (i == prefix.size() || prefix[i] == '/') {
      if (level == 0) return false;  // an empty level
      level = 0;
      continue;
    }
    const char c = prefix[i];
    if (c == '+' || c == '#' || static_cast<unsigned char>(c) < 0x20) return false;
    ++level;
  }
  return true;
}

}  // namespace

MqttTarget parse_mqtt_uri(const std::string& uri) {
  const std::string usage = "--events: expected mqtt://HOST[:PORT]/PREFIX or mqtts://HOST[:PORT]/PREFIX";
  MqttTarget t;
  std::string rest;
  if (uri.rfind("mqtt://", 0) == 0) {
    rest = uri.substr(7);
  } else if (uri.rfind("mqtts://", 0) == 0) {
    rest = uri.substr(8);
    t.tls = true;
    t.port = 8883;
  } else {
    throw UsageError(usage + ", got '" + uri + "'");
  }
  const size_t slash = rest.find('/');
  const std::string authority = rest.substr(0, slash);
  if (authority.find('@') != std::string::npos)
    throw UsageError("--events: the URI holds user information; put the user name and password in a file given "
                     "with --events-credentials (mode 0600), never on the command line");
  if (slash == std::string::npos || !valid_prefix(rest.substr(slash + 1)))
    throw UsageError(usage + ": PREFIX is one or more topic levels without + or # (e.g. site/hall), got '" + uri + "'");
  t.prefix = rest.substr(slash + 1);
  std::string port;
  if (!authority.empty() && authority[0] == '[') {
    const size_t close = authority.find(']');
    if (close == std::string::npos) throw UsageError(usage + ", got '" + uri + "'");
    t.host = authority.substr(1, close - 1);
    if (close + 1 < authority.size()) {
      if (authority[close + 1] != ':') throw UsageError(usage + ", got '" + uri + "'");
      port = authority.substr(close + 2);
    }
  } else {
    const size_t colon = authority.find(':');
    t.host = authority.substr(0, colon);
    if (colon != std::string::npos) port = authority.substr(colon + 1);
  }
  if (t.host.empty()) throw UsageError(usage + ": no host in '" + uri + "'");
  if (!port.empty() || authority.find(':') != std::string::npos) {
    const auto p = parse_integer(port);
    if (!p || *p < 1 || *p > 65535) throw UsageError("--events: port must be 1..65535, got '" + port + "'");
    t.port = static_cast<int>(*p);
  }
  return t;
}

MqttCredentials read_mqtt_credentials(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError(path + ": cannot read credentials: " + std::strerror(errno));
  if (st.st_mode & 077)
    throw UsageError(path + ": credentials file is readable by others (mode " +
                     std::to_string((st.st_mode >> 6) & 7) + std::to_string((st.st_mode >> 3) & 7) +
                     std::to_string(st.st_mode & 7) + "); chmod 600 it");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read credentials");
  MqttCredentials c;
  bool user = false, password = false;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const size_t eq = line.find('=');
    const std::string key = line.substr(0, eq);
    if (eq != std::string::npos && key == "username") {
      c.username = line.substr(eq + 1);
      user = true;
    } else if (eq != std::string::npos && key == "password") {
      c.password = line.substr(eq + 1);
      password = true;
    } else {
      throw InputError(path + ": line " + std::to_string(n) + ": expected username=NAME or password=SECRET");
    }
  }
  if (!user || c.username.empty()) throw InputError(path + ": no username= line");
  if (!password) throw InputError(path + ": no password= line");
  return c;
}

bool valid_sensor_id(const std::string& id) {
  if (id.empty() || id.size() > 64) return false;
  for (char c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') return false;
  return true;
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

std::string default_sensor_id() {
  std::string id = host_name();
  if (id.empty()) return "default";
  if (id.size() > 64) id.resize(64);
  for (char& c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '-';
  return id;
}

}  // namespace bodyrec
