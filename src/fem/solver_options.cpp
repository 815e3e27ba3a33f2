// Names of the solver's enums and the validation of its options.
#include <cmath>
#include <sstream>

#include "needlekit/core/errors.hpp"
#include "needlekit/fem/parallel_session.hpp"
#include "needlekit/fem/solver_options.hpp"

namespace needlekit::fem {

std::string to_string(MaterialLaw law) { return std::string(name_of(kMaterialLawNames, law)); }
std::string to_string(ElementOrder order) { return std::string(name_of(kElementOrderNames, order)); }
std::string to_string(ContactModel contact) { return std::string(name_of(kContactModelNames, contact)); }
std::string to_string(LinearSolver solver) { return std::string(name_of(kLinearSolverNames, solver)); }
std::string to_string(BoundaryCondition c) { return std::string(name_of(kBoundaryConditionNames, c)); }
std::string to_string(VolumetricFormulation f) { return std::string(name_of(kVolumetricFormulationNames, f)); }
std::string to_string(SolverBackend b) { return std::string(name_of(kSolverBackendNames, b)); }

MaterialLaw material_law_from_string(const std::string& t, const std::string& what) {
  if (t == "st-venant-kirchhoff") return MaterialLaw::StVenantKirchhoff;  // the long name, kept as an alias
  return value_of(kMaterialLawNames, t, what);
}
ElementOrder element_order_from_string(const std::string& t, const std::string& what) {
  return value_of(kElementOrderNames, t, what);
}
ContactModel contact_model_from_string(const std::string& t, const std::string& what) {
  return value_of(kContactModelNames, t, what);
}
BoundaryCondition boundary_condition_from_string(const std::string& t, const std::string& what) {
  return value_of(kBoundaryConditionNames, t, what);
}
VolumetricFormulation volumetric_formulation_from_string(const std::string& t, const std::string& what) {
  return value_of(kVolumetricFormulationNames, t, what);
}

namespace {
template <class T>
void check(bool ok, const char* field, T value, const char* expected) {
  if (ok) return;
  std::ostringstream s;
  s << "solver " << field << " = " << value << ": expected " << expected;
  throw InvalidInput(s.str());
}
}  // namespace

int newton_iteration_limit(const SolverOptions& o) {
  if (o.max_iterations > 0) return o.max_iterations;
  return o.contact == ContactModel::Surface ? kSurfaceContactNewtonIterations : kNewtonIterations;
}

bool nodal_average_possible(const SolverOptions& o) {
  return o.law == MaterialLaw::NeoHookean && o.order == ElementOrder::Linear &&
         o.volumetric != VolumetricFormulation::Element;
}

bool nodal_average_applies(const SolverOptions& o, double poisson_ratio) {
  return nodal_average_possible(o) &&
         (o.volumetric == VolumetricFormulation::NodalAverage || poisson_ratio >= kNearlyIncompressible);
}

void SolverOptions::validate() const {
  check(residual_tolerance > 0 && residual_tolerance < 1, "residual_tolerance", residual_tolerance, "(0, 1)");
  check(displacement_tolerance > 0 && displacement_tolerance < 1, "displacement_tolerance", displacement_tolerance,
        "(0, 1)");
  check(energy_tolerance > 0 && energy_tolerance < 1, "energy_tolerance", energy_tolerance, "(0, 1)");
  check(max_iterations >= 0, "max_iterations", max_iterations, ">= 0");
  check(max_cutbacks >= 0, "max_cutbacks", max_cutbacks, ">= 0");
  check(penalty_factor > 0, "penalty_factor", penalty_factor, "> 0");
  check(penetration_tolerance > 0 && penetration_tolerance < 1, "penetration_tolerance", penetration_tolerance,
        "(0, 1)");
  check(max_augmentations >= 0, "max_augmentations", max_augmentations, ">= 0");
  check(friction >= 0 && std::isfinite(friction), "friction", friction, ">= 0");
  check(boundary_tolerance >= 0, "boundary_tolerance", boundary_tolerance, ">= 0");
  check(max_reuse_iterations >= 1, "max_reuse_iterations", max_reuse_iterations, ">= 1");
  check(linear_tolerance > 0 && linear_tolerance < 1, "linear_tolerance", linear_tolerance, "(0, 1)");
  check(threads >= 0, "threads", threads, ">= 0");
  check(volumetric_stabilization >= 0 && std::isfinite(volumetric_stabilization), "volumetric_stabilization",
        volumetric_stabilization, ">= 0");
  check(two_grid_refresh_iterations >= 1, "two_grid_refresh_iterations", two_grid_refresh_iterations, ">= 1");
  if (!backend_compiled(backend))
    throw InvalidInput("solver backend = \"" + to_string(backend) + "\": this build has no such backend, expected " +
                       compiled_backend_names() + " (PETSc: configure with -DNEEDLEKIT_WITH_PETSC=ON)");
  if (volumetric == VolumetricFormulation::NodalAverage) {
    if (law != MaterialLaw::NeoHookean)
      throw InvalidInput("solver volumetric = \"nodal-average\" averages the neo-Hookean law's volumetric term: "
                         "expected law = \"neo-hookean\" (or volumetric = \"element\")");
    if (order != ElementOrder::Linear)
      throw InvalidInput("solver volumetric = \"nodal-average\" is for linear tetrahedra: expected element = "
                         "\"linear\" (quadratic tetrahedra integrate the volume per element)");
  }
}

}  // namespace needlekit::fem
