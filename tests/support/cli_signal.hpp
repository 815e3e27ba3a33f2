// Interrupting the needlekit tool from the example tests: start it in its own process group, wait until it is under
// way, send a signal to the whole group (as a terminal's Ctrl-C does) and collect how it ended.
#pragma once
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"

namespace needlekit::test {

// Runs `needlekit ARGUMENTS...` in `directory` (stdout.txt and stderr.txt there), waits until `under_way()` holds
// (at most 60 s: a test failure), sends `signal_number` to its process group and waits for it to end.
inline CliRun run_cli_and_signal(const std::filesystem::path& directory, const std::vector<std::string>& arguments,
                                 const std::function<bool()>& under_way, int signal_number) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    if (::chdir(directory.c_str()) != 0) std::_Exit(127);
    if (!std::freopen("stderr.txt", "w", stderr) || !std::freopen("stdout.txt", "w", stdout)) std::_Exit(127);
    std::vector<char*> argv{const_cast<char*>(NEEDLEKIT_CLI)};
    for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    ::execv(NEEDLEKIT_CLI, argv.data());
    std::_Exit(127);
  }
  EXPECT_GT(pid, 0);
  ::setpgid(pid, pid);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int status = 0;
  bool ended = false;
  while (!under_way() && std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      ended = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_FALSE(ended) << "the run ended before it could be interrupted";
  EXPECT_TRUE(under_way()) << "the run did not get under way within 60 s";
  if (!ended) {
    ::kill(-pid, signal_number);
    ::waitpid(pid, &status, 0);
  }
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, file_text(directory / "stdout.txt"),
          file_text(directory / "stderr.txt")};
}

}  // namespace needlekit::test
