// Quoting for the /bin/sh command lines through which the CLI runs its Python plot scripts.
#pragma once
#include <string>

namespace needlekit::cli {

// `text` as one single-quoted shell word (a ' inside becomes '\'').
inline std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace needlekit::cli
