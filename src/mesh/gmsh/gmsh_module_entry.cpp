// The Gmsh module's entry point (src/mesh/gmsh_module.hpp): its functions with every exception caught and reported
// as a GmshError, so that none crosses the dlopen boundary.
#include <exception>

#include "gmsh_functions.hpp"
#include "needlekit/core/errors.hpp"

namespace needlekit::mesh::detail {
namespace {

template <class Function>
auto reporting_errors(GmshError& error, Function&& function) -> decltype(function()) {
  error = {};
  try {
    return function();
  } catch (const InvalidInput& e) {
    error = {GmshErrorKind::InvalidInput, e.what()};
  } catch (const IoError& e) {
    error = {GmshErrorKind::IoError, e.what()};
  } catch (const std::exception& e) {
    error = {GmshErrorKind::Failure, e.what()};
  } catch (...) {
    error = {GmshErrorKind::Failure, "unknown error in the Gmsh module"};
  }
  return {};
}

TetMesh layered_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers, GmshError& error) {
  return reporting_errors(error, [&] { return gmsh_layered_block(options, layers); });
}

CellBlockMesh cell_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                         const CellLayout& layout, GmshError& error) {
  return reporting_errors(error, [&] { return gmsh_cell_block(options, layers, layout); });
}

MshContents read_msh(const std::string& file, const std::vector<TissueLayer>& layers, GmshError& error) {
  return reporting_errors(error, [&] { return gmsh_read_msh(file, layers); });
}

TetMesh refill(const SurfaceToFill& surface, GmshError& error) {
  return reporting_errors(error, [&] { return gmsh_refill(surface); });
}

const GmshModule kModule{NEEDLEKIT_VERSION, &layered_block, &cell_block, &read_msh, &refill};

}  // namespace
}  // namespace needlekit::mesh::detail

extern "C" __attribute__((visibility("default"))) const needlekit::mesh::detail::GmshModule*
needlekit_gmsh_module_v1() {
  return &needlekit::mesh::detail::kModule;
}
