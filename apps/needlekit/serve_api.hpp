// The JSON API of `needlekit serve` (docs/serve.md) without the HTTP: each function parses a request body with the
// library's readers (io/json_config.hpp), calls one library function and presents its result as the CLI's --json
// does (numbers rounded as io::json_text rounds them). Bad input throws InvalidInput / IoError with the CLI's message; http_server.cpp turns it into HTTP 400 and
// error_json().
#pragma once
#include <nlohmann/json.hpp>

#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "job_pool.hpp"

// Declared only: http_server.cpp includes cpp-httplib, whose <resolv.h> defines the macro `_res` that Eigen's headers
// use as a parameter name, so this header must not bring Eigen in.
namespace needlekit::geometry {
struct BodySurface;
}
namespace needlekit::io {
struct BodyMeshFile;
}

namespace needlekit::cli {

// {"error": message, "key": the dotted key the message names, or null}.
nlohmann::json error_json(std::string_view message);

// GET /api/presets: needle shapes, materials (with their values and sources), tissue models, buckling end conditions,
// effective-length values, patch kinds and approaches, from the library's tables.
nlohmann::json presets_json();

// POST /api/evaluate: exactly what `needlekit evaluate --json` prints for the design.
nlohmann::json evaluate_json(std::string_view body);

// POST /api/optimize and POST /api/uncertainty: the body is parsed now (bad input throws before anything is queued);
// the returned work runs on the job pool and returns what `needlekit optimize --json` (top designs; `certified`:
// the branch-and-bound optimum) or `needlekit uncertainty --json` prints.
struct OptimizeRequest {
  bool certified = false;
  int top = 10;  // [1, 100]
};
JobWork optimize_work(std::string_view body, const OptimizeRequest& request);
JobWork uncertainty_work(std::string_view body);

// The body meshes patch jobs may use, by name: the OBJ files of data/meshes (listed once at start, with the unit,
// centre vertex and approach of the first examples/patch_*.toml that uses each) and the uploads, each written to its
// own file in a private temporary folder (removed with the registry). Thread-safe.
class MeshRegistry {
public:
  static constexpr std::size_t kMaxUploads = 8;  // the oldest upload is deleted beyond

  MeshRegistry(const std::filesystem::path& mesh_folder, const std::filesystem::path& examples_folder);
  ~MeshRegistry();
  MeshRegistry(const MeshRegistry&) = delete;
  MeshRegistry& operator=(const MeshRegistry&) = delete;

  // GET /api/meshes: [{"name", "upload", "example"?, "unit_m"?, "center_vertex"?, "approach"?, "triangles"?}].
  nlohmann::json listing() const;
  // Name -> file, for io::parse_patch_case_json.
  std::map<std::string, std::filesystem::path> meshes() const;
  // POST /api/uploads?format=obj|stl|ply: writes `bytes` to a new file "upload-N.FORMAT", reads it as a body surface
  // (the reader's InvalidInput / IoError for a file that fails to read, the file then deleted) and returns its entry.
  nlohmann::json add_upload(std::string_view bytes, std::string_view format);
  // The body surface `file` names, read once: the last one read is kept, so that the clicks on a body's view after
  // its POST /api/body-view, and the patch jobs on that body, do not each read the mesh again (1.2 s for the
  // 240k-triangle neck).
  std::shared_ptr<const geometry::BodySurface> body(const io::BodyMeshFile& file) const;

private:
  mutable std::mutex lock_;
  std::map<std::string, std::filesystem::path> meshes_;
  nlohmann::json listing_ = nlohmann::json::array();
  std::filesystem::path upload_folder_;
  std::deque<std::string> uploads_;  // oldest first
  std::uint64_t next_upload_ = 1;
  mutable std::mutex body_lock_;  // held while a body is read: requests for the same body wait for that read
  mutable std::filesystem::path last_body_mesh_;
  mutable double last_body_unit_ = 0;
  mutable std::shared_ptr<const geometry::BodySurface> last_body_;
};

// POST /api/patch[?view=true]: a patch case whose [surface] mesh is a name of `meshes`; the job's result is what
// `needlekit patch CASE.toml --json` prints, and with `with_view` also "view": the fit's 3D view (io/patch_view.hpp,
// the data of `needlekit patch --out`'s patch_view.js) for the page's viewer. The job reads the body through
// `meshes` (MeshRegistry::body), which must outlive it.
JobWork patch_work(std::string_view body, const MeshRegistry& meshes, bool with_view = false);

// POST /api/body-view: {"surface": {"mesh": a name of `meshes`, "unit": "1 m"}} (a patch case's [surface] keys);
// the body's whole surface as a 3D view to place the patch on (io/body_view.hpp: decimated, with the full mesh's
// vertex index of every vertex drawn).
nlohmann::json body_view_json(std::string_view body, const MeshRegistry& meshes);

// POST /api/body-pick: {"surface": as for body-view, "ray": {"origin": ["x m", "y m", "z m"], "direction": [dx, dy,
// dz]}} (io/json_config.hpp), the camera's ray through a click on the body's view; the answer is io::body_pick's:
// the vertex of the full mesh the click means, where the ray met it, and its normal.
nlohmann::json body_pick_json(std::string_view body, const MeshRegistry& meshes);

}  // namespace needlekit::cli
