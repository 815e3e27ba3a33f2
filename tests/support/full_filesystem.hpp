// A really full file system for tests of what a writer leaves behind: a tmpfs of a few kilobytes mounted in a private
// mount namespace, so that nothing outside the test sees it and it disappears with the process. As root the mount
// namespace is enough; otherwise a user namespace maps the test's user to root inside it (unprivileged user
// namespaces, enabled on Debian). Either way the kernel's tmpfs returns ENOSPC exactly as a full disk does.
#pragma once
#include <sched.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

namespace needlekit::test {

// The shell prefix that runs a command with a `bytes`-sized tmpfs (read-only when `read_only`) mounted at
// `mount_point` (which must exist): `unshare ... sh -c 'mount ... && COMMAND'`. The command's exit code is the
// shell's.
inline std::string with_small_tmpfs(const std::filesystem::path& mount_point, const std::string& size,
                                    const std::string& command, bool read_only = false) {
  const std::string user = ::geteuid() == 0 ? "" : " --map-root-user";
  return "unshare --mount --propagation private" + user + " sh -c \"mount -t tmpfs -o size=" + size +
         (read_only ? ",ro" : "") + " needlekit-test '" + mount_point.string() + "' && " + command + "\"";
}

// Mounts a `bytes`-sized tmpfs at `mount_point` in a new private mount namespace of the calling process (call it in a
// child process: a death test). Returns "" on success, else what failed.
inline std::string mount_small_tmpfs(const std::filesystem::path& mount_point, std::size_t bytes) {
  const bool root = ::geteuid() == 0;
  if (::unshare(root ? CLONE_NEWNS : (CLONE_NEWUSER | CLONE_NEWNS)) != 0)
    return std::string("unshare: ") + std::strerror(errno);
  if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0)
    return std::string("mount --make-rprivate /: ") + std::strerror(errno);
  const std::string options = "size=" + std::to_string(bytes);
  if (::mount("needlekit-test", mount_point.c_str(), "tmpfs", 0, options.c_str()) != 0)
    return std::string("mount tmpfs: ") + std::strerror(errno);
  return "";
}

}  // namespace needlekit::test
