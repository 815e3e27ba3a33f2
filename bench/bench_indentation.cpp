// Benchmarks of the FE indentation (issue 3): the default skin block (3000 x 3000 x 1150 um, SC 20 um / EP to
// 160 um / DM, 100 MPa / 0.134 MPa / 0.08 MPa, nu = 0.4) indented by a 230 um flat cylinder, 20 load steps to
// 200 um, linear tetrahedra, neo-Hookean, the dissertation's tip-node contact. The argument is the target number of
// tetrahedra in thousands (100, 300, 1000).
// BM_SkinIndentation meshes at the sizes directly and solves as "auto" does (from 25k estimated tetrahedra the
// two-grid solver on the block meshed again at three times the sizes; factorizations then counts the coarse
// operator's);
// BM_SkinIndentationCholeskyCg is the same with CHOLMOD and CG on reused factorizations; BM_SkinIndentationSplit
// meshes at twice the sizes and splits every tet into eight (the two-grid solver on the nested coarse level). The
// label names the linear solver. Run one size per process (peak RSS):
//   build/bin/needlekit_bench --benchmark_filter='BM_SkinIndentationSplit/300/'
// Meshing alone is BM_SkinBlockMesh (bench_tissue_mesh.cpp). Counters: tets, dofs, steps_done, mesh_s, setup_s,
// newton_iterations, factorizations, cg_iterations, assembly_s_per_iteration, solve_s_per_iteration, total_s,
// force_N (at the last step), peak_rss_GB.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "needlekit/insertion/indentation.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"
#include "skin_block_sizes.hpp"

using namespace needlekit;

namespace {

double peak_rss_gigabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / (1024.0 * 1024.0);  // ru_maxrss is in KiB on Linux
}

// Element sizes for about `thousands` x 1000 tetrahedra (skin_block_sizes.hpp).
mesh::LayeredBlockOptions skin_block(double thousands) {
  return bench::skin_block_options(thousands <= 100 ? 0 : thousands <= 300 ? 1 : 2);
}

// The same block meshed at twice the sizes and split into eight (mesh::LayeredBlockOptions::split), which gives the
// solver its two-grid solver. Sizes for about the same element counts: the direct sizes times 1.35 (100k), 1.13
// (300k: 297k tetrahedra), 1.03 (1M), and the thin-layer cap scaled alike.
mesh::LayeredBlockOptions split_skin_block(double thousands) {
  mesh::LayeredBlockOptions block = skin_block(thousands);
  const double scale = thousands <= 100 ? 1.35 : thousands <= 300 ? 1.13 : 1.03;
  block.size_at_site *= scale;
  block.size_far *= scale;
  block.thin_layer_size_factor *= scale;
  block.split = true;
  return block;
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void skin_indentation(benchmark::State& state, const mesh::LayeredBlockOptions& block,
                      fem::VolumetricFormulation volumetric = fem::VolumetricFormulation::Automatic,
                      double depth = 200e-6, int steps = 20,
                      fem::LinearSolver linear_solver = fem::LinearSolver::Automatic) {
  insertion::IndentationCase c;
  c.name = "bench";
  const needle::NeedleGeometry cylinder{needle::Shape::Cylinder, 230e-6, 230e-6, 0, 1000e-6};
  c.geometry = cylinder;
  c.needle = needle::needle_surface_mesh(cylinder);
  c.block = block;
  c.depth = depth;
  c.steps = steps;
  c.solver.law = fem::MaterialLaw::NeoHookean;
  c.solver.contact = fem::ContactModel::TipNodes;
  c.solver.order = fem::ElementOrder::Linear;
  c.solver.volumetric = volumetric;
  c.solver.linear_solver = linear_solver;
  insertion::IndentationResult result;
  const double cpu_start = process_cpu_seconds();
  for (auto _ : state) {
    result = insertion::run_indentation(c);
    benchmark::DoNotOptimize(result);
  }
  double assembly = 0, solve = 0;
  int iterations = 0, factorizations = 0, cg_iterations = 0;
  for (const insertion::IndentationStep& step : result.steps) {
    assembly += step.assembly_seconds;
    solve += step.solve_seconds;
    iterations += step.newton_iterations;
    factorizations += step.factorizations;
    cg_iterations += step.linear_iterations;
  }
  state.counters["tets"] = result.elements;
  state.counters["dofs"] = result.dofs;
  state.counters["steps_done"] = static_cast<double>(result.steps.size());
  state.counters["mesh_s"] = result.mesh_seconds;
  state.counters["setup_s"] = result.setup_seconds;
  state.counters["newton_iterations"] = iterations;
  state.counters["factorizations"] = factorizations;
  state.counters["cg_iterations"] = cg_iterations;
  state.counters["assembly_s_per_iteration"] = iterations ? assembly / iterations : 0.0;
  state.counters["solve_s_per_iteration"] = iterations ? solve / iterations : 0.0;
  state.counters["total_s"] = result.total_seconds;
  state.counters["force_N"] = result.steps.empty() ? 0.0 : result.steps.back().force;
  state.counters["peak_rss_GB"] = peak_rss_gigabytes();
  state.counters["cpu_s"] = process_cpu_seconds() - cpu_start;
  state.SetLabel(std::string(name_of(fem::kLinearSolverNames, result.linear_solver)));
  if (result.status == insertion::IndentationStatus::SolverFailed) state.SkipWithError(result.reason.c_str());
}

void BM_SkinIndentation(benchmark::State& state) {
  skin_indentation(state, skin_block(static_cast<double>(state.range(0))));
}
void BM_SkinIndentationCholeskyCg(benchmark::State& state) {
  skin_indentation(state, skin_block(static_cast<double>(state.range(0))), fem::VolumetricFormulation::Automatic,
                   200e-6, 20, fem::LinearSolver::CholeskyCg);
}
void BM_SkinIndentationSplit(benchmark::State& state) {
  skin_indentation(state, split_skin_block(static_cast<double>(state.range(0))));
}
// The Sneddon case of §6.2 with linear tetrahedra: the 230 um flat punch 50 um into the silicone phantom (E = 0.2 MPa,
// nu = 0.49, 3000 x 3000 x 1150 um, 25 um at the tip), 5 steps; argument 0: per-element volume (locks), 1: the
// nodal-averaged volume (the default for nu >= 0.45).
void BM_PhantomFlatPunch(benchmark::State& state) {
  mesh::LayeredBlockOptions block;
  block.layers = materials::tissue_preset("silicone-0.2mpa").layers;
  block.size_at_site = 25e-6, block.size_far = 250e-6, block.refinement_radius = 250e-6;
  skin_indentation(state, block,
                   state.range(0) ? fem::VolumetricFormulation::NodalAverage : fem::VolumetricFormulation::Element,
                   50e-6, 5);
}
BENCHMARK(BM_PhantomFlatPunch)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_SkinIndentationSplit)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_SkinIndentation)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_SkinIndentationCholeskyCg)->Arg(100)->Arg(300)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
