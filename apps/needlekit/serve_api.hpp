// The JSON API of `needlekit serve` (docs/serve.md) without the HTTP: each function parses a request body with the
// library's readers (io/json_config.hpp), calls one library function and presents its result as the CLI's --json
// does (numbers rounded as io::json_text rounds them). Bad input throws InvalidInput / IoError with the CLI's message; http_server.cpp turns it into HTTP 400 and
// error_json().
#pragma once
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "job_pool.hpp"

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

// The body meshes offered to patch jobs: the OBJ files of `mesh_folder` (data/meshes), by name, read once at start.
struct MeshChoices {
  std::filesystem::path folder;
  std::vector<std::string> names;
  nlohmann::json listing;  // GET /api/meshes: per mesh its name and, from the first examples/patch_*.toml that uses
                           // it, the example, the unit in m, the centre vertex and the approach
};
MeshChoices mesh_choices(const std::filesystem::path& mesh_folder, const std::filesystem::path& examples_folder);

// POST /api/patch: a patch case whose [surface] mesh is a name of `meshes`; the job's result is what
// `needlekit patch CASE.toml --json` prints.
JobWork patch_work(std::string_view body, const MeshChoices& meshes);

}  // namespace needlekit::cli
