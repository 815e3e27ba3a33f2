// Private to the Gmsh module (src/mesh/gmsh/): Gmsh is one global state, so every use goes through a GmshSession,
// which holds a process-wide mutex, initializes Gmsh silently (no terminal output, messages kept in its logger) and
// finalizes it on exit.
#pragma once
#include <gmsh.h>

#include <mutex>
#include <string>
#include <vector>

namespace needlekit::mesh::detail {

class GmshSession {
public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // Sets the first of `names` that this Gmsh version knows (option names changed between versions).
  static void set_option(const std::vector<std::string>& names, double value);
  // The last error Gmsh logged, or "" if none.
  static std::string last_error();

private:
  std::unique_lock<std::mutex> lock_;
};

// The message of an exception thrown by Gmsh (std::string, std::exception or other), with its last logged error.
std::string gmsh_error_message();

}  // namespace needlekit::mesh::detail
