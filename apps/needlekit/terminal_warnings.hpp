// Warnings of a run (implausible scales, a mesh without attribution) on the terminal: one "needlekit: warning: ..."
// line each on stderr, so that stdout stays the command's result. The same texts go into the result's "notes".
#pragma once
#include <string>
#include <vector>

namespace needlekit::cli {

void print_warnings(const std::vector<std::string>& warnings);

}  // namespace needlekit::cli
