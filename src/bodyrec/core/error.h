// Typed errors. Every failure bodyrec reports is one of these; the CLI turns it into one line on stderr
// and the exit code below. Messages name the file and, where known, the frame, line or field at fault.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace bodyrec {

// Exit codes of the `bodyrec` program (documented in the README).
enum class ExitCode : int {
  kOk = 0,
  kUsage = 2,       // bad command line or option value
  kInput = 3,       // missing, unreadable, corrupt or wrongly formatted input
  kProcessing = 4,  // failure while processing valid input (including writing outputs)
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

// A bad option value or combination of options.
class UsageError : public Error {
 public:
  explicit UsageError(const std::string& message) : Error(ExitCode::kUsage, message) {}
};

// A bad value in one field of an options struct, e.g. OptionError("HogOptions", "hit_threshold", "must be finite").
// The message is "HogOptions.hit_threshold must be finite"; a front end may name its own option for the field
// instead (the bodyrec program says "--hit-threshold must be finite").
class OptionError : public UsageError {
 public:
  OptionError(std::string options, std::string field, std::string problem)
      : UsageError(options + "." + field + " " + problem),
        options_(std::move(options)), field_(std::move(field)), problem_(std::move(problem)) {}
  const std::string& options() const { return options_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string options_, field_, problem_;
};

// Input that cannot be used: missing, unreadable, truncated, or not in the expected format.
class InputError : public Error {
 public:
  explicit InputError(const std::string& message) : Error(ExitCode::kInput, message) {}
};

// Valid input that could not be processed, or an output that could not be written.
class ProcessingError : public Error {
 public:
  explicit ProcessingError(const std::string& message) : Error(ExitCode::kProcessing, message) {}
};

}  // namespace bodyrec
