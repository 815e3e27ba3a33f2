// `needlekit materials`: the needle-material presets and the tissue presets with their properties and sources.
#include <fmt/format.h>

#include <optional>
#include <string>

#include "commands.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/materials/tissue_presets.hpp"

namespace needlekit::cli {
namespace {

std::string mpa(const std::optional<double>& pascals) {
  return pascals ? fmt::format("{:.4g} MPa", *pascals * 1e-6) : "-";
}

void run_materials() {
  fmt::print("{:<17} {:>10} {:>20} {:>17}\n", "preset", "E", "yield/fracture s_y", "allowable sigma");
  for (const std::string& name : materials::material_preset_names()) {
    const materials::NeedleMaterial material = materials::material_preset(name);
    fmt::print("{:<17} {:>10} {:>20} {:>17}\n", name, fmt::format("{:.4g} GPa", material.youngs_modulus * 1e-9),
               mpa(material.yield_strength), mpa(material.allowable_stress));
    fmt::print("    source: {}\n", material.source);
  }
  fmt::print("\ntissue preset (case files: [tissue] preset = ...), layers top to bottom: thickness, E, nu\n");
  for (const std::string& name : materials::tissue_preset_names()) {
    const materials::TissuePreset preset = materials::tissue_preset(name);
    fmt::print("{}\n", name);
    for (const materials::TissueLayer& l : preset.layers) {
      fmt::print("    {:<17} {:>10} {:>14} {:>6}\n", l.name, fmt::format("{:g} um", l.thickness * 1e6),
                 fmt::format("{:.4g} MPa", l.youngs_modulus * 1e-6), fmt::format("{:g}", l.poisson_ratio));
    }
    fmt::print("    source: {}\n", preset.source);
  }
}

}  // namespace

void add_materials_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "materials", "List the needle-material presets (Young's modulus, strength, allowable stress) and the tissue "
                   "presets (layers, E, nu), with sources");
  command->callback(run_materials);
}

}  // namespace needlekit::cli
