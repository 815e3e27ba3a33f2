// Benchmarks of the calibration (issue 13).
// BM_CalibrationCoverage: the synthetic-recovery study over 20 noise seeds (tests/support/calibration_fixture.hpp:
//   a flat 300 um punch 120 um into a 1 mm silicone layer, E = 0.2 MPa, nu = 0.3, P_c = 0.1 MPa, data made on a 30 um
//   mesh with 2 % noise, fitted on another, 36 um mesh). Counters: coverage_E, coverage_Pc (fraction of the seeds
//   whose 95 % interval holds the truth), max_error_E, max_error_Pc (largest relative error), within_3pct (seeds with
//   both within 3 %).
//     build/bin/needlekit_bench --benchmark_filter=BM_CalibrationCoverage/20  (/5: a shorter run)
// BM_CalibrateInsertion: E and P_c fitted to one complete insertion curve (the blunt bevel of §6.2 into the phantom (a sharp tip punctures at its first step whatever P_c is, so P_c would not be identifiable),
//   FE to puncture + cutting force) on a mesh of about 10k tetrahedra, from 50 % / 32 % off; the curve and its
//   puncture point are the model's own at E = 0.2 MPa, P_c = 0.663 MPa on the same mesh. (From the curve alone P_c
//   is found only through where the drop falls between samples, a step function of P_c: the fit then stalls.) Counters: tets, fe_runs, iterations, seconds,
//   error_E, error_Pc.
//     build/bin/needlekit_bench --benchmark_filter=BM_CalibrateInsertion
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "../tests/support/calibration_fixture.hpp"

using namespace needlekit;

namespace {

void BM_CalibrationCoverage(benchmark::State& state) {
  const int seeds = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const test::SyntheticIndentation synthetic = test::synthetic_indentation("bench_coverage", 30e-6, 0);
    int covered_e = 0, covered_p = 0, within = 0, converged = 0;
    double max_e = 0, max_p = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      const test::RecoveryOutcome o = test::recover(synthetic, 36e-6, static_cast<unsigned>(seed));
      converged += o.result.status == calibration::CalibrationStatus::Converged;
      covered_e += o.covered[0];
      covered_p += o.covered[1];
      within += std::abs(o.error[0]) < 0.03 && std::abs(o.error[1]) < 0.03;
      max_e = std::max(max_e, std::abs(o.error[0]));
      max_p = std::max(max_p, std::abs(o.error[1]));
    }
    state.counters["seeds"] = seeds;
    state.counters["converged"] = converged;
    state.counters["coverage_E"] = static_cast<double>(covered_e) / seeds;
    state.counters["coverage_Pc"] = static_cast<double>(covered_p) / seeds;
    state.counters["within_3pct"] = within;
    state.counters["max_error_E"] = max_e;
    state.counters["max_error_Pc"] = max_p;
  }
}
BENCHMARK(BM_CalibrationCoverage)->Arg(5)->Arg(20)->Unit(benchmark::kSecond)->Iterations(1);

const char* kInsertCase = R"(name = "blunt_bevel"
[needle]
shape = "bevel"
tip_diameter = "50 um"
base_diameter = "230 um"
length = "1000 um"
[tissue]
width = "3000 um"
length = "3000 um"
[[tissue.layers]]
name = "silicone rubber"
thickness = "1150 um"
youngs_modulus = "0.2 MPa"
poisson_ratio = 0.49
[mesh]
size_at_tip = "35 um"
size_far = "600 um"
[loading]
depth = "200 um"
steps = 10
[model]
law = "neo-hookean"
contact = "tip-nodes"
[puncture]
critical_pressure = "0.663 MPa"
[post_puncture]
stiffness = "0.2 N/mm2"
scale = 0.168
final_depth = "1000 um"
samples = 100
)";

void BM_CalibrateInsertion(benchmark::State& state) {
  const auto dir = std::filesystem::temp_directory_path() / "needlekit_bench_calibrate_insertion";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "case.toml") << kInsertCase;
  calibration::ExperimentSpec spec;
  spec.name = "truth";
  spec.case_path = dir / "case.toml";
  spec.case_text = kInsertCase;
  spec.kind = calibration::ExperimentKind::Insertion;
  spec.puncture.force = 1;
  const calibration::ExperimentModel truth(spec, {});
  const calibration::Prediction p = truth.predict({});
  state.counters["tets"] = p.elements;
  std::string csv = "depth_um,force_N\n";
  for (std::size_t i = 1; i < p.curve.depth.size(); i += 3)
    if (p.curve.depth[i] > p.curve.depth[i - 1]) csv += fmt::format("{:.9g},{:.9g}\n", p.curve.depth[i] * 1e6, p.curve.force[i]);
  std::ofstream(dir / "curve.csv") << csv;
  std::ofstream(dir / "fit.toml") << test::phantom_parameters() << R"([[experiments]]
name = "blunt bevel"
case = "case.toml"
measured = "curve.csv"
)" << fmt::format("puncture = {{ depth = \"{:.9g} um\", force = \"{:.9g} N\" }}\n", p.puncture->depth * 1e6,
                    p.puncture->force);
  for (auto _ : state) {
    const auto result = calibration::calibrate(calibration::read_calibration_file(dir / "fit.toml"));
    state.counters["fe_runs"] = result.model_runs;
    state.counters["iterations"] = result.iterations;
    state.counters["seconds"] = result.seconds;
    state.counters["converged"] = result.status == calibration::CalibrationStatus::Converged;
    state.counters["error_E"] = result.parameters[0].value / test::kTrueModulus - 1;
    state.counters["error_Pc"] = result.parameters[1].value / test::kTrueCriticalPressure - 1;
  }
}
BENCHMARK(BM_CalibrateInsertion)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
