// Exceptions for bad input. Expected numerical outcomes (no convergence, a needle that buckles, an infeasible
// design) are never exceptions: they are a status and a reason inside a Result struct.
#pragma once
#include <stdexcept>
#include <string>

namespace needlekit {

// A parameter, key or value that the user supplied is invalid. The message names the key (and file:line when the
// value came from a file), the value, and what was expected.
class InvalidInput : public std::invalid_argument {
public:
  explicit InvalidInput(const std::string& message) : std::invalid_argument(message) {}
};

// A file cannot be read or written, or its contents cannot be parsed.
class IoError : public std::runtime_error {
public:
  explicit IoError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace needlekit
