// `needlekit describe`: the parameter tables' keys with their meaning, unit, default and range.
#pragma once
#include <CLI/CLI.hpp>

namespace needlekit::cli {

void add_describe_command(CLI::App& app);  // command_describe.cpp

}  // namespace needlekit::cli
