// `needlekit serve`'s HTTP server (cpp-httplib from Debian, used in http_server.cpp only): the design page's own
// assets from a fixed allow-list, three.js from Debian's libjs-three, and the JSON API of serve_api.hpp. docs/serve.md
// describes the routes, the security model and the limits.
#pragma once
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>

namespace needlekit::cli {

struct ServeOptions {
  std::string host = "127.0.0.1";
  int port = 8737;                                   // 0: any free port
  std::filesystem::path web_dir;                     // web/design: index.html, design.js, design.css
  std::filesystem::path viewer_dir;                  // web/viewer: needlekit_viewer.js, .css (the patch fit in 3D)
  std::filesystem::path mesh_dir;                    // data/meshes: the body meshes patch jobs may use, by name
  std::filesystem::path examples_dir;                // examples: patch_*.toml suggest a unit and centre per mesh
  std::filesystem::path three_dir = "/usr/share/javascript/three";  // libjs-three
  std::size_t max_body_bytes = 1 << 20;              // larger JSON bodies get 413
  std::size_t max_upload_bytes = 32 << 20;           // larger mesh uploads (and any larger body) get 413
  int job_workers = 1;                               // threads running optimize/uncertainty jobs
  std::size_t job_queue = 4;                         // jobs waiting for a worker; more get 503
  int http_threads = 8;                              // threads answering requests
};

// Reads the assets (IoError naming a missing one), binds (IoError when the address is taken), calls `listening`
// with the bound port, and serves until an interrupt is requested (core/interrupt.hpp: Ctrl-C, SIGTERM).
void serve(const ServeOptions& options, const std::function<void(int port)>& listening);

}  // namespace needlekit::cli
