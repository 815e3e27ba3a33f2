#include "msh_read_isolated.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <mutex>
#include <stdexcept>
#include <type_traits>

#include "needlekit/core/errors.hpp"

namespace needlekit::mesh::detail {
namespace {

// The child's answer as one byte string: the error, then the contents. Both ends are this build of this program,
// so scalars travel in native layout; the parent checks every length against what is left.
class Writer {
public:
  template <class T>
  void scalar(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void text(const std::string& s) {
    scalar<std::uint64_t>(s.size());
    bytes_ += s;
  }
  template <class T>
  void array(const std::vector<T>& values) {
    scalar<std::uint64_t>(values.size());
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  const std::string& bytes() const { return bytes_; }

private:
  std::string bytes_;
};

class Reader {
public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  T scalar() {
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  std::string text() {
    const auto n = count(1);
    return std::string(take(n), n);
  }
  template <class T>
  std::vector<T> array() {
    const auto n = count(sizeof(T));
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
    return values;
  }

private:
  std::size_t count(std::size_t item_size) {
    const auto n = scalar<std::uint64_t>();
    if (n > (bytes_.size() - at_) / item_size) throw std::runtime_error("the .msh reader's child sent a short answer");
    return static_cast<std::size_t>(n);
  }
  const char* take(std::size_t n) {
    if (n > bytes_.size() - at_) throw std::runtime_error("the .msh reader's child sent a short answer");
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

std::string encode(const GmshError& error, const MshContents& contents) {
  Writer w;
  w.scalar(error.kind);
  w.text(error.message);
  w.scalar<std::uint64_t>(contents.layers.size());
  for (const TissueLayer& layer : contents.layers) {
    w.text(layer.name);
    w.scalar(layer.thickness);
    w.scalar(layer.youngs_modulus);
    w.scalar(layer.poisson_ratio);
  }
  w.scalar<std::uint64_t>(contents.layer_corners.size());
  for (const auto& corners : contents.layer_corners) w.array(corners);
  w.array(contents.node_tags);
  w.array(contents.coords);
  return w.bytes();
}

MshContents decode(const std::string& bytes, GmshError& error) {
  Reader r(bytes);
  MshContents contents;
  error.kind = r.scalar<GmshErrorKind>();
  error.message = r.text();
  for (auto n = r.scalar<std::uint64_t>(); n > 0; --n) {
    TissueLayer layer;
    layer.name = r.text();
    layer.thickness = r.scalar<double>();
    layer.youngs_modulus = r.scalar<double>();
    layer.poisson_ratio = r.scalar<double>();
    contents.layers.push_back(std::move(layer));
  }
  for (auto n = r.scalar<std::uint64_t>(); n > 0; --n) contents.layer_corners.push_back(r.array<std::size_t>());
  contents.node_tags = r.array<std::size_t>();
  contents.coords = r.array<double>();
  return contents;
}

bool write_all(int fd, const std::string& bytes) {
  for (std::size_t at = 0; at < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<std::size_t>(n);
  }
  return true;
}

std::string read_all(int fd) {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return bytes;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace

MshContents read_msh_isolated(const std::string& file, const std::vector<TissueLayer>& layers, GmshError& error) {
  const GmshModule& module = gmsh_module();
  // No other thread may be inside the module (holding Gmsh's lock) when the child is forked.
  const std::lock_guard<std::mutex> lock(gmsh_call_mutex());
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(fmt::format("{}: cannot read: no pipe ({})", file, std::strerror(errno)));
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(fmt::format("{}: cannot read: no child process ({})", file, std::strerror(errno)));
  }
  if (child == 0) {
    ::close(fds[0]);
    // A crash kills the child with its signal, whatever handlers the program has (a sanitizer's report included).
    for (int signal_number : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::signal(signal_number, SIG_DFL);
    GmshError child_error;
    const MshContents contents = module.read_msh(file, layers, child_error);
    // _exit: the child runs no exit handlers of the parent's program (files, Gmsh's globals, sanitizer reports).
    ::_exit(write_all(fds[1], encode(child_error, contents)) ? 0 : 1);
  }
  ::close(fds[1]);
  const std::string answer = read_all(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    throw InvalidInput(fmt::format("{}: Gmsh's .msh reader crashed on this file ({}): it is malformed; expected a "
                                   "Gmsh MSH 2.2 or 4.1 mesh whose element nodes are all listed in $Nodes",
                                   file, ::strsignal(WTERMSIG(status))));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw InvalidInput(fmt::format("{}: Gmsh's .msh reader failed on this file (exit status {}): it is malformed",
                                   file, WIFEXITED(status) ? WEXITSTATUS(status) : status));
  }
  return decode(answer, error);
}

}  // namespace needlekit::mesh::detail
