// The process exit codes of the needlekit tool, declared once (docs/cli.md "Exit codes"; the CLI's main() maps
// exceptions and command outcomes onto them, and the tests assert them).
#pragma once

namespace needlekit {

enum class ExitCode : int {
  Success = 0,           // the command did what it was asked
  InternalError = 1,     // a defect in needlekit: an unexpected exception
  InvalidInput = 2,      // bad input (file, key, value, command line); nothing was written
  NumericalFailure = 3,  // a numerical failure (no convergence): the result says why, every completed step kept
  Interrupted = 130,     // SIGINT / SIGTERM: stopped cleanly, no half-written file left
};

}  // namespace needlekit
