#include "model/analysis/fit_json.h"

#include "model/json_numbers.h"

namespace fovea {

namespace {
nlohmann::json matrixJson(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(numberOrNull(m(i, j)));
    rows.push_back(row);
  }
  return rows;
}
}  // namespace

nlohmann::json fitResultJson(const FitResult& r, const FitOptions& o) {
  nlohmann::json params = nlohmann::json::array(), targets = nlohmann::json::array(), starts = nlohmann::json::array(),
                 warnings = nlohmann::json::array(), paths = nlohmann::json::array();
  for (const auto& p : r.parameters) {
    paths.push_back(p.parameter.path);
    params.push_back({{"path", p.parameter.path},
                      {"unit", p.parameter.unit},
                      {"initial", p.parameter.initial},
                      {"fitted", p.fitted},
                      {"change", p.fitted - p.parameter.initial},
                      {"lower", p.parameter.lower},
                      {"upper", p.parameter.upper},
                      {"uncertainty", optionalNumber(p.uncertainty)},
                      {"uncertainty_scaled", optionalNumber(p.uncertainty_scaled)},
                      {"determined", p.determined},
                      {"at_bound", p.at_bound}});
  }
  for (const auto& t : r.targets)
    targets.push_back({{"id", t.target.id},
                       {"observable", t.target.observable},
                       {"parameters", t.target.parameters},
                       {"unit", t.target.unit},
                       {"source", t.target.source},
                       {"value", t.target.value},
                       {"sigma", t.target.sigma},
                       {"initial_model", numberOrNull(t.initial_model)},
                       {"model", numberOrNull(t.model)},
                       {"residual", numberOrNull(t.model - t.target.value)},
                       {"normalised", numberOrNull(t.normalised())}});
  for (const auto& s : r.starts)
    starts.push_back(
        {{"from", s.from}, {"to", s.to}, {"chi2", s.chi2}, {"evaluations", s.evaluations}, {"status", s.status}});
  for (const auto& w : r.warnings) warnings.push_back({{"parameter", w.parameter}, {"message", w.message}});
  nlohmann::json worst = nlohmann::json::array();
  for (const std::size_t i : r.worst_targets)
    if (i < r.targets.size())
      worst.push_back({{"id", r.targets[i].target.id}, {"normalised", numberOrNull(r.targets[i].normalised())}});
  return {{"algorithm", r.algorithm},
          {"starts", o.starts},
          {"seed", o.seed},
          {"evaluations", r.evaluations},
          {"parameters", params},
          {"targets", targets},
          {"chi2_initial", numberOrNull(r.chi2_initial)},
          {"chi2", numberOrNull(r.chi2)},
          {"dof", r.dof},
          {"reduced_chi2", r.dof > 0 ? numberOrNull(r.chi2 / r.dof) : nlohmann::json(nullptr)},
          {"covariance_scaled_by_reduced_chi2", false},
          // Which of uncertainty / uncertainty_scaled the front ends show (scaled when chi2/dof > 1).
          {"uncertainties_shown", r.scaled_uncertainties_recommended ? "scaled" : "unscaled"},
          {"worst_targets", worst},
          {"parameter_order", paths},
          {"covariance", matrixJson(r.covariance)},
          {"correlation", matrixJson(r.correlation)},
          {"relative_singular_values", r.relative_singular_values},
          {"rcond", o.rcond},
          {"warnings", warnings},
          {"start_results", starts}};
}

}  // namespace fovea
