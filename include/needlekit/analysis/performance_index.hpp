// The Microneedle Performance Index of a needle array (dissertation §4.8 Eq 4.25, §5.3 Eq 5.9):
//   PI = φ·ω·Q / (Pxy²·H),  Pxy = w/n,
// with every intermediate quantity of chapters 4–5 and, when the index is zero, the reasons why.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/analysis/buckling.hpp"
#include "needlekit/analysis/puncture_model.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::analysis {

// A square array of n × n identical needles on a patch of width w (§4.8, Fig 4.6).
struct ArrayDesign {
  needle::NeedleGeometry needle;
  materials::NeedleMaterial material;
  int needles_per_row = 10;     // n >= 1
  double width = 1e-2;          // m, w > 0
};

struct InsertionConditions {
  PunctureModel tissue = skin_puncture_model();
  double angle = 0;             // rad, θ between the needle axis and the surface normal, [0, π/2)
  double target_depth = 50e-6;  // m, T of Eq 4.23 (transdermal: 50 µm), > 0
};

struct PerformanceIndexOptions {
  BucklingOptions buckling;
  double buckling_safety_factor = 1.0;  // φ = 1 iff SF·F_buckling < P_cr, >= 1
  double bending_safety_factor = 1.0;   // ω = 1 iff SF·F_bending < P_Be, >= 1
  double gap_ratio = 0.0025;            // δ of Eqs 4.20–4.24 (only for the reported hole/gap volumes and f_v)
  double spacing_factor = 3.0;          // β of the constraint w >= β·n·D2 (§4.8); 0 disables the constraint
  // Pitch used in the index (not in the constraint). Empty: w/n. The published-compatibility switch of the
  // optimizer sets it to w_max/n (notes, "Compatibility quirk").
  std::optional<double> index_pitch;
  // false: reason and notes are left empty (every number, the status and failed_checks are the same): for
  // evaluate_many, which returns numbers and codes only and would spend most of its time formatting messages
  bool explain = true;
};

enum class PerformanceStatus {
  Ok,                  // PI > 0
  ConstraintViolated,  // a design constraint of §4.8 does not hold
  TooShort,            // L < d + T: the needle does not reach the target depth (Eq 4.23)
  Buckles,             // φ = 0 (Eq 4.5)
  Bends,               // ω = 0 (§5.2)
};
inline constexpr EnumTable<PerformanceStatus, 5> kPerformanceStatusNames{{
    {PerformanceStatus::Ok, "ok", "PI > 0"},
    {PerformanceStatus::ConstraintViolated, "constraint_violated", "a design constraint of §4.8 does not hold"},
    {PerformanceStatus::TooShort, "too_short", "L < d + T: the needle does not reach the target depth (Eq 4.23)"},
    {PerformanceStatus::Buckles, "buckles", "phi = 0 (Eq 4.5)"},
    {PerformanceStatus::Bends, "bends", "omega = 0 (§5.2)"},
}};
std::string_view to_string(PerformanceStatus status);

struct PerformanceIndexResult {
  double tip_area = 0;               // m², A
  double puncture_force = 0;         // N, F(A) of the tissue's force law (Eq 4.2 by default; signed)
  PunctureForceLawKind puncture_force_law = PunctureForceLawKind::Eq4_2;  // the law F(A) came from
  bool puncture_force_in_range = true;  // the tip lies within the law's validity range and F(A) > 0 (else a note)
  double deformation = 0;            // m, d (Eq 4.3 or the small-tip line)
  bool small_tip_branch = false;     // d came from the small-tip line d = K·A
  double cutting_depth = 0;          // m, h = L − d (Eq 4.4)
  double permeation_depth = 0;       // m, H (Eq 4.23)
  double diameter_at_surface = 0;    // m, b
  double embedded_volume = 0;        // m³ (Table 4.2)
  double q_factor = 0;               // m², Q (Table 4.4)
  double hole_volume = 0;            // m³ (Eqs 4.20–4.22)
  double gap_volume = 0;             // m³
  double pitch = 0;                  // m, Pxy = w/n
  double fractional_skin_volume = 0; // f_v (Table 4.3)
  double needle_volume = 0;          // m³, material volume of one needle
  BucklingResult buckling;           // P_cr and how it was obtained
  double buckling_force = 0;         // N, |F|/cos θ (Eqs 5.2, 5.3)
  std::optional<double> critical_bending_load;  // N, P_Be (Eqs 5.7, 5.8); empty: no allowable stress known
  double bending_force = 0;          // N, |F|·tan θ (Eq 5.4)
  bool buckling_ok = false;          // φ
  std::optional<bool> bending_ok;    // ω; empty: not assessed (no allowable stress and θ > 0)
  double performance_index = 0;      // 1/m (multiply by 1e-6 for the dissertation's 1/µm)
  PerformanceStatus status = PerformanceStatus::Ok;
  unsigned failed_checks = 0;        // bit 1 << int(PerformanceStatus) of every failed check (status is the first)
  std::string reason;                // why the index is zero (every failed check), or notes
  std::vector<std::string> notes;    // e.g. "bending not assessed: material has no allowable_stress"
};

// Evaluates one array. Throws InvalidInput for invalid geometry, material, tissue or conditions; physical
// outcomes (buckling, too short, ...) are a status with a reason. `known_tapered_factor`: as critical_buckling_load().
PerformanceIndexResult performance_index(const ArrayDesign& design, const InsertionConditions& conditions,
                                         const PerformanceIndexOptions& options = {},
                                         std::optional<double> known_tapered_factor = std::nullopt);

}  // namespace needlekit::analysis
