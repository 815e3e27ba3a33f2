// Dissertation §6.4: the published buckling and bending forces of the fitted patches follow from F(A) and the
// insertion angle θ (Eqs 5.3, 5.4): for each published pair, θ from the buckling force gives the bending force.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "needlekit/analysis/bending.hpp"
#include "needlekit/analysis/puncture_model.hpp"
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit {
namespace {

TEST(Section_6_4, PublishedPatchForcesFollowFromThePunctureForceAndTheAngle) {
  std::ifstream in(std::string(NEEDLEKIT_TEST_DATA_DIR) + "/regression/section_6_4_forces.json");
  const nlohmann::json data = nlohmann::json::parse(in);
  const double d1 = data["tip_diameter_um"].get<double>() * 1e-6;
  const double force =
      analysis::puncture_force(needle::tip_area({needle::Shape::Cylinder, d1, d1, 0, 400e-6}),
                               analysis::skin_puncture_model());
  EXPECT_NEAR(force, data["puncture_force_N"].get<double>(), 5e-5);
  for (const auto& c : data["cases"]) {
    SCOPED_TRACE(c["name"].get<std::string>());
    for (const char* end : {"min", "max"}) {
      const double buckling = c[std::string("buckling_") + end].get<double>();
      const double bending = c[std::string("bending_") + end].get<double>();
      // θ from the bending force (the more precise of the two when θ is small), then both forces.
      const double theta = std::atan(bending / force);
      EXPECT_NEAR(analysis::angled_buckling_force(force, theta), buckling, 6e-5) << end;
      // θ from the buckling force (precise when θ is large), then the bending force.
      const double from_buckling = std::acos(std::min(1.0, force / buckling));
      EXPECT_NEAR(analysis::angled_bending_force(force, from_buckling), bending, c["tolerance"].get<double>()) << end;
    }
  }
}

}  // namespace
}  // namespace needlekit
