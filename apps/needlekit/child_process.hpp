// Running a helper program (the Python plot and report scripts) and waiting for it, with needlekit's interrupt
// handling: its standard output goes to needlekit's standard error (stdout stays the command's result).
#pragma once
#include <string>
#include <vector>

namespace needlekit::cli {

// Runs argv[0] (looked up in PATH) with argv and returns its exit code. Throws needlekit::Interrupted when the
// program was ended by SIGINT/SIGTERM (Ctrl-C reaches the whole process group) or an interrupt was requested
// meanwhile; IoError naming the program when it cannot be started.
int run_program(const std::vector<std::string>& argv);

}  // namespace needlekit::cli
