#include "model/analysis/fit_solver.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>

#include <nlopt.hpp>

#include "model/analysis/fit_uncertainty.h"
#include "model/analysis/tolerance_spec.h"  // counterUniform

namespace fovea {

namespace {

// Normalised residuals of a parameter vector; nothing when the scene rules refuse it or a
// target has no value there.
std::optional<std::vector<double>> residualsAt(const Scene& scene, const std::vector<FitTarget>& targets,
                                               const std::vector<FreeParameter>& free, const std::vector<double>& p,
                                               const ObservableSettings& settings) {
  try {
    const std::vector<double> m = evaluateTargets(sceneWithValues(scene, free, p), targets, settings);
    std::vector<double> r(m.size());
    for (std::size_t i = 0; i < m.size(); ++i) r[i] = (m[i] - targets[i].value) / targets[i].sigma;
    return r;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

double chi2Of(const std::vector<double>& r) {
  double s = 0;
  for (const double x : r) s += x * x;
  return s;
}

const char* statusText(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS:
      return "success";
    case nlopt::STOPVAL_REACHED:
      return "stopval reached";
    case nlopt::FTOL_REACHED:
      return "ftol reached";
    case nlopt::XTOL_REACHED:
      return "xtol reached";
    case nlopt::MAXEVAL_REACHED:
      return "max evaluations";
    case nlopt::MAXTIME_REACHED:
      return "max time";
    case nlopt::FORCED_STOP:
      return "stopped";
    case nlopt::ROUNDOFF_LIMITED:
      return "roundoff limited";
    default:
      return "failed";
  }
}

struct Problem {
  const Scene* scene;
  const std::vector<FitTarget>* targets;
  const std::vector<FreeParameter>* free;
  const FitOptions* options;
  const StudyControl* control;
  ProgressCounter* progress;
};

std::vector<double> fromUnit(const std::vector<FreeParameter>& free, const std::vector<double>& u) {
  std::vector<double> p(u.size());
  for (std::size_t j = 0; j < u.size(); ++j)
    p[j] = free[j].lower + std::clamp(u[j], 0.0, 1.0) * (free[j].upper - free[j].lower);
  return p;
}

FitStart runStart(const Problem& pb, std::vector<double> u, int max_evals) {
  const std::size_t n = u.size();
  FitStart s;
  s.from = fromUnit(*pb.free, u);
  struct Data {
    const Problem* pb;
    int evals = 0;
    nlopt::opt* opt = nullptr;
    double best_chi2 = std::numeric_limits<double>::infinity();  // the best evaluated point and its residuals
    std::vector<double> best_p;
    std::vector<double> best_r;
  } data{&pb, 0, nullptr, std::numeric_limits<double>::infinity(), {}, {}};
  nlopt::opt opt(n >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_COBYLA, static_cast<unsigned>(n));
  data.opt = &opt;
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  opt.set_xtol_abs(pb.options->xtol);
  opt.set_ftol_abs(1e-12);
  opt.set_stopval(1e-14);
  opt.set_maxeval(max_evals);
  opt.set_initial_step(pb.options->initial_step);
  opt.set_min_objective(
      [](unsigned, const double* x, double*, void* raw) -> double {
        auto* d = static_cast<Data*>(raw);
        if (d->pb->control->cancelled()) d->opt->force_stop();
        ++d->evals;
        d->pb->progress->add();
        const std::vector<double> point(x, x + d->pb->free->size());
        const std::vector<double> p = fromUnit(*d->pb->free, point);
        const auto r = residualsAt(*d->pb->scene, *d->pb->targets, *d->pb->free, p, d->pb->options->observables);
        const double chi2 = r ? chi2Of(*r) : kFitPenaltyChi2;
        if (r && chi2 < d->best_chi2) d->best_chi2 = chi2, d->best_p = p, d->best_r = *r;
        return chi2;
      },
      &data);
  double f = 0;
  nlopt::result res = nlopt::FAILURE;
  try {
    res = opt.optimize(u, f);
  } catch (const nlopt::roundoff_limited&) {
    res = nlopt::ROUNDOFF_LIMITED;
  } catch (const nlopt::forced_stop&) {
    res = nlopt::FORCED_STOP;
  }
  if (data.evals < max_evals) pb.progress->add(static_cast<std::size_t>(max_evals - data.evals));
  s.to = fromUnit(*pb.free, u);
  s.chi2 = f;
  s.evaluations = data.evals;
  s.status = statusText(res);
  if (!data.best_p.empty() && data.best_p == s.to) s.residuals_at_to = std::move(data.best_r);
  return s;
}

}  // namespace

StudyOutcome<FitResult> fitScene(const Scene& scene, const std::vector<FitTarget>& targets,
                                 const std::vector<FreeParameter>& free, const FitOptions& options,
                                 const StudyControl& control) {
  if (free.empty()) throw std::invalid_argument("fit: no free parameter");
  if (targets.empty()) throw std::invalid_argument("fit: no target");
  if (options.starts < 1) throw std::invalid_argument("fit: starts must be >= 1");
  const std::size_t n = free.size();
  FitResult out;
  out.algorithm = n >= 2 ? "LN_BOBYQA" : "LN_COBYLA";
  std::vector<double> p0(n);
  for (std::size_t j = 0; j < n; ++j) p0[j] = free[j].initial;
  // The scene's own values must give every target (else the message names the one that fails).
  const std::vector<double> m0 = evaluateTargets(scene, targets, options.observables);
  const int max_evals = options.max_evaluations > 0 ? options.max_evaluations : 40 * static_cast<int>(n + 2);
  ProgressCounter progress(control, static_cast<std::size_t>(options.starts * max_evals) + 2 * n + 1);
  const Problem pb{&scene, &targets, &free, &options, &control, &progress};
  auto starts = runSamples<FitStart>(
      static_cast<std::size_t>(options.starts),
      [&](std::size_t k) {
        std::vector<double> u(n);
        for (std::size_t j = 0; j < n; ++j)
          u[j] = k == 0 ? (free[j].initial - free[j].lower) / (free[j].upper - free[j].lower)
                        : counterUniform(options.seed, k, 0, j);
        return runStart(pb, u, max_evals);
      },
      StudyControl{nullptr, control.cancel});
  if (!starts.ok() || control.cancelled()) return {};
  out.starts = *starts.value;
  std::size_t best = 0;
  for (std::size_t k = 0; k < out.starts.size(); ++k) {
    out.evaluations += out.starts[k].evaluations;
    if (out.starts[k].chi2 < out.starts[best].chi2) best = k;
  }
  const std::vector<double> p = out.starts[best].to;

  // Jacobian of the normalised residuals at the optimum (central differences, one-sided at a
  // bound): its 2n points and the optimum itself (unless its start kept its residuals), all
  // independent, evaluated in parallel.
  struct Column {
    std::optional<std::vector<double>> plus, minus;
  };
  const std::optional<std::vector<double>>& known = out.starts[best].residuals_at_to;
  auto points = runSamples<std::optional<std::vector<double>>>(
      known ? 2 * n : 2 * n + 1,
      [&](std::size_t k) {
        if (k == 2 * n) return residualsAt(scene, targets, free, p, options.observables);
        const std::size_t j = k / 2;
        const double h = options.jacobian_step * (free[j].upper - free[j].lower);
        std::vector<double> x = p;
        x[j] = k % 2 == 0 ? std::min(p[j] + h, free[j].upper) : std::max(p[j] - h, free[j].lower);
        auto r = residualsAt(scene, targets, free, x, options.observables);
        progress.add();
        return r;
      },
      StudyControl{nullptr, control.cancel});
  if (!points.ok()) return {};
  std::vector<Column> columns(n);
  for (std::size_t j = 0; j < n; ++j) columns[j] = {(*points.value)[2 * j], (*points.value)[2 * j + 1]};
  const std::optional<std::vector<double>> rp = known ? known : (*points.value)[2 * n];
  progress.add();
  if (!rp) throw std::runtime_error("fit: the best point gives no value for a target");
  UncertaintyInput ui;
  ui.jacobian = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(targets.size()), static_cast<Eigen::Index>(n));
  ui.rcond = options.rcond;
  for (std::size_t j = 0; j < n; ++j) {
    const Column& c = columns[j];
    const double window = free[j].upper - free[j].lower;
    ui.windows.push_back(window);
    ui.at_bound.push_back(p[j] - free[j].lower < 1e-6 * window || free[j].upper - p[j] < 1e-6 * window);
    // A refused side falls back to the one-sided difference with the optimum.
    const double h = options.jacobian_step * window;
    const double a = std::min(p[j] + h, free[j].upper), b = std::max(p[j] - h, free[j].lower);
    const std::vector<double>* hi = c.plus ? &*c.plus : &*rp;
    const std::vector<double>* lo = c.minus ? &*c.minus : &*rp;
    const double step = (c.plus ? a : p[j]) - (c.minus ? b : p[j]);
    if (!(step > 0)) continue;  // no column: this parameter reads as undetermined
    for (std::size_t i = 0; i < targets.size(); ++i)
      ui.jacobian(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = ((*hi)[i] - (*lo)[i]) / step;
  }
  const UncertaintyResult u = analyseUncertainty(ui);
  out.chi2 = chi2Of(*rp);
  out.dof = static_cast<int>(targets.size()) - static_cast<int>(n);
  const double scale = out.dof > 0 ? std::sqrt(out.chi2 / out.dof) : std::numeric_limits<double>::quiet_NaN();
  out.covariance = u.covariance;
  out.correlation = u.correlation;
  out.relative_singular_values = u.relative_singular_values;
  for (std::size_t j = 0; j < n; ++j) {
    FitParameterResult r;
    r.parameter = free[j];
    r.fitted = p[j];
    r.uncertainty = u.sigma[j];
    if (u.sigma[j] && out.dof > 0) r.uncertainty_scaled = *u.sigma[j] * scale;
    r.determined = u.determined[j];
    r.at_bound = ui.at_bound[j];
    out.parameters.push_back(r);
    if (!u.warnings[j].empty()) out.warnings.push_back({free[j].path, u.warnings[j]});
  }
  if (out.dof < 0)
    out.warnings.push_back({"", "fewer targets (" + std::to_string(targets.size()) + ") than free parameters (" +
                                    std::to_string(n) + "): some directions cannot be determined"});
  if (out.starts[best].status == "max evaluations")
    out.warnings.push_back({"", "the best start stopped at its evaluation budget (raise max evaluations)"});
  for (std::size_t i = 0; i < targets.size(); ++i) {
    FitTargetResult t;
    t.target = targets[i];
    t.initial_model = m0[i];
    t.model = targets[i].value + (*rp)[i] * targets[i].sigma;
    out.targets.push_back(t);
    const double r0 = (m0[i] - targets[i].value) / targets[i].sigma;
    out.chi2_initial += r0 * r0;
  }
  // Misfit beyond the sigmas: say so and name the targets that pull hardest.
  if (out.dof > 0 && out.chi2 / out.dof > 1.0) {
    out.scaled_uncertainties_recommended = true;
    std::vector<std::size_t> order(targets.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return std::abs((*rp)[a]) > std::abs((*rp)[b]); });
    order.resize(std::min<std::size_t>(3, order.size()));
    out.worst_targets = order;
    char head[256];
    std::snprintf(head, sizeof head,
                  "reduced chi2 %.3g > 1 (chi2 %.4g for %d dof): the targets disagree with the model beyond their "
                  "sigmas; uncertainties scaled by sqrt(chi2/dof) = %.3g are the ones to quote; worst targets:",
                  out.chi2 / out.dof, out.chi2, out.dof, scale);
    std::string msg = head;
    for (std::size_t k = 0; k < order.size(); ++k) {
      char one[48];
      std::snprintf(one, sizeof one, " (%+.3g sigma)", (*rp)[order[k]]);
      msg += (k ? ", " : " ") + targets[order[k]].id + one;
    }
    out.warnings.push_back({"", msg});
  }
  out.fitted_scene = sceneWithValues(scene, free, p);
  StudyOutcome<FitResult> done;
  done.status = StudyStatus::Completed;
  done.value = std::move(out);
  return done;
}

}  // namespace fovea
