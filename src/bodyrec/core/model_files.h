// Where bodyrec finds the trained models it ships (models/README.md lists them): a default path needs no
// flag. Searched in order:
//   1. $BODYREC_MODELS (a directory), when set;
//   2. <directory of the running program>/../share/bodyrec/models (an installed `bodyrec`);
//   3. the install prefix this library was built for: <prefix>/share/bodyrec/models;
//   4. the source tree's models/ (a program run from its build folder).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace bodyrec {

// The directories above that exist, in search order.
std::vector<std::string> model_directories();

// The first existing `<directory>/<name>`; none when no directory has it.
std::optional<std::string> find_model_file(const std::string& name);

// As find_model_file, but throws InputError naming `name`, the directories searched and `hint` (how to
// get or make the model) when none has it.
std::string require_model_file(const std::string& name, const std::string& hint);

}  // namespace bodyrec
