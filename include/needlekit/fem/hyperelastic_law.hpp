// Hyperelastic laws of the total-Lagrangian FE (dissertation §3.4): the second Piola-Kirchhoff stress S and its
// material tangent dS/dE as functions of the deformation gradient F, with the strain energy density W.
#pragma once
#include <Eigen/Core>
#include <string>

#include "needlekit/core/enum_table.hpp"

namespace needlekit::fem {

enum class MaterialLaw {
  StVenantKirchhoff,  // S = λ tr(E) I + 2μ E: the dissertation's S = D E (Eqs 3.3-3.5, notes' corrections).
                      // Softens and can fail under large compression.
  NeoHookean,         // compressible: W = μ/2 (I1 - 3) - μ ln J + λ/2 (ln J)^2; same small-strain limit.
};
// The names of the laws, as case files, JSON and the CLI help write them (core/enum_table.hpp).
inline constexpr EnumTable<MaterialLaw, 2> kMaterialLawNames{{
    {MaterialLaw::NeoHookean, "neo-hookean", "compressible neo-Hookean: robust under large compression"},
    {MaterialLaw::StVenantKirchhoff, "svk", "St Venant-Kirchhoff, the dissertation's S = D E (Eqs 3.3-3.5)"},
}};
std::string_view to_string(MaterialLaw law);
// Parse the names of kMaterialLawNames (and "st-venant-kirchhoff" for svk). Throws InvalidInput naming `what`.
MaterialLaw material_law_from_string(const std::string& text, const std::string& what = "law");

struct LameConstants {
  double lambda = 0;  // Pa
  double mu = 0;      // Pa, shear modulus
};
// λ = Eν/((1+ν)(1-2ν)), μ = E/(2(1+ν)): the entries of D in Eqs 3.4/3.5 (prefactor corrected per the notes).
LameConstants lame_constants(double youngs_modulus, double poisson_ratio);

struct StressResponse {
  double energy_density = 0;   // W, J/m^3 of reference volume
  Eigen::Matrix3d second_piola_kirchhoff;  // S = dW/dE, Pa
  // dS/dE in the form both laws' tangents take, C_IJKL = λ' A_IJ A_KL + μ' (A_IK A_JL + A_IL A_JK) (SVK: A = I,
  // λ' = λ, μ' = μ; neo-Hookean: A = C^-1, λ' = λ, μ' = μ - λ ln J). The element kernel contracts it with the shape
  // gradients in closed form (tet_kernel.hpp) instead of through a 6 x 6 Voigt matrix.
  double tangent_lambda = 0;                                 // λ', Pa
  double tangent_mu = 0;                                     // μ', Pa
  Eigen::Matrix3d tangent_metric = Eigen::Matrix3d::Zero();  // A, dimensionless
  bool valid = true;           // false when J = det F <= 0 (inverted; neo-Hookean: energy infinite, SVK: values
                               // still computed but the state is not physical)
};

// Green-Lagrange strain E = (F^T F - I)/2 (Eq 3.3, corrected).
Eigen::Matrix3d green_lagrange_strain(const Eigen::Matrix3d& deformation_gradient);

// S, dS/dE and W of the law at F. SVK: S = λ tr(E) I + 2μE (Eqs 3.4, 3.5). Neo-Hookean:
// S = μ(I - C^-1) + λ ln J C^-1.
StressResponse stress_response(MaterialLaw law, const LameConstants& lame, const Eigen::Matrix3d& deformation_gradient,
                               bool with_tangent = true);

// Cauchy stress σ = F S F^T / J.
Eigen::Matrix3d cauchy_stress(const Eigen::Matrix3d& deformation_gradient, const Eigen::Matrix3d& second_pk);
double von_mises_stress(const Eigen::Matrix3d& cauchy);

}  // namespace needlekit::fem
