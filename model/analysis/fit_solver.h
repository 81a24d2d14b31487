#pragma once
// Fitting scene parameters to target observables (docs/fitting.md): bounded least squares on
// the normalised residuals r_i = (model_i - value_i) / sigma_i, chi^2 = sum r_i^2.
//
// Method: NLopt's BOBYQA (Powell 2009, derivative-free, bounds native) on the parameters scaled
// to [0, 1] over their bounds, from several starts: the scene's values first, then points drawn
// uniformly in the box, deterministic in `seed` (counterUniform, tolerance_spec.h). Why not a
// gradient method with finite differences: the observables come out of root-finding and
// bisection (FOV edges, x_p plateau edges, eye-box borders) and so are smooth only down to
// their tolerances; BOBYQA's quadratic model over a shrinking trust region tolerates that,
// and it needs no 2n extra evaluations per step. One-parameter fits use LN_COBYLA (BOBYQA needs
// n >= 2).
// Uncertainties: at the best optimum the Jacobian J = d r / d p by central differences (step a
// fraction of each bound window; one-sided at a bound), covariance C = (J^T J)^-1 from its SVD
// on the parameters scaled by their windows — NOT scaled by the reduced chi^2 (the sigmas are
// taken as the targets' real uncertainties; `uncertainty_scaled` multiplies by
// sqrt(chi^2 / dof) for when they are not). A direction with relative singular value
// s_k / s_max < rcond is undetermined: left out of C, and every parameter with weight > 0.1 in
// it is reported undetermined (no uncertainty).

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "model/analysis/fit_parameters.h"
#include "model/analysis/fit_targets.h"
#include "model/analysis/study_runner.h"

namespace fovea {

struct FitOptions {
  int starts = 3;
  std::uint64_t seed = 1;
  int max_evaluations = 0;      // per start; 0: 40 (n + 2)
  double xtol = 1e-5;           // on the parameters scaled to their windows
  double initial_step = 0.1;    // of each window
  double jacobian_step = 1e-3;  // of each window
  double rcond = 1e-6;          // relative singular value of an undetermined direction
  ObservableSettings observables;
};

struct FitParameterResult {
  FreeParameter parameter;
  double fitted = 0;
  std::optional<double> uncertainty, uncertainty_scaled;  // empty when undetermined
  bool determined = true, at_bound = false;
};

// NOLINTNEXTLINE(bugprone-exception-escape): the implicit members copy json/strings; std::bad_alloc only.
struct FitTargetResult {
  FitTarget target;
  double initial_model = 0, model = 0;
  double normalised() const { return (model - target.value) / target.sigma; }
};

struct FitStart {
  std::vector<double> from, to;
  double chi2 = 0;
  int evaluations = 0;
  std::string status;  // NLopt's result: "xtol reached", "max evaluations" ...
  // The normalised residuals at `to` when the start evaluated it (the fit reuses them for the
  // optimum instead of tracing it again); nothing otherwise.
  std::optional<std::vector<double>> residuals_at_to;
};

struct FitWarning {
  std::string parameter;  // its path; empty for the whole fit
  std::string message;
};

struct FitResult {
  std::string algorithm;
  std::vector<FitParameterResult> parameters;
  std::vector<FitTargetResult> targets;
  double chi2_initial = 0, chi2 = 0;
  int dof = 0;                              // targets - parameters
  Eigen::MatrixXd covariance, correlation;  // parameter order; NaN for undetermined ones
  std::vector<double> relative_singular_values;
  std::vector<FitWarning> warnings;
  std::vector<FitStart> starts;
  int evaluations = 0;
  Scene fitted_scene;
  // chi^2 / dof > 1: the targets scatter more than their sigmas say, so the uncertainties to
  // show are the scaled ones (sigma * sqrt(chi^2 / dof)); the worst targets (largest
  // |residual| / sigma, at most 3) are named in a warning.
  bool scaled_uncertainties_recommended = false;
  std::vector<std::size_t> worst_targets;  // indices into `targets`, worst first
  double reducedChi2() const { return dof > 0 ? chi2 / dof : std::numeric_limits<double>::quiet_NaN(); }
};

// The penalty chi^2 of a point where the scene rules refuse the values or a target has no value.
inline constexpr double kFitPenaltyChi2 = 1e8;

// Throws std::invalid_argument for no free parameter, and std::runtime_error (naming the target)
// when a target has no value at the scene's own parameters. Cancelled: no value.
StudyOutcome<FitResult> fitScene(const Scene& scene, const std::vector<FitTarget>& targets,
                                 const std::vector<FreeParameter>& free, const FitOptions& options = {},
                                 const StudyControl& control = {});

}  // namespace fovea
