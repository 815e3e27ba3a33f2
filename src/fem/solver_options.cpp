// Names of the solver's enums and the validation of its options.
#include "needlekit/core/errors.hpp"
#include "needlekit/fem/parallel_session.hpp"
#include "needlekit/fem/solver_options.hpp"
#include "needlekit/fem/solver_parameters.hpp"

namespace needlekit::fem {

std::string_view to_string(MaterialLaw law) { return name_of(kMaterialLawNames, law); }
std::string_view to_string(ElementOrder order) { return name_of(kElementOrderNames, order); }
std::string_view to_string(ContactModel contact) { return name_of(kContactModelNames, contact); }
std::string_view to_string(LinearSolver solver) { return name_of(kLinearSolverNames, solver); }
std::string_view to_string(BoundaryCondition c) { return name_of(kBoundaryConditionNames, c); }
std::string_view to_string(VolumetricFormulation f) { return name_of(kVolumetricFormulationNames, f); }
std::string_view to_string(SolverBackend b) { return name_of(kSolverBackendNames, b); }

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
  check_ranges(kSolverParameters, *this, "solver");  // each number against its row's range
  if (!backend_compiled(backend))
    throw InvalidInput("solver backend = \"" + std::string(to_string(backend)) +
                       "\": this build has no such backend, expected " + compiled_backend_names() +
                       " (PETSc: configure with -DNEEDLEKIT_WITH_PETSC=ON)");
  if (volumetric == VolumetricFormulation::NodalAverage) {
    if (law != MaterialLaw::NeoHookean)
      throw InvalidInput("solver volumetric = \"nodal-average\" averages the neo-Hookean law's volumetric term: "
                         "expected law = \"neo-hookean\" (or volumetric = \"element\")");
    if (order != ElementOrder::Linear)
      throw InvalidInput("solver volumetric = \"nodal-average\" is for linear tetrahedra: expected element = "
                         "\"linear\" (quadratic tetrahedra integrate the volume per element)");
  }
  if (rezone && (contact != ContactModel::Surface || order != ElementOrder::Linear))
    throw InvalidInput("solver rezone = true meshes the deformed tissue anew under surface contact with linear "
                       "tetrahedra: expected contact = \"surface\" and element = \"linear\" (or rezone = false)");
}

}  // namespace needlekit::fem
