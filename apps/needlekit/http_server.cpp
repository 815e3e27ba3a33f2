// The one file that includes cpp-httplib. Every route is declared here; nothing from a request reaches the file
// system: the assets are read once at start from a fixed allow-list, and every other path is 404.
#include "http_server.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <map>
#include <thread>

#include "job_pool.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/file_bytes.hpp"
#include "needlekit/core/interrupt.hpp"
#include "serve_api.hpp"

namespace needlekit::cli {
namespace {

struct Asset {
  std::string content_type;
  std::string bytes;
};

// URL path -> file: the page's own files, the 3D viewer of the patch fit and the two three.js classic scripts. Nothing
// else is served.
std::map<std::string, Asset> read_assets(const ServeOptions& options) {
  const struct {
    const char* url;
    std::filesystem::path file;
    const char* type;
  } allowed[] = {
      {"/", options.web_dir / "index.html", "text/html; charset=utf-8"},
      {"/index.html", options.web_dir / "index.html", "text/html; charset=utf-8"},
      {"/design.js", options.web_dir / "design.js", "text/javascript; charset=utf-8"},
      {"/design.css", options.web_dir / "design.css", "text/css; charset=utf-8"},
      {"/three/three.min.js", options.three_dir / "three.min.js", "text/javascript; charset=utf-8"},
      {"/three/OrbitControls.js", options.three_dir / "examples" / "js" / "controls" / "OrbitControls.js",
       "text/javascript; charset=utf-8"},
      {"/viewer/needlekit_viewer.js", options.viewer_dir / "needlekit_viewer.js", "text/javascript; charset=utf-8"},
      {"/viewer/needlekit_viewer.css", options.viewer_dir / "needlekit_viewer.css", "text/css; charset=utf-8"},
  };
  std::map<std::string, Asset> assets;
  for (const auto& a : allowed) assets[a.url] = {a.type, read_file_bytes(a.file, "web asset")};
  return assets;
}

constexpr int kListenBacklog = 1024;  // connections waiting to be accepted (capped by net.core.somaxconn)

bool loopback(const std::string& host) { return host == "127.0.0.1" || host == "localhost" || host == "::1"; }

// Invalid UTF-8 in a message (a malformed body quoted by the JSON parser) becomes U+FFFD instead of an exception.
std::string json_body(const nlohmann::json& json) {
  return json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void send_json(httplib::Response& res, int status, const nlohmann::json& json) {
  res.status = status;
  res.set_content(json_body(json), "application/json");
}

// Runs a handler; bad input is 400 with the CLI's message and the key it names, a body over `max_body` 413.
template <class Handler>
void answer(const httplib::Request& req, httplib::Response& res, std::size_t max_body, Handler&& handler) {
  if (req.body.size() > max_body) {
    send_json(res, 413, error_json(fmt::format("the request body has {} bytes, more than the limit of {}",
                                               req.body.size(), max_body)));
    return;
  }
  try {
    handler();
  } catch (const InvalidInput& error) {
    send_json(res, 400, error_json(error.what()));
  } catch (const IoError& error) {
    send_json(res, 400, error_json(error.what()));
  }
}

// The server's threads, timeouts and keep-alive, Nagle off (headers and body are two writes: without it Nagle waits
// for a delayed ACK, 40 ms), and the listening socket: SO_REUSEADDR only (httplib's default SO_REUSEPORT would let
// another process bind the same port and take a share of the connections); its descriptor goes to
// `listening_socket`, for a backlog of kListenBacklog instead of the 5 compiled into Debian's libcpp-httplib (listen()
// again on the bound socket), so that a burst of connections waits instead of being reset.
void configure(httplib::Server& server, const ServeOptions& options, int& listening_socket) {
  const int http_threads = options.http_threads;
  server.new_task_queue = [http_threads] { return new httplib::ThreadPool(static_cast<std::size_t>(http_threads)); };
  server.set_payload_max_length(options.max_upload_bytes);  // JSON routes check their own, smaller limit
  server.set_tcp_nodelay(true);
  server.set_read_timeout(5, 0);
  server.set_write_timeout(5, 0);
  server.set_keep_alive_timeout(2);
  server.set_keep_alive_max_count(1000);
  server.set_socket_options([&listening_socket](int socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    listening_socket = socket;
  });
}

// Before routing: a page elsewhere cannot use this server. A POST to /api/ must be application/json (a
// cross-origin page then needs a CORS preflight, which is never granted), and on loopback the Host header must be
// this server's (a DNS-rebinding page sends its own name). An upload is application/octet-stream, not a
// CORS-safelisted type either. Errors without a body get a JSON message; an exception that is not bad input is a
// defect: 500 for this request, the server goes on.
void add_guards(httplib::Server& server, const ServeOptions& options, const std::atomic<int>& bound_port) {
  server.set_pre_routing_handler([&options, &bound_port](const httplib::Request& req, httplib::Response& res) {
    if (loopback(options.host)) {
      const std::string host = req.get_header_value("Host");
      const std::string port = fmt::format(":{}", bound_port.load());
      if (host != "127.0.0.1" + port && host != "localhost" + port && host != "[::1]" + port) {
        send_json(res, 403, error_json(fmt::format("Host '{}' is not this server's, expected 127.0.0.1{}", host, port)));
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    const std::string type = req.path == "/api/uploads" ? "application/octet-stream" : "application/json";
    if (req.method == "POST" && req.path.rfind("/api/", 0) == 0 &&
        req.get_header_value("Content-Type").rfind(type, 0) != 0) {
      send_json(res, 415, error_json(fmt::format("the request's Content-Type is not {}", type)));
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  server.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request&, httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    const char* what = res.status == 404   ? "not found"
                       : res.status == 413 ? "the request body is larger than the server's limit"
                                           : "bad request";
    res.set_content(json_body(error_json(what)), "application/json");
    return httplib::Server::HandlerResponse::Handled;
  }));
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
    std::string what = "unknown exception";
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    send_json(res, 500, error_json(fmt::format("internal error: {}", what)));
  });
}

// The allow-listed assets, the presets and the design's evaluation.
void add_page_routes(httplib::Server& server, const ServeOptions& options, const std::map<std::string, Asset>& assets) {
  const std::size_t max_body = options.max_body_bytes;
  for (const auto& [url, asset] : assets) {
    server.Get(url, [&asset = asset](const httplib::Request&, httplib::Response& res) {
      res.set_content(asset.bytes, asset.content_type);
      res.set_header("Cache-Control", "no-cache");
      res.set_header("X-Content-Type-Options", "nosniff");
    });
  }
  server.Get("/api/presets", [](const httplib::Request&, httplib::Response& res) {
    send_json(res, 200, presets_json());
  });
  server.Post("/api/evaluate", [max_body](const httplib::Request& req, httplib::Response& res) {
    answer(req, res, max_body, [&] { send_json(res, 200, evaluate_json(req.body)); });
  });
}

// The body meshes: the list, the uploads and a body's view (to place a patch on it).
void add_mesh_routes(httplib::Server& server, const ServeOptions& options, MeshRegistry& meshes) {
  server.Get("/api/meshes", [&meshes](const httplib::Request&, httplib::Response& res) {
    send_json(res, 200, meshes.listing());
  });
  const std::size_t max_upload = options.max_upload_bytes;
  server.Post("/api/uploads", [&meshes, max_upload](const httplib::Request& req, httplib::Response& res) {
    answer(req, res, max_upload, [&] { send_json(res, 201, meshes.add_upload(req.body, req.get_param_value("format"))); });
  });
  const std::size_t max_body = options.max_body_bytes;
  server.Post("/api/body-view", [&meshes, max_body](const httplib::Request& req, httplib::Response& res) {
    answer(req, res, max_body, [&] { send_json(res, 200, body_view_json(req.body, meshes)); });
  });
  server.Post("/api/body-pick", [&meshes, max_body](const httplib::Request& req, httplib::Response& res) {
    answer(req, res, max_body, [&] { send_json(res, 200, body_pick_json(req.body, meshes)); });
  });
}

// The long runs, on the job pool: submitted, polled, cancelled.
void add_job_routes(httplib::Server& server, const ServeOptions& options, MeshRegistry& meshes, JobPool& jobs) {
  const std::size_t max_body = options.max_body_bytes;
  const auto submit = [&jobs](httplib::Response& res, std::string kind, JobWork work) {
    if (const auto id = jobs.submit(std::move(kind), std::move(work))) {
      send_json(res, 202, *jobs.status(*id));
    } else {
      send_json(res, 503, error_json("the job queue is full, expected a retry once a job has finished"));
    }
  };
  server.Post("/api/optimize", [submit, max_body](const httplib::Request& req, httplib::Response& res) {
    answer(req, res, max_body, [&] {
      OptimizeRequest request;
      request.certified = req.get_param_value("certified") == "true";
      if (req.has_param("top")) {
        const std::string top = req.get_param_value("top");
        try {
          request.top = std::stoi(top);
        } catch (const std::exception&) {
          throw InvalidInput(fmt::format("top: '{}' is not an integer, expected an integer in [1, 100]", top));
        }
      }
      submit(res, "optimize", optimize_work(req.body, request));
    });
  });
  server.Post("/api/uncertainty", [submit, max_body](const httplib::Request& req, httplib::Response& res) {
    answer(req, res, max_body, [&] { submit(res, "uncertainty", uncertainty_work(req.body)); });
  });
  server.Post("/api/patch", [submit, max_body, &meshes](const httplib::Request& req, httplib::Response& res) {
    answer(req, res, max_body, [&] {
      submit(res, "patch", patch_work(req.body, meshes, req.get_param_value("view") == "true"));
    });
  });
  server.Get(R"(/api/jobs/(\d{1,18}))", [&jobs](const httplib::Request& req, httplib::Response& res) {
    if (const auto status = jobs.status(req.matches[1])) {
      send_json(res, 200, *status);
    } else {
      send_json(res, 404, error_json("no such job"));
    }
  });
  server.Delete(R"(/api/jobs/(\d{1,18}))", [&jobs](const httplib::Request& req, httplib::Response& res) {
    if (jobs.cancel(req.matches[1])) {
      send_json(res, 200, *jobs.status(req.matches[1]));
    } else {
      send_json(res, 404, error_json("no such job"));
    }
  });
}

}  // namespace

void serve(const ServeOptions& options, const std::function<void(int port)>& listening) {
  const std::map<std::string, Asset> assets = read_assets(options);
  MeshRegistry meshes(options.mesh_dir, options.examples_dir);
  JobPool jobs(options.job_workers, options.job_queue);
  httplib::Server server;
  std::atomic<int> bound_port = 0;
  int listening_socket = -1;
  configure(server, options, listening_socket);
  add_guards(server, options, bound_port);
  add_page_routes(server, options, assets);
  add_mesh_routes(server, options, meshes);
  add_job_routes(server, options, meshes, jobs);

  const int port = options.port == 0 ? server.bind_to_any_port(options.host)
                                     : (server.bind_to_port(options.host, options.port) ? options.port : -1);
  if (port < 0) {
    throw IoError(fmt::format("cannot listen on {}:{} (the port is taken or the address is not this machine's)",
                              options.host, options.port));
  }
  bound_port = port;
  if (listening_socket >= 0) ::listen(listening_socket, kListenBacklog);
  std::thread stopper([&server] {  // Ctrl-C / SIGTERM set the interrupt flag: stop accepting, finish, return
    while (!interrupt_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    server.stop();
  });
  listening(port);
  server.listen_after_bind();
  if (!interrupt_requested()) request_interrupt();  // listen failed: end the stopper thread too
  stopper.join();
  jobs.stop();
}

}  // namespace needlekit::cli
