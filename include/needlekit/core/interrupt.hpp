// Stopping a run on request (Ctrl-C, SIGTERM), declared once. The request is a process-wide flag: the CLI's signal
// handlers set it, and long loops check it between units of work — in the library through their progress callbacks,
// in the CLI through throw_if_interrupted() — so that a run stops at a point where every file it wrote is complete.
// The tool then exits with ExitCode::Interrupted (130).
#pragma once
#include <stdexcept>

namespace needlekit {

// Thrown (by the caller's code, typically a progress callback) when a run stops because it was asked to.
class Interrupted : public std::runtime_error {
public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// True once an interrupt was requested (async-signal-safe to set, cheap to test: one atomic load).
bool interrupt_requested() noexcept;
// Requests an interrupt: what the signal handler does; a caller (a test, the Python module) may do it too.
void request_interrupt() noexcept;
// Forgets a request (for a caller that goes on after an interrupted run).
void clear_interrupt() noexcept;
// Throws Interrupted when an interrupt was requested.
void throw_if_interrupted();

// Installs SIGINT and SIGTERM handlers that request an interrupt (system calls are restarted, not failed with
// EINTR). A second signal while the first is pending ends the process at once with the signal's default action.
void install_interrupt_handlers();

}  // namespace needlekit
