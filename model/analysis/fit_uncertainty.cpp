#include "model/analysis/fit_uncertainty.h"

#include <cmath>
#include <limits>

#include <Eigen/SVD>

namespace fovea {

namespace {
std::string shortNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}
}  // namespace

UncertaintyResult analyseUncertainty(const UncertaintyInput& in) {
  const Eigen::Index n = in.jacobian.cols();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  UncertaintyResult out;
  out.covariance = Eigen::MatrixXd::Constant(n, n, nan);
  out.correlation = Eigen::MatrixXd::Constant(n, n, nan);
  out.sigma.assign(static_cast<std::size_t>(n), std::nullopt);
  out.determined.assign(static_cast<std::size_t>(n), true);
  out.warnings.assign(static_cast<std::size_t>(n), {});
  if (n == 0) return out;
  Eigen::VectorXd w(n);
  for (Eigen::Index j = 0; j < n; ++j) w(j) = in.windows[static_cast<std::size_t>(j)];
  // J on the scaled parameters q_j = p_j / window_j: its singular values compare alike.
  const Eigen::MatrixXd js = in.jacobian * w.asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(js, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();  // min(rows, n) values, descending
  const Eigen::MatrixXd& v = svd.matrixV();
  const double s_max = s.size() > 0 ? s(0) : 0.0;
  Eigen::MatrixXd cs = Eigen::MatrixXd::Zero(n, n);
  std::vector<double> worst(static_cast<std::size_t>(n), 1.0);  // smallest relative s of a direction it is in
  for (Eigen::Index k = 0; k < n; ++k) {
    const double sk = k < s.size() ? s(k) : 0.0;
    const double rel = s_max > 0 ? sk / s_max : 0.0;
    out.relative_singular_values.push_back(rel);
    if (rel >= in.rcond && sk > 0) {
      cs += v.col(k) * v.col(k).transpose() / (sk * sk);
      continue;
    }
    for (Eigen::Index j = 0; j < n; ++j)
      if (std::abs(v(j, k)) > 0.1) {
        out.determined[static_cast<std::size_t>(j)] = false;
        worst[static_cast<std::size_t>(j)] = std::min(worst[static_cast<std::size_t>(j)], rel);
      }
  }
  const Eigen::MatrixXd c = w.asDiagonal() * cs * w.asDiagonal();
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (!out.determined[ui]) {
      out.warnings[ui] =
          "undetermined: J^T J is near-singular along a direction it takes part in (relative singular "
          "value " +
          shortNumber(worst[ui]) + " < " + shortNumber(in.rcond) +
          "); the targets cannot tell its value, keep it fixed or add a target that depends on it";
      continue;
    }
    out.sigma[ui] = std::sqrt(c(i, i));
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!out.determined[static_cast<std::size_t>(j)]) continue;
      out.covariance(i, j) = c(i, j);
      out.correlation(i, j) = c(i, j) / std::sqrt(c(i, i) * c(j, j));
    }
    if (in.at_bound[ui])
      out.warnings[ui] =
          "at its bound: the bound, not the targets, holds it (its uncertainty is that of an interior "
          "optimum and may be meaningless); widen the bounds if that is not physical";
    else if (*out.sigma[ui] > 0.5 * in.windows[ui])
      out.warnings[ui] = "weakly determined: uncertainty " + shortNumber(*out.sigma[ui]) +
                         " exceeds half its bound window " + shortNumber(in.windows[ui]);
  }
  return out;
}

}  // namespace fovea
