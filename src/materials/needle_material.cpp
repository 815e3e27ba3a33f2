#include "needlekit/materials/needle_material.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/materials/preset_key.hpp"

namespace needlekit::materials {
namespace {

struct Preset {
  std::string_view key;
  NeedleMaterial material;
};

// Allowable stress σ (Eqs 5.7/5.8): the dissertation never gives it. We use the yield (or, for brittle silicon, the
// fracture) strength divided by a safety factor of 1.5, the common design factor for static loads with well-known
// materials (Mott, Machine Elements in Mechanical Design, 4th ed., §5-7). Users can override it per design.
constexpr double kAllowableFactor = 1.0 / 1.5;

const std::vector<Preset>& presets() {
  static const std::vector<Preset> table = {
      {"silicon",
       {"silicon", 169e9, 7.0e9, 7.0e9 * kAllowableFactor,
        "E = 169 GPa: dissertation §6.3 (Si <110>, Hopcroft et al., J. MEMS 19(2), 2010); fracture strength 7 GPa: "
        "Petersen, Proc. IEEE 70(5), 1982; allowable = strength/1.5"}},
      {"su-8",
       {"SU-8", 4.02e9, 60e6, 60e6 * kAllowableFactor,
        "E = 4.02 GPa, tensile strength 60 MPa: MicroChem SU-8 2000 data sheet (dissertation §6.4.1 says 4-5 GPa); "
        "allowable = strength/1.5"}},
      {"plga",
       {"PLGA", 1.9e9, 45e6, 45e6 * kAllowableFactor,
        "PLGA 50:50, E = 1.9 GPa, tensile strength 45 MPa: Middleton & Tipton, Biomaterials 21, 2000 (Table 1 range "
        "41-55 MPa); allowable = strength/1.5"}},
      {"pla",
       {"PLA", 3.5e9, 50e6, 50e6 * kAllowableFactor,
        "PLLA, E = 3.5 GPa, tensile strength 50 MPa: Park, Allen & Prausnitz, J. Control. Release 104, 2005; "
        "Middleton & Tipton 2000; allowable = strength/1.5"}},
      {"pga",
       {"PGA", 7.0e9, 60e6, 60e6 * kAllowableFactor,
        "E = 7.0 GPa, tensile strength 60 MPa (lower bound of 60-100 MPa): Middleton & Tipton, Biomaterials 21, "
        "2000; allowable = strength/1.5"}},
      {"titanium",
       {"titanium", 114e9, 880e6, 880e6 * kAllowableFactor,
        "Ti-6Al-4V annealed, E = 114 GPa, yield 880 MPa: ASM Handbook vol. 2 (1990); allowable = yield/1.5"}},
      {"stainless-steel",
       {"stainless steel", 193e9, 290e6, 290e6 * kAllowableFactor,
        "AISI 316L annealed, E = 193 GPa, yield 290 MPa: ASM Handbook vol. 1 (1990); allowable = yield/1.5"}},
      {"e-shell-200",
       {"e-Shell 200", 2.4e9, 55e6, 55e6 * kAllowableFactor,
        "E = 2.4 GPa: Gittard et al., Biofabrication 1, 2009 (the dissertation §2.4.2 prints '2400 GPa' for 2400 "
        "MPa); tensile strength ~55 MPa: EnvisionTEC e-Shell 200 data sheet (approximate); allowable = strength/1.5"}},
      {"e-shell-300",
       {"e-Shell 300", 2.4e9, 55e6, 55e6 * kAllowableFactor,
        "e-Shell 300 (dissertation §6.2 arrays): E ~2.4 GPa, tensile strength ~55 MPa, EnvisionTEC e-Shell 300 "
        "data sheet (approximate; the same acrylate family as e-Shell 200); allowable = strength/1.5"}},
  };
  return table;
}

}  // namespace

std::vector<std::string> material_preset_names() {
  std::vector<std::string> names;
  for (const auto& p : presets()) names.emplace_back(p.key);
  return names;
}

NeedleMaterial material_preset(std::string_view name, std::string_view what) {
  const std::string wanted = preset_key(name);
  for (const auto& p : presets()) {
    if (preset_key(p.key) == wanted) return p.material;
  }
  throw InvalidInput(fmt::format("{}: unknown material '{}', expected one of: {} (or an inline table with "
                                 "youngs_modulus)",
                                 what, name, fmt::join(material_preset_names(), ", ")));
}

void validate(const NeedleMaterial& m, std::string_view where) {
  auto check = [&](double v, std::string_view key) {
    if (!std::isfinite(v) || v <= 0) {
      throw InvalidInput(fmt::format("{}.{}: {} Pa must be a positive finite value", where, key, v));
    }
  };
  check(m.youngs_modulus, "youngs_modulus");
  if (m.yield_strength) check(*m.yield_strength, "yield_strength");
  if (m.allowable_stress) check(*m.allowable_stress, "allowable_stress");
}

}  // namespace needlekit::materials
