#pragma once
// The one error type for bad input: what() is "file:line: message"; line 0 means the file
// as a whole (e.g. it does not exist). Readers, validation and model building (a linkage that
// cannot be assembled) all report through it, so the CLI can name the place and exit 2.
#include <stdexcept>
#include <string>

namespace linkbox::input {

struct InputError : std::invalid_argument {
  std::string file;
  int line;
  std::string message;
  InputError(std::string file, int line, const std::string& message)
      : std::invalid_argument(file + ":" + std::to_string(line) + ": " + message),
        file(std::move(file)),
        line(line),
        message(message) {}
};

}  // namespace linkbox::input
