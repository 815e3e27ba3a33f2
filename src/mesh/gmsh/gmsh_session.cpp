#include "gmsh_session.hpp"

#include <exception>
#include <stdexcept>

namespace needlekit::mesh::detail {
namespace {

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

GmshSession::GmshSession() : lock_(gmsh_mutex()) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 2);  // errors and warnings, into the logger only
  gmsh::logger::start();
}

GmshSession::~GmshSession() {
  try {
    gmsh::logger::stop();
    gmsh::finalize();
  } catch (...) {
  }
}

void GmshSession::set_option(const std::vector<std::string>& names, double value) {
  for (const std::string& name : names) {
    try {
      gmsh::option::setNumber(name, value);
      return;
    } catch (...) {
    }
  }
  throw std::logic_error("Gmsh knows none of the options " + names.front());
}

std::string GmshSession::last_error() {
  std::string error;
  try {
    gmsh::logger::getLastError(error);
  } catch (...) {
  }
  return error;
}

std::string gmsh_error_message() {
  std::string what;
  try {
    throw;
  } catch (const std::string& s) {
    what = s;
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
    what = "unknown error";
  }
  const std::string logged = GmshSession::last_error();
  if (!logged.empty() && logged != what) what += what.empty() ? logged : " (" + logged + ")";
  return what;
}

}  // namespace needlekit::mesh::detail
