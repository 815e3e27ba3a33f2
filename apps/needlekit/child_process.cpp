#include "child_process.hpp"

#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"

extern char** environ;

namespace needlekit::cli {

int run_program(const std::vector<std::string>& argv_text) {
  std::vector<std::string> copy = argv_text;
  std::vector<char*> argv;
  for (std::string& text : copy) argv.push_back(text.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  ::posix_spawn_file_actions_init(&actions);
  ::posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  pid_t pid = 0;
  const int started = ::posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  ::posix_spawn_file_actions_destroy(&actions);
  if (started != 0) throw IoError(fmt::format("cannot run '{}': {}", argv_text.front(), std::strerror(started)));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw IoError(fmt::format("waiting for '{}' failed: {}", argv_text.front(), std::strerror(errno)));
  }
  if (WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM)) request_interrupt();
  throw_if_interrupted();
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace needlekit::cli
