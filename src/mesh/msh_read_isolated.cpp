#include "msh_read_isolated.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <mutex>
#include <optional>
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

void encode_layers(Writer& w, const std::vector<TissueLayer>& layers) {
  w.scalar<std::uint64_t>(layers.size());
  for (const TissueLayer& layer : layers) {
    w.text(layer.name);
    w.scalar(layer.thickness);
    w.scalar(layer.youngs_modulus);
    w.scalar(layer.poisson_ratio);
  }
}

std::vector<TissueLayer> decode_layers(Reader& r) {
  std::vector<TissueLayer> layers;
  for (auto n = r.scalar<std::uint64_t>(); n > 0; --n) {
    TissueLayer layer;
    layer.name = r.text();
    layer.thickness = r.scalar<double>();
    layer.youngs_modulus = r.scalar<double>();
    layer.poisson_ratio = r.scalar<double>();
    layers.push_back(std::move(layer));
  }
  return layers;
}

std::string encode(const GmshError& error, const MshContents& contents) {
  Writer w;
  w.scalar(error.kind);
  w.text(error.message);
  encode_layers(w, contents.layers);
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
  contents.layers = decode_layers(r);
  for (auto n = r.scalar<std::uint64_t>(); n > 0; --n) contents.layer_corners.push_back(r.array<std::size_t>());
  contents.node_tags = r.array<std::size_t>();
  contents.coords = r.array<double>();
  return contents;
}

std::string encode_request(const std::string& file, const std::vector<TissueLayer>& layers, double cpu_limit) {
  Writer w;
  w.text(file);
  encode_layers(w, layers);
  w.scalar(cpu_limit);
  return w.bytes();
}

// The profiling timer (user and system CPU time of the process) set to `seconds`; 0 stops it. Its SIGPROF, left to
// its default action, ends the child.
void set_cpu_timer(double seconds) {
  itimerval timer{};
  const auto whole = static_cast<long>(seconds);
  timer.it_value.tv_sec = whole;
  timer.it_value.tv_usec = static_cast<long>((seconds - static_cast<double>(whole)) * 1e6);
  if (seconds > 0 && timer.it_value.tv_sec == 0 && timer.it_value.tv_usec == 0) timer.it_value.tv_usec = 1;
  ::setitimer(ITIMER_PROF, &timer, nullptr);
}

// Sends every byte; false when the other end is gone (MSG_NOSIGNAL: a dead child is not a SIGPIPE for the parent).
bool send_all(int fd, const char* bytes, std::size_t size) {
  for (std::size_t at = 0; at < size;) {
    const ssize_t n = ::send(fd, bytes + at, size - at, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<std::size_t>(n);
  }
  return true;
}

bool receive_exactly(int fd, char* bytes, std::size_t size) {
  for (std::size_t at = 0; at < size;) {
    const ssize_t n = ::recv(fd, bytes + at, size - at, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<std::size_t>(n);
  }
  return true;
}

// A message is its length (8 bytes) and its bytes.
bool send_message(int fd, const std::string& bytes) {
  const std::uint64_t size = bytes.size();
  return send_all(fd, reinterpret_cast<const char*>(&size), sizeof size) && send_all(fd, bytes.data(), bytes.size());
}

std::optional<std::string> receive_message(int fd) {
  std::uint64_t size = 0;
  if (!receive_exactly(fd, reinterpret_cast<char*>(&size), sizeof size)) return std::nullopt;
  std::string bytes(size, '\0');
  if (!receive_exactly(fd, bytes.data(), bytes.size())) return std::nullopt;
  return bytes;
}

// The child's loop: one read per request until the parent closes its end.
[[noreturn]] void serve_reads(int fd, const GmshModule& module) {
  // A crash kills the child with its signal, whatever handlers the program has (a sanitizer's report included).
  for (int signal_number : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGPROF}) ::signal(signal_number, SIG_DFL);
  while (const std::optional<std::string> request = receive_message(fd)) {
    Reader r(*request);
    const std::string file = r.text();
    const std::vector<TissueLayer> layers = decode_layers(r);
    const auto cpu_limit = r.scalar<double>();
    GmshError error;
    if (cpu_limit > 0) set_cpu_timer(cpu_limit);
    const MshContents contents = module.read_msh(file, layers, error);
    if (cpu_limit > 0) set_cpu_timer(0);
    if (!send_message(fd, encode(error, contents))) break;
  }
  // _exit: the child runs no exit handlers of the parent's program (files, Gmsh's globals, sanitizer reports).
  ::_exit(0);
}

// The child process that runs Gmsh's reader, started on the first read and kept until stop().
class ReaderProcess {
public:
  ReaderProcess() = default;
  ReaderProcess(const ReaderProcess&) = delete;
  ReaderProcess& operator=(const ReaderProcess&) = delete;
  ~ReaderProcess() { stop(); }

  // The child's answer to one request; empty when the child died, with its wait status in `status` (the child is
  // then gone and the next read starts another).
  std::optional<std::string> read(const std::string& file, const std::string& request, int& status) {
    if (child_ < 0) start(file);
    std::optional<std::string> answer;
    if (send_message(socket_, request)) answer = receive_message(socket_);
    if (!answer) status = stop();
    return answer;
  }

  // Closes the child's socket (it leaves its loop) and waits for it; its wait status, 0 if none ran.
  int stop() {
    if (child_ < 0) return 0;
    ::close(socket_);
    int status = 0;
    while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
    }
    child_ = -1;
    socket_ = -1;
    return status;
  }

private:
  void start(const std::string& file) {
    const GmshModule& module = gmsh_module();
    int fds[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) {
      throw std::runtime_error(fmt::format("{}: cannot read: no socket ({})", file, std::strerror(errno)));
    }
    const pid_t child = ::fork();
    if (child < 0) {
      ::close(fds[0]);
      ::close(fds[1]);
      throw std::runtime_error(fmt::format("{}: cannot read: no child process ({})", file, std::strerror(errno)));
    }
    if (child == 0) {
      ::close(fds[0]);
      serve_reads(fds[1], module);
    }
    ::close(fds[1]);
    child_ = child;
    socket_ = fds[0];
  }

  pid_t child_ = -1;
  int socket_ = -1;
};

}  // namespace

MshContents read_msh_isolated(const std::string& file, const std::vector<TissueLayer>& layers, GmshError& error,
                              const ReaderProcessOptions& options) {
  // No other thread may be inside the module (holding Gmsh's lock) when the child is forked, and one read at a time
  // goes to the child.
  const std::lock_guard<std::mutex> lock(gmsh_call_mutex());
  static ReaderProcess process;
  int status = 0;
  const std::optional<std::string> answer =
      process.read(file, encode_request(file, layers, options.cpu_limit), status);
  if (!answer && WIFSIGNALED(status) && WTERMSIG(status) == SIGPROF) {
    throw InvalidInput(fmt::format("{}: Gmsh's .msh reader used up its {} s of CPU time on this file: it is malformed "
                                   "(a count read from garbage) or larger than the reader's CPU time limit allows",
                                   file, options.cpu_limit));
  }
  if (!answer && WIFSIGNALED(status)) {
    throw InvalidInput(fmt::format("{}: Gmsh's .msh reader crashed on this file ({}): it is malformed; expected a "
                                   "Gmsh MSH 2.2 or 4.1 mesh whose element nodes are all listed in $Nodes",
                                   file, ::strsignal(WTERMSIG(status))));
  }
  if (!answer) {
    throw InvalidInput(fmt::format("{}: Gmsh's .msh reader failed on this file (exit status {}): it is malformed",
                                   file, WIFEXITED(status) ? WEXITSTATUS(status) : status));
  }
  // Gmsh is initialised and finalised for each file (GmshSession), a refusal included, so a kept child starts each
  // file from Gmsh's initial state; only a crash needs a new child.
  if (!options.keep_process) process.stop();
  return decode(*answer, error);
}

}  // namespace needlekit::mesh::detail
