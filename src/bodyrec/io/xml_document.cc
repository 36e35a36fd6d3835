#include "bodyrec/io/xml_document.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"

namespace bodyrec {
namespace {

int line_of_offset(const std::string& text, std::ptrdiff_t offset) {
  int line = 1;
  for (std::ptrdiff_t i = 0; i < offset && i < static_cast<std::ptrdiff_t>(text.size()); ++i)
    if (text[i] == '\n') ++line;
  return line;
}

}  // namespace

pugi::xml_document load_xml_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read " + path);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_xml_text(buffer.str(), path);
}

pugi::xml_document parse_xml_text(const std::string& text, const std::string& path) {
  if (text.empty()) throw InputError(path + ": empty file, expected XML");
  pugi::xml_document doc;
  const pugi::xml_parse_result result = doc.load_buffer(text.data(), text.size());
  if (!result)
    throw InputError(path + ": line " + std::to_string(line_of_offset(text, result.offset)) +
                     ": malformed XML (" + result.description() + ")");
  return doc;
}

double required_number(const pugi::xml_node& node, const char* name, const std::string& where) {
  const pugi::xml_attribute attr = node.attribute(name);
  if (!attr) throw InputError(where + ": missing attribute '" + name + "'");
  const char* text = attr.value();
  const auto value = parse_double(text);
  if (!value || !std::isfinite(*value))
    throw InputError(where + ": attribute '" + name + "' is not a finite number: '" + text + "'");
  return *value;
}

int required_int(const pugi::xml_node& node, const char* name, const std::string& where) {
  const double value = required_number(node, name, where);
  if (value != std::floor(value) || std::fabs(value) > 1e9)
    throw InputError(where + ": attribute '" + name + "' is not an integer: '" +
                     node.attribute(name).value() + "'");
  return static_cast<int>(value);
}

}  // namespace bodyrec
