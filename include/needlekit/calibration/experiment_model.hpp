// One experiment of a calibration as a function of the fitted parameters: the case file with the parameters put in,
// run through the library (design file: the analytic model of §4.2; indent case: the FE curve; insert case: the
// complete insertion curve of §3.4-3.6), and its residuals against the measured data.
//
// Set-up work is done once: the FE tissue mesh (the fitted keys never change the geometry, so the mesh is reused by
// every run, and Gmsh, which is not thread-safe, runs only here) and the post-puncture loads of the needle.
// predict() is const and thread-safe: several runs may go at once.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/calibration/calibration_problem.hpp"
#include "needlekit/insertion/force_curve.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/insertion_case.hpp"

namespace needlekit::calibration {

// What the model says for one parameter vector.
struct Prediction {
  bool ok = false;
  std::string failure;                                // why not ok (e.g. the FE converged no load step)
  insertion::ForceDepthCurve curve;                   // design files: empty
  std::optional<insertion::PuncturePoint> puncture;  // design files: depth = deformation d, force = F(A)
  std::string status;                                 // the run's own status and reason, for reports
  std::string reason;                                 // FE runs: why the run ended (IndentationResult::reason)
  std::vector<std::string> notes;                     // e.g. a puncture-force law used outside its range
  int model_runs = 0;                                 // FE runs (0 for design files)
  int elements = 0;                                   // tetrahedra of the FE mesh (0 for design files)
  int warm_started_steps = 0;                         // FE load steps that started from a warm start
  bool stopped = false;                               // the FE run was stopped on request (not ok)
  // The FE run's displacement field per load step, when asked: the warm start of the finite-difference runs around
  // this point.
  std::shared_ptr<const std::vector<insertion::StepDisplacement>> displacements;
};

class ExperimentModel {
public:
  // Throws InvalidInput naming the case file and key when the case does not read with the initial values, or when
  // the measured curve goes deeper than the model's curve can. `mesh_scale` in (0, 1]: the FE block's element sizes
  // (size_at_tip, size_far) times this factor (the finer model of the discretisation-error estimate).
  ExperimentModel(const ExperimentSpec& experiment, const std::vector<ParameterSpec>& parameters,
                  double mesh_scale = 1.0);
  ~ExperimentModel();
  ExperimentModel(ExperimentModel&&) noexcept;

  const ExperimentSpec& experiment() const { return experiment_; }
  // Whether the model meshes its own FE block (and so can be refined by mesh_scale): FE cases without a given .msh
  // mesh or a given pre-puncture curve.
  bool meshes_block() const;
  // Whether the parameter's path exists in this experiment's case.
  bool uses(std::size_t parameter) const { return uses_[parameter]; }
  // The case text with the parameters put in: SI at full precision, or in the units the user gave them (written
  // calibrated cases) with `significant_digits`.
  std::string case_text(const std::vector<double>& values, bool user_units = false, int significant_digits = 17) const;

  // `warm_start`: the displacements of an earlier prediction of this experiment (FE cases: its load steps start
  // from them); `keep_displacements`: return this run's in Prediction::displacements; `stop_requested`: polled at
  // every Newton iteration of the FE run, true stops it (Prediction::stopped).
  Prediction predict(const std::vector<double>& values,
                     const std::vector<insertion::StepDisplacement>* warm_start = nullptr,
                     bool keep_displacements = false, const std::function<bool()>& stop_requested = {}) const;

  // Weighted relative residuals: for each measured curve sample (F_model(d_i) − F_i)/max(|F_i|, 0.05·max|F|), then
  // (d_model − d)/d and (F_model − F)/F of the puncture point. No model puncture: the model's last sample stands in.
  std::size_t residual_count() const { return residual_count_; }
  std::vector<double> residuals(const Prediction& prediction) const;

private:
  struct Setup;
  // The complete curve of an insert case from its pre-puncture curve (Algorithm 3.1's cutting force after it).
  Prediction cutting(Prediction prediction, const io::InsertionSettings& settings, const insertion::PrePunctureCurve& pre,
                     const std::optional<insertion::PuncturePoint>& fe_puncture) const;
  ExperimentSpec experiment_;
  std::vector<ParameterSpec> parameters_;
  std::vector<bool> uses_;
  std::size_t residual_count_ = 0;
  double force_scale_ = 1;  // N, the largest measured force
  std::unique_ptr<Setup> setup_;
};

// Linear interpolation of a curve at `depth` (the first of repeated depths: the force before a drop); the end values
// beyond its ends.
double force_at(const insertion::ForceDepthCurve& curve, double depth);

}  // namespace needlekit::calibration
