#pragma once
// Parameter uncertainties of a least-squares fit from the Jacobian of the normalised residuals
// at the optimum (fit_solver.h): covariance (J^T J)^-1 through the SVD of J on the parameters
// scaled by their bound windows, undetermined directions (relative singular value < rcond) left
// out, correlations, and the per-parameter warnings.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace fovea {

struct UncertaintyInput {
  Eigen::MatrixXd jacobian;     // d r_i / d p_j (targets x parameters), r normalised
  std::vector<double> windows;  // upper - lower of each parameter
  std::vector<bool> at_bound;   // the fitted value sits on a bound
  double rcond = 1e-6;
};

struct UncertaintyResult {
  Eigen::MatrixXd covariance, correlation;       // NaN rows/columns for undetermined parameters
  std::vector<double> relative_singular_values;  // descending, s_k / s_max
  std::vector<std::optional<double>> sigma;      // sqrt(C_jj), empty when undetermined
  std::vector<bool> determined;
  std::vector<std::string> warnings;  // per parameter, empty when none
};

UncertaintyResult analyseUncertainty(const UncertaintyInput& in);

}  // namespace fovea
