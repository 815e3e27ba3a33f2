// The averaged-pressure puncture law (insertion/averaged_contact_pressure.hpp) on indenters whose surface contact
// converges with the mesh: a flat punch and a cone with a rounded tip, quarter models of a structured block (the
// contact field mirrored to the whole disc, so that the law reads the whole punch). What the law predicts, checked:
//  - similarity: a punch twice the size in a tissue twice as stiff, with l and p_c doubled too, punctures at the same
//    depth over radius and the same pressure over modulus (p/E is a function of l/a and p_c/E only);
//  - size: at fixed l and p_c the puncture pressure falls as the punch grows (the same as rising with l at a fixed
//    punch, by the similarity), as Sneddon's field does (unit test: p_m = 1.27 p_c √(l/a) for l << a);
//  - shape: a flat punch needs a far higher pressure over its section than a rounded sharp tip of the same diameter
//    (Shergold & Fleck 2005);
//  - mesh: the puncture depth on two meshes of the flat punch (4 and 6 cells across its radius) differs < 10 %.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fem_test_support.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/averaged_contact_pressure.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/puncture_criteria.hpp"

using namespace needlekit;
using namespace needlekit::fem::test_support;

namespace {

constexpr double kA = 100e-6;  // m, the punch radius of the smaller runs
constexpr double kE = 0.2e6;   // Pa
constexpr double kNu = 0.3;    // no locking of the linear tetrahedra
constexpr double kCriticalOverE = 0.2;  // p_c / E

enum class Tip { Flat, RoundedCone };

// The needle of radius 1.05 a (no tissue node exactly on its rim), tip at the block's corner (the quarter model's
// axis), as run_indentation places it: its edges rounded (the flat punch's by 2 % of a, the cone's tip by 0.24 a).
fem::Indenter placed_tip(Tip tip, double a, double corner) {
  insertion::IndentationCase c;
  const double radius = 1.05 * a;
  c.geometry = tip == Tip::Flat ? needle::NeedleGeometry{needle::Shape::Cylinder, 2 * radius, 2 * radius, 0, 3 * a}
                                : needle::NeedleGeometry{needle::Shape::Cone, 0.5 * a, 2 * radius, 0, 3 * a};
  c.edge_radius = tip == Tip::Flat ? 0.02 * a : 0.24 * a;
  c.needle_mesh = {256, 8};
  c.needle = needle::needle_surface_mesh(*c.geometry, c.needle_mesh);
  c.needles = {insertion::NeedleSite{{corner, corner}, 0.0}};
  c.solver.contact = fem::ContactModel::Surface;
  return insertion::placed_indenters(c).front();
}

// The quarter model's contact points mirrored in both symmetry planes: a node on a plane has half its area and force
// in the quarter and meets its image there, so the sums are the whole punch's.
std::vector<insertion::ContactPoint> whole_contact(const fem::QuasiStaticSolver& solver, double corner) {
  std::vector<insertion::ContactPoint> points;
  for (std::size_t n = 0; n < solver.nodes().size(); ++n) {
    if (solver.contact_flag()[n] == 0) continue;
    const double area = solver.top_node_area()[n];
    const Eigen::Vector3d& x = solver.nodes()[n];
    for (double sx : {1.0, -1.0})
      for (double sy : {1.0, -1.0})
        points.push_back({{corner + sx * (x.x() - corner), corner + sy * (x.y() - corner), x.z()},
                          solver.contact_pressure()[n] * area, area});
  }
  return points;
}

struct PunchRun {
  std::vector<std::vector<insertion::PunctureSample>> samples;  // per material length, per step (whole punch)
};

// `steps` equal steps to `depth`; after each one the whole punch's force and p̄_l for each l of `lengths`.
PunchRun indent(Tip tip, double a, double youngs, int core, double depth, int steps, const std::vector<double>& lengths) {
  const double extent = 6 * a, corner = -extent / 2;
  fem::SolverOptions o;
  o.law = fem::MaterialLaw::NeoHookean;
  o.contact = fem::ContactModel::Surface;
  o.boundary = fem::BoundaryCondition::QuarterSymmetry;
  fem::QuasiStaticSolver solver(quarter_punch_block(a, extent, core, youngs, kNu), {placed_tip(tip, a, corner)}, o);
  PunchRun run;
  run.samples.resize(lengths.size());
  for (int k = 1; k <= steps; ++k) {
    const double d = depth * k / steps;
    const fem::StepResult r = solver.advance_to(d);
    EXPECT_TRUE(r.converged) << r.reason;
    if (!r.converged) break;
    const auto points = whole_contact(solver, corner);
    for (std::size_t i = 0; i < lengths.size(); ++i) {
      run.samples[i].push_back({d, 4 * r.indenter_force[0], 0.0, 0.0,
                                insertion::averaged_peak_pressure(points, lengths[i])});
    }
  }
  return run;
}

insertion::PuncturePoint puncture(const std::vector<insertion::PunctureSample>& samples, double critical) {
  const auto point = insertion::averaged_pressure_puncture(samples, critical);
  EXPECT_TRUE(point.has_value()) << "no puncture; last p̄ = " << (samples.empty() ? 0 : samples.back().averaged_pressure);
  return point.value_or(insertion::PuncturePoint{});
}

// Pa: the force at puncture over the needle's section (radius 1.05 a).
double section_pressure(const insertion::PuncturePoint& p, double a) { return p.force / (M_PI * 1.1025 * a * a); }

TEST(AveragedPressurePuncture, SameDimensionlessGroupsSamePuncture) {
  const double pc = kCriticalOverE * kE;
  const PunchRun small_punch = indent(Tip::Flat, kA, kE, 4, 0.32 * kA, 4, {0.5 * kA});
  const PunchRun large_punch = indent(Tip::Flat, 2 * kA, 2 * kE, 4, 0.64 * kA, 4, {kA});
  const auto p1 = puncture(small_punch.samples[0], pc), p2 = puncture(large_punch.samples[0], 2 * pc);
  EXPECT_NEAR(p2.depth / (2 * kA), p1.depth / kA, 1e-3 * p1.depth / kA);
  EXPECT_NEAR(section_pressure(p2, 2 * kA) / (2 * kE), section_pressure(p1, kA) / kE, 1e-3 * section_pressure(p1, kA) / kE);
  RecordProperty("puncture_depth_over_a", std::to_string(p1.depth / kA));
  RecordProperty("puncture_pressure_over_E", std::to_string(section_pressure(p1, kA) / kE));
}

TEST(AveragedPressurePuncture, PressureFallsAsThePunchGrowsAndTheMeshConverges) {
  // At a fixed punch, l = a/2 and 2.2a: by the similarity above, the same as punches of radius 2a and a/2.2 at a fixed
  // l. The wide disc holds the whole contact: there the law is the mean pressure F/A reaching p_c. On Sneddon's field
  // the half-radius disc at the rim averages 1.20 p_m (unit test's sampling), so the law predicts the larger punch to
  // puncture at 1/1.20 = 0.83 of the smaller one's pressure.
  const double pc = kCriticalOverE * kE;
  const std::vector<double> lengths{0.5 * kA, 2.2 * kA};
  const PunchRun coarse = indent(Tip::Flat, kA, kE, 4, 0.32 * kA, 4, lengths);
  const PunchRun fine = indent(Tip::Flat, kA, kE, 6, 0.32 * kA, 4, lengths);
  std::vector<double> pressure;
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    const auto p = puncture(fine.samples[i], pc);
    pressure.push_back(section_pressure(p, kA));
    const auto q = puncture(coarse.samples[i], pc);
    EXPECT_NEAR(q.depth / p.depth, 1.0, 0.10) << "puncture depth on 4 and 6 cells across a, l = " << lengths[i];
    RecordProperty("depth_ratio_coarse_fine_l" + std::to_string(i), std::to_string(q.depth / p.depth));
    RecordProperty("pressure_over_pc_l" + std::to_string(i), std::to_string(pressure.back() / pc));
  }
  EXPECT_NEAR(pressure[0] / pressure[1], 1 / 1.20, 0.08) << "a larger punch (smaller l/a) punctures at a lower pressure";
  EXPECT_NEAR(pressure[1] / pc, 1.0, 0.2) << "a disc holding the whole contact: F/A = p_c (A: the nodes' areas)";
}

TEST(AveragedPressurePuncture, AFlatPunchNeedsAHigherPressureThanARoundedSharpTip) {
  const double pc = kCriticalOverE * kE, l = 0.5 * kA;
  const PunchRun flat = indent(Tip::Flat, kA, kE, 4, 0.32 * kA, 4, {l});
  const PunchRun sharp = indent(Tip::RoundedCone, kA, kE, 4, 0.32 * kA, 4, {l});
  const double p_flat = section_pressure(puncture(flat.samples[0], pc), kA);
  const double p_sharp = section_pressure(puncture(sharp.samples[0], pc), kA);
  EXPECT_LT(p_sharp, 0.25 * p_flat) << "Shergold & Fleck 2005: the blunt punch needs the higher pressure";
  RecordProperty("flat_pressure_over_pc", std::to_string(p_flat / pc));
  RecordProperty("sharp_pressure_over_pc", std::to_string(p_sharp / pc));
}

}  // namespace
