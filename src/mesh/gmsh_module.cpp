#include "gmsh_module.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "needlekit/core/errors.hpp"

// Set by CMakeLists.txt: the module's file name and where `cmake --install` puts it.
#ifndef NEEDLEKIT_GMSH_MODULE_NAME
#error "NEEDLEKIT_GMSH_MODULE_NAME is not defined"
#endif
#ifndef NEEDLEKIT_GMSH_MODULE_INSTALLED
#error "NEEDLEKIT_GMSH_MODULE_INSTALLED is not defined"
#endif

namespace needlekit::mesh::detail {
namespace {

// The module by its file name through the dynamic loader first (LD_LIBRARY_PATH, then the RUNPATH of the program:
// the build tree's lib/ for the build's programs, $ORIGIN/../lib for the installed tool, the installed lib/ for
// programs linked with find_package(needlekit)), then at the installed path (a program without that RUNPATH).
const GmshModule* load_gmsh_module() {
  const std::vector<std::string> candidates = {NEEDLEKIT_GMSH_MODULE_NAME, NEEDLEKIT_GMSH_MODULE_INSTALLED};
  std::string tried;
  for (const std::string& candidate : candidates) {
    void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* error = dlerror();
      tried += fmt::format("\n  {}: {}", candidate, error ? error : "not found");
      continue;
    }
    using Entry = const GmshModule* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, "needlekit_gmsh_module_v1"));
    if (entry == nullptr) {
      tried += fmt::format("\n  {}: no needlekit_gmsh_module_v1", candidate);
      dlclose(handle);
      continue;
    }
    const GmshModule* module = entry();
    if (std::string(module->version) != NEEDLEKIT_VERSION) {
      tried += fmt::format("\n  {}: built by needlekit {}, expected {}", candidate, module->version, NEEDLEKIT_VERSION);
      dlclose(handle);
      continue;
    }
    return module;  // never closed: Gmsh keeps global state until the process ends
  }
  throw std::runtime_error(
      fmt::format("cannot open needlekit's Gmsh module, which meshing and .msh import need; tried:{}", tried));
}

}  // namespace

const GmshModule& gmsh_module() {
  static const GmshModule* const module = load_gmsh_module();
  return *module;
}

std::mutex& gmsh_call_mutex() {
  static std::mutex m;
  return m;
}

void throw_if_failed(const GmshError& error) {
  switch (error.kind) {
    case GmshErrorKind::None:
      return;
    case GmshErrorKind::InvalidInput:
      throw InvalidInput(error.message);
    case GmshErrorKind::IoError:
      throw IoError(error.message);
    case GmshErrorKind::Failure:
      break;
  }
  throw std::runtime_error(error.message);
}

}  // namespace needlekit::mesh::detail
