// The process exit codes of the needlekit tool, declared once (docs/cli.md "Exit codes"; the CLI's main() maps
// exceptions and command outcomes onto them, and the tests assert them).
#pragma once
#include "needlekit/core/enum_table.hpp"

namespace needlekit {

enum class ExitCode : int {
  Success = 0,           // the command did what it was asked
  InternalError = 1,     // a defect in needlekit: an unexpected exception
  InvalidInput = 2,      // bad input (file, key, value, command line); nothing was written
  NumericalFailure = 3,  // a numerical failure (no convergence): the result says why, every completed step kept
  Interrupted = 130,     // SIGINT / SIGTERM: stopped cleanly, no half-written file left
};
inline constexpr EnumTable<ExitCode, 5> kExitCodeNames{{
    {ExitCode::Success, "success", "0: the command did what it was asked"},
    {ExitCode::InternalError, "internal-error", "1: a defect in needlekit (an unexpected exception)"},
    {ExitCode::InvalidInput, "invalid-input", "2: bad input (file, key, value, command line); nothing was written"},
    {ExitCode::NumericalFailure, "numerical-failure", "3: a numerical failure; the result says why"},
    {ExitCode::Interrupted, "interrupted", "130: SIGINT / SIGTERM; stopped cleanly, no half-written file left"},
}};

}  // namespace needlekit
