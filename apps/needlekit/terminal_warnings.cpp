#include "terminal_warnings.hpp"

#include <fmt/format.h>

namespace needlekit::cli {

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) fmt::print(stderr, "needlekit: warning: {}\n", warning);
  std::fflush(stderr);
}

}  // namespace needlekit::cli
