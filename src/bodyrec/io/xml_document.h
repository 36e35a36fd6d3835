// Loading XML files with errors that say where: the file and line of a syntax error, the element and
// attribute of a missing or malformed value.
#pragma once

#include <string>

#include <pugixml.hpp>

namespace bodyrec {

// Parses an XML file. Throws InputError naming the file (and the line of a syntax error) when it is
// missing, unreadable, empty or not well-formed XML.
pugi::xml_document load_xml_file(const std::string& path);

// Parses XML text read from `name` (a file name for messages); the same errors as load_xml_file.
pugi::xml_document parse_xml_text(const std::string& text, const std::string& name);

// Required numeric attribute. Throws InputError "<file>: <where>: missing attribute 'name'" or
// "... attribute 'name' is not a number: '...'".
double required_number(const pugi::xml_node& node, const char* name, const std::string& where);

// Required integer attribute, same errors as required_number plus "is not an integer".
int required_int(const pugi::xml_node& node, const char* name, const std::string& where);

}  // namespace bodyrec
