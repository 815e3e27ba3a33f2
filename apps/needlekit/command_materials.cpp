// `needlekit materials`: the needle-material presets with their properties and sources.
#include <fmt/format.h>

#include <optional>
#include <string>

#include "commands.hpp"
#include "needlekit/materials/needle_material.hpp"

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
}

}  // namespace

void add_materials_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "materials", "List the needle-material presets: Young's modulus, strength, allowable stress and sources");
  command->callback(run_materials);
}

}  // namespace needlekit::cli
