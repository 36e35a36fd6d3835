// Where events go over MQTT (issue 47): the --events URI, the credentials file and TLS settings.
#pragma once

#include <optional>
#include <string>

namespace bodyrec {

struct MqttTarget {
  bool tls = false;    // mqtts://
  std::string host;    // name or address; [v6] brackets removed
  int port = 1883;     // default 1883, 8883 with TLS
  std::string prefix;  // topic prefix: events go to PREFIX/<sensor-id>/<kind of run>
};

// Parses mqtt://HOST[:PORT]/PREFIX or mqtts://HOST[:PORT]/PREFIX. PREFIX is one or more topic levels
// without wildcards (+, #) or empty levels. UsageError naming --events for anything else, and for a URI
// with user info (user:password@): credentials go in a file (--events-credentials), never on the
// command line; the message does not repeat the URI.
MqttTarget parse_mqtt_uri(const std::string& uri);

struct MqttCredentials {
  std::string username, password;
};

// Reads a credentials file: lines `username=NAME` and `password=SECRET` (both required; blank lines and
// lines starting with # ignored; the value is the rest of the line). UsageError when group or others
// have any permission on the file (chmod 600 it: it holds a password); InputError naming the file when it
// cannot be read or a line is malformed.
MqttCredentials read_mqtt_credentials(const std::string& path);

// A topic level for a sensor name: letters, digits, '.', '_' and '-', 1 to 64 characters.
bool valid_sensor_id(const std::string& id);
// This machine's host name as gethostname() gives it; "" when it has none.
std::string host_name();
// The default sensor id: this machine's host name with other characters as '-', "default" when it has
// none.
std::string default_sensor_id();

}  // namespace bodyrec
