#include "serve_api.hpp"

#include <fmt/format.h>

#include <stdlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>

#include "needlekit/analysis/column_eigenvalue.hpp"
#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/analysis/puncture_model.hpp"
#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/body_view.hpp"
#include "needlekit/io/design_evaluation.hpp"
#include "needlekit/io/json_config.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/patch_run.hpp"
#include "needlekit/io/patch_view.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/robust_design_run.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::cli {
namespace {

template <class Value, std::size_t N>
nlohmann::json names_json(const EnumTable<Value, N>& table) {
  nlohmann::json names = nlohmann::json::array();
  for (const EnumEntry<Value>& entry : table) names.push_back({{"name", entry.name}, {"meaning", entry.meaning}});
  return names;
}

nlohmann::json optional_value(const std::optional<double>& value, double scale) {
  return value ? nlohmann::json(*value * scale) : nlohmann::json(nullptr);
}

// A space with min_success_probability: `needlekit optimize --json`'s robust design (the grid ranked by brute force,
// then the best candidates checked under uncertainty, best first).
JobWork robust_design_work(std::shared_ptr<const io::SpaceFile> file, const OptimizeRequest& request) {
  if (request.certified) {
    throw InvalidInput("space.json: certified=true does not apply with min_success_probability (robust design ranks "
                       "the grid by brute force), expected certified=false");
  }
  io::RobustDesignRunOptions options;
  options.top = request.top;
  return [file, options](JobProgress& progress) mutable {
    options.progress = [&progress](double fraction) { return progress.report(fraction); };
    return io::rounded_numbers(io::robust_design_run_json(*file, options));
  };
}

}  // namespace

nlohmann::json error_json(std::string_view message) {
  nlohmann::json json = {{"error", message}, {"key", nullptr}};
  const std::size_t start = message.find("key '");
  if (start != std::string_view::npos) {
    const std::size_t end = message.find('\'', start + 5);
    if (end != std::string_view::npos) json["key"] = message.substr(start + 5, end - start - 5);
  }
  return json;
}

nlohmann::json presets_json() {
  nlohmann::json materials = nlohmann::json::array();
  for (const std::string& name : materials::material_preset_names()) {
    const materials::NeedleMaterial m = materials::material_preset(name);
    materials.push_back({{"name", name},
                         {"youngs_modulus_GPa", m.youngs_modulus * 1e-9},
                         {"yield_strength_MPa", optional_value(m.yield_strength, 1e-6)},
                         {"allowable_stress_MPa", optional_value(m.allowable_stress, 1e-6)},
                         {"source", m.source}});
  }
  nlohmann::json tissues = nlohmann::json::array();
  for (const std::string& name : analysis::puncture_model_preset_names()) {
    const analysis::PunctureModel t = analysis::puncture_model_preset(name);
    tissues.push_back({{"name", name}, {"alpha_N", t.alpha}, {"tau_per_mm", t.tau * 1e-3}});
  }
  return {{"shapes", names_json(needle::kShapeNames)},
          {"materials", materials},
          {"tissue_models", tissues},
          {"end_conditions", names_json(analysis::kEndConditionNames)},
          {"effective_lengths", names_json(analysis::kEffectiveLengthNames)},
          {"patch_kinds", names_json(patch::kPatchKindNames)},
          {"approaches", names_json(patch::kApproachNames)}};
}

nlohmann::json evaluate_json(std::string_view body) {
  return io::rounded_numbers(io::evaluate_design(io::parse_design_json(body, "design.json")).json);
}

JobWork optimize_work(std::string_view body, const OptimizeRequest& request) {
  if (request.top < 1 || request.top > 100) {
    throw InvalidInput(fmt::format("top: {} is out of range, expected an integer in [1, 100]", request.top));
  }
  auto file = std::make_shared<const io::SpaceFile>(io::parse_space_json(body, "space.json"));
  if (file->robust) return robust_design_work(file, request);
  analysis::OptimizerOptions options;
  options.method = request.certified ? analysis::SearchMethod::Certified : analysis::SearchMethod::BruteForce;
  options.top = request.top;
  // A grid too large for brute force or for memory is refused by the optimizer before any work: that job's error,
  // with "bad_input": true.
  return [file, options](JobProgress& progress) mutable {
    options.progress = [&progress](double fraction) { return progress.report(fraction); };
    const analysis::OptimizerResult result = analysis::optimize_design(file->space, options);
    if (result.status == analysis::OptimizerStatus::Cancelled) throw Interrupted();
    return io::rounded_numbers(io::optimizer_json(file->space, result));
  };
}

JobWork uncertainty_work(std::string_view body) {
  auto file = std::make_shared<const io::UncertaintyFile>(io::parse_uncertainty_json(body, "uncertainty.json"));
  return [file](JobProgress& progress) {
    uncertainty::DesignUncertaintyOptions options;
    options.sampling = file->sampling;
    options.sampling.progress = [&progress](double fraction) { return progress.report(fraction); };
    const uncertainty::DesignUncertaintyResult result =
        uncertainty::design_uncertainty(file->design, file->inputs, file->correlations, options);
    return io::rounded_numbers(io::uncertainty_json(*file, result));
  };
}

MeshRegistry::MeshRegistry(const std::filesystem::path& mesh_folder, const std::filesystem::path& examples_folder) {
  namespace fs = std::filesystem;
  for (const fs::directory_entry& entry : fs::directory_iterator(mesh_folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".obj") {
      meshes_[entry.path().filename().string()] = entry.path();
    }
  }
  std::vector<fs::path> examples;
  for (const fs::directory_entry& entry : fs::directory_iterator(examples_folder)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("patch_", 0) == 0 && entry.path().extension() == ".toml") examples.push_back(entry.path());
  }
  std::sort(examples.begin(), examples.end());
  for (const auto& [name, path] : meshes_) {
    nlohmann::json mesh = {{"name", name}, {"upload", false}, {"example", nullptr}};
    for (const fs::path& example : examples) {
      const io::PatchCase c = io::read_patch_case(example);
      if (c.mesh.filename() != name || !c.placement.center_vertex) continue;
      mesh["example"] = example.filename().string();
      mesh["unit_m"] = c.mesh_unit;
      mesh["center_vertex"] = *c.placement.center_vertex;
      mesh["approach"] = patch::to_string(c.placement.approach);
      break;
    }
    listing_.push_back(mesh);
  }
  std::string folder = (fs::temp_directory_path() / "needlekit-serve-XXXXXX").string();
  if (!::mkdtemp(folder.data())) {
    throw IoError(fmt::format("{}: cannot create the upload folder: {}", folder, std::strerror(errno)));
  }
  upload_folder_ = folder;
}

MeshRegistry::~MeshRegistry() {
  std::error_code ignored;
  std::filesystem::remove_all(upload_folder_, ignored);
}

nlohmann::json MeshRegistry::listing() const {
  const std::lock_guard<std::mutex> guard(lock_);
  return listing_;
}

std::map<std::string, std::filesystem::path> MeshRegistry::meshes() const {
  const std::lock_guard<std::mutex> guard(lock_);
  return meshes_;
}

nlohmann::json MeshRegistry::add_upload(std::string_view bytes, std::string_view format) {
  if (format != "obj" && format != "stl" && format != "ply") {
    throw InvalidInput(fmt::format("format: '{}' is not a mesh format, expected obj, stl or ply", format));
  }
  std::string name;
  {
    const std::lock_guard<std::mutex> guard(lock_);
    name = fmt::format("upload-{}.{}", next_upload_++, format);
  }
  const std::filesystem::path path = upload_folder_ / name;
  write_file_atomically(path, bytes);
  nlohmann::json entry = {{"name", name}, {"upload", true}, {"example", nullptr}};
  try {
    const geometry::BodySurface body = geometry::read_body_surface(path, 1.0);
    entry["triangles"] = body.surface.triangle_count();
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    throw;
  }
  const std::lock_guard<std::mutex> guard(lock_);
  meshes_[name] = path;
  listing_.push_back(entry);
  uploads_.push_back(name);
  if (uploads_.size() > kMaxUploads) {
    const std::string oldest = uploads_.front();
    uploads_.pop_front();
    std::error_code ignored;
    std::filesystem::remove(meshes_[oldest], ignored);
    meshes_.erase(oldest);
    nlohmann::json kept = nlohmann::json::array();
    for (const nlohmann::json& mesh : listing_) {
      if (mesh["name"] != oldest) kept.push_back(mesh);
    }
    listing_ = std::move(kept);
  }
  return entry;
}

JobWork patch_work(std::string_view body, const MeshRegistry& meshes, bool with_view) {
  auto c = std::make_shared<const io::PatchCase>(io::parse_patch_case_json(body, "patch.json", meshes.meshes()));
  // The registry outlives the job pool (http_server.cpp declares it first).
  return [c, with_view, &meshes](JobProgress& progress) {
    // The job's fraction: the mesh read (none when the page's body view read it already), then the library's fit
    // (its frame, each node or Newton iteration, the evaluation, the springs along the surface), then the view.
    constexpr double kRead = 0.2, kFitted = 0.95;
    const std::shared_ptr<const geometry::BodySurface> body = meshes.body({c->mesh, c->mesh_unit});
    const std::vector<std::string> warnings = io::patch_surface_warnings(*c, *body);
    if (!progress.report(kRead)) throw Interrupted();
    patch::FitAndEvaluateOptions options{c->placement, c->fit, c->evaluation, true, nullptr};
    options.progress = [&progress](double fraction) { return progress.report(kRead + fraction * (kFitted - kRead)); };
    const patch::FitAndEvaluateResult result = patch::fit_and_evaluate(body->surface, c->design, options);
    nlohmann::json summary = io::rounded_numbers(io::patch_case_summary(*c, result, warnings));
    if (with_view) {
      summary["view"] = io::patch_view(c->mesh.stem().string(), body->surface, result.design, result.fit,
                                       result.evaluation);
    }
    return summary;
  };
}

std::shared_ptr<const geometry::BodySurface> MeshRegistry::body(const io::BodyMeshFile& file) const {
  const std::lock_guard<std::mutex> guard(body_lock_);
  if (!last_body_ || last_body_mesh_ != file.mesh || last_body_unit_ != file.mesh_unit) {
    last_body_ = std::make_shared<const geometry::BodySurface>(geometry::read_body_surface(file.mesh, file.mesh_unit));
    last_body_mesh_ = file.mesh;
    last_body_unit_ = file.mesh_unit;
  }
  return last_body_;
}

nlohmann::json body_view_json(std::string_view body, const MeshRegistry& meshes) {
  const io::BodyMeshFile file = io::parse_body_mesh_json(body, "surface.json", meshes.meshes());
  return io::body_view(file.mesh.filename().string(), meshes.body(file)->surface);
}

nlohmann::json body_pick_json(std::string_view body, const MeshRegistry& meshes) {
  const io::BodyPick pick = io::parse_body_pick_json(body, "pick.json", meshes.meshes());
  return io::rounded_numbers(io::body_pick(meshes.body(pick.body)->surface, pick.origin, pick.direction));
}

}  // namespace needlekit::cli
