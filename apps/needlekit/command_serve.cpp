// `needlekit serve [--port N] [--host H]`: the local design page and its JSON API (docs/serve.md). Parses the options,
// finds the page's assets (web/design, resources_root.hpp), prints the address and serves until Ctrl-C
// (http_server.cpp).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.hpp"
#include "http_server.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "resources_root.hpp"

namespace needlekit::cli {

void add_serve_command(CLI::App& app) {
  auto options = std::make_shared<ServeOptions>();
  CLI::App* command = app.add_subcommand(
      "serve", "The design page in a browser and its JSON API (docs/serve.md), on 127.0.0.1 until Ctrl-C");
  command->add_option("--port", options->port, "TCP port, 0 for any free one (the address is printed)")
      ->type_name("N")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  command->add_option("--host", options->host, "address to bind; anything but 127.0.0.1 exposes the API to the network")
      ->type_name("H")
      ->capture_default_str();
  command->add_option("--job-workers", options->job_workers, "threads running optimize/uncertainty jobs, in [1, 16]")
      ->type_name("N")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  command->add_option("--job-queue", options->job_queue, "jobs that may wait for a worker (more get HTTP 503)")
      ->type_name("N")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  command->callback([options] {
    if (options->host != "127.0.0.1" && options->host != "localhost" && options->host != "::1") {
      fmt::print(stderr,
                 "needlekit: warning: serving on {} exposes the design API to every machine that can reach it; it has "
                 "no authentication (docs/serve.md)\n",
                 options->host);
    }
    const std::filesystem::path root =
        resources_root({"web/design/index.html", "web/viewer/needlekit_viewer.js", "data/meshes", "examples"});
    options->web_dir = root / "web" / "design";
    options->viewer_dir = root / "web" / "viewer";
    options->mesh_dir = root / "data" / "meshes";
    options->examples_dir = root / "examples";
    serve(*options, [&](int port) {
      fmt::print("needlekit serve: listening on http://{}:{}/ (Ctrl-C to stop)\n",
                 options->host.find(':') != std::string::npos ? "[" + options->host + "]" : options->host, port);
      std::fflush(stdout);
    });
    throw Interrupted();  // served until Ctrl-C / SIGTERM: exit code 130, as every interrupted command
  });
}

}  // namespace needlekit::cli
