#include "needlekit/materials/tissue_presets.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/materials/preset_key.hpp"

namespace needlekit::materials {
namespace {

constexpr double kSkinHeight = 1150e-6;     // §3.3.2 / §6.2: 3000 x 3000 x 1150 um block
constexpr double kStratumCorneum = 20e-6;   // §3.3.2: SC within 20 um of the surface
constexpr double kEpidermisBottom = 160e-6; // §3.3.2: DM below 160 um

constexpr std::string_view kDissertationSkin =
    "dissertation §3.3.2: SC 20 um (Wu, Van Osdol & Dauskardt, Biomaterials 27, 785-795, 2006: about 1 GPa at the "
    "surface, under 100 MPa at 10 um depth), EP to 160 um depth E = 0.134 MPa and DM E = 0.08 MPa (L'Etang & "
    "Huang, Ultrasonics 44, 1243-1247, 2006), nu = 0.4 for every layer; block height 1150 um";

std::vector<TissueLayer> phantom(double modulus) {
  // §6.2: silicone rubber, nu = 0.49 (the issue allows 0.48-0.49), one homogeneous layer.
  return {{"silicone rubber", kSkinHeight, modulus, 0.49}};
}

struct Entry {
  std::string_view key;
  TissuePreset preset;
};

const std::vector<Entry>& presets() {
  static const std::vector<Entry> table = {
      {"skin", {"skin", skin_layers(100e6), kSkinHeight, std::string(kDissertationSkin) + "; SC E = 100 MPa (the value "
                                                                                           "the dissertation uses)"}},
      {"skin-stiff-sc",
       {"skin-stiff-sc", skin_layers(1e9), kSkinHeight,
        std::string(kDissertationSkin) + "; SC E = 1 GPa (Wu 2006's value at the extreme surface)"}},
      {"silicone-0.2mpa",
       {"silicone-0.2mpa", phantom(0.2e6), kSkinHeight,
        "dissertation §6.2: silicone rubber skin phantom, E = 0.2 MPa, nu = 0.49, 1150 um block"}},
      {"silicone-0.5mpa",
       {"silicone-0.5mpa", phantom(0.5e6), kSkinHeight,
        "dissertation §6.2: stiffer silicone rubber skin phantom, E = 0.5 MPa, nu = 0.49, 1150 um block"}},
      {"skin-geerligs-2011",
       {"skin-geerligs-2011",
        {{"stratum corneum", kStratumCorneum, 1.5e6, 0.4},
         {"epidermis", kEpidermisBottom - kStratumCorneum, 1.5e6, 0.4},
         {"dermis", kSkinHeight - kEpidermisBottom, 0.08e6, 0.4}},
        kSkinHeight,
        "SC and viable epidermis E = 1.5 MPa, the middle of the 1-2 MPa that Geerligs et al. (J. Biomech. 44, "
        "1176-1181, 2011) measured for both by in vitro micro-indentation perpendicular to the skin; dermis "
        "0.08 MPa (L'Etang & Huang 2006, as the dissertation); thicknesses and nu = 0.4 as dissertation §3.3.2"}},
  };
  return table;
}

}  // namespace

std::vector<TissueLayer> skin_layers(double stratum_corneum_modulus) {
  return {{"stratum corneum", kStratumCorneum, stratum_corneum_modulus, 0.4},
          {"epidermis", kEpidermisBottom - kStratumCorneum, 0.134e6, 0.4},
          {"dermis", kSkinHeight - kEpidermisBottom, 0.08e6, 0.4}};
}

std::vector<std::string> tissue_preset_names() {
  std::vector<std::string> names;
  for (const auto& p : presets()) names.emplace_back(p.key);
  return names;
}

TissuePreset tissue_preset(std::string_view name, std::string_view what) {
  const std::string wanted = preset_key(name);
  for (const auto& p : presets()) {
    if (preset_key(p.key) == wanted) return p.preset;
  }
  throw InvalidInput(fmt::format("{}: unknown tissue preset '{}', expected one of: {}", what, name,
                                 fmt::join(tissue_preset_names(), ", ")));
}

void validate(const std::vector<TissueLayer>& layers, std::string_view where) {
  if (layers.empty()) throw InvalidInput(fmt::format("{}: no layers; expected at least one", where));
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const TissueLayer& l = layers[i];
    const std::string at = fmt::format("{}[{}] (\"{}\")", where, i, l.name);
    if (l.name.empty()) throw InvalidInput(fmt::format("{}[{}].name: empty; every layer needs a name", where, i));
    if (!std::isfinite(l.thickness) || l.thickness <= 0) {
      throw InvalidInput(fmt::format("{}.thickness: {} um; expected a positive thickness", at, l.thickness * 1e6));
    }
    if (!std::isfinite(l.youngs_modulus) || l.youngs_modulus <= 0) {
      throw InvalidInput(fmt::format("{}.youngs_modulus: {} Pa; expected a positive value", at, l.youngs_modulus));
    }
    if (!std::isfinite(l.poisson_ratio) || l.poisson_ratio <= -1 || l.poisson_ratio >= 0.5) {
      throw InvalidInput(fmt::format("{}.poisson_ratio: {}; expected a value in (-1, 0.5)", at, l.poisson_ratio));
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (layers[j].name == l.name) {
        throw InvalidInput(fmt::format("{}.name: \"{}\" is also layer {}; layer names must be unique", at, l.name, j));
      }
    }
  }
}

}  // namespace needlekit::materials
