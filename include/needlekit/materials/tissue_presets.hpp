// Tissue layer presets (dissertation §3.3.2 and §6.2) and a literature set, each with its sources. Thicknesses are
// top to bottom; a preset's last layer fills the rest of its default block height.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/materials/tissue_layer.hpp"

namespace needlekit::materials {

struct TissuePreset {
  std::string name;                    // e.g. "skin"
  std::vector<TissueLayer> layers;  // top to bottom, thicknesses sum to `height`
  double height = 0;                   // m, default block height (the dissertation's block is 1150 um)
  std::string source;                  // where every value comes from
};

// Dissertation §3.3.2: stratum corneum 20 um (E = `stratum_corneum_modulus`, 100 MPa by default; [Wu 2006],
// Biomaterials 27:785, gives 1 GPa at the extreme surface), epidermis to 160 um depth (0.134 MPa) and dermis for the
// rest of a 1150 um block (0.08 MPa) [L'Etang 2006, Ultrasonics 44:1243], nu = 0.4 for all.
std::vector<TissueLayer> skin_layers(double stratum_corneum_modulus = 100e6);

// The preset names in a stable order: skin, skin-stiff-sc, silicone-0.2mpa, silicone-0.5mpa, skin-geerligs-2011.
std::vector<std::string> tissue_preset_names();

// A preset by name (case-insensitive, '-', '_' and ' ' ignored); throws InvalidInput naming `what` and listing the
// presets if unknown.
TissuePreset tissue_preset(std::string_view name, std::string_view what = "tissue preset");

// Throws InvalidInput naming the layer (by `where`[i] and its name) and the field for an empty name, a non-positive
// or non-finite thickness or Young's modulus, or a Poisson ratio outside (-1, 0.5).
void validate(const std::vector<TissueLayer>& layers, std::string_view where = "layers");

}  // namespace needlekit::materials
