#include "needlekit/core/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace needlekit {
namespace {

std::atomic<bool> g_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_interrupt_signal(int signal_number) {
  if (g_requested.exchange(true)) {  // asked twice: stop now
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
  }
}

}  // namespace

bool interrupt_requested() noexcept { return g_requested.load(std::memory_order_relaxed); }
void request_interrupt() noexcept { g_requested.store(true); }
void clear_interrupt() noexcept { g_requested.store(false); }

void throw_if_interrupted() {
  if (interrupt_requested()) throw Interrupted();
}

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt_signal;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

}  // namespace needlekit
