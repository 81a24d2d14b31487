#include "model/rigorous/rcwa_grating.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "model/units.h"

namespace fovea::rigorous {

namespace {

RcwaConvergedResult solveOne(const RcwaGratingRequest& q, RcwaPolarization pol) {
  RcwaProblem p;
  const double lambda_um = q.wavelength_nm * 1e-3;
  const double kappa = q.absorption_per_mm * 1e-3 * lambda_um / (4.0 * kPi);
  p.n0 = std::complex<double>(q.n0, kappa);
  p.n1 = q.n1;
  p.thickness_um = q.thickness_um;
  p.period_nm = q.period_nm;
  p.slant_deg = q.slant_deg;
  p.wavelength_nm = q.wavelength_nm;
  p.n_cover = q.n_cover.value_or(q.n0);
  p.n_substrate = q.n_substrate.value_or(q.n0);
  p.polarization = pol;
  p.setFilmAngleDeg(q.probe_deg);
  if (!(p.n_cover > 0.0) || !std::isfinite(p.n_cover))
    throw std::invalid_argument("n_cover: must be a positive number");
  if (!(p.n_substrate > 0.0) || !std::isfinite(p.n_substrate))
    throw std::invalid_argument("n_substrate: must be a positive number");
  if (std::abs(p.kx_over_k0) >= p.n_cover)
    throw std::invalid_argument("probe_deg: a probe at " + std::to_string(q.probe_deg) +
                                " deg inside the film cannot come from a cover of index " + std::to_string(p.n_cover) +
                                " (n0 sin θ >= n_cover)");
  if (q.orders && (*q.orders < 0 || *q.orders > 400)) throw std::invalid_argument("orders: must be in [0, 400]");
  if (q.slices && (*q.slices < 1 || *q.slices > (1 << 24)))
    throw std::invalid_argument("slices: must be in [1, 16777216]");
  if (!(q.tolerance > 0.0)) throw std::invalid_argument("tolerance: must be > 0");

  const KogelnikOrder ko = kogelnikDiffractedOrder(p);
  if (q.orders && q.slices) {
    RcwaConvergedResult r;
    r.result = solveRcwa(p, {*q.orders, *q.slices, false});
    r.orders = r.result.orders_used;
    r.slices = r.result.slices_used;
    r.converged = true;
    r.solves = 1;
    return r;
  }
  RcwaConvergence c;
  c.tolerance = q.tolerance;
  c.target_order = ko.order;
  c.target_reflected = ko.reflected;
  // Start the staircase at 16 slices per fringe period along z (no convergence by aliasing).
  const double periods_z = q.thickness_um * 1e3 * std::abs(std::cos(degToRad(q.slant_deg))) / q.period_nm;
  c.min_slices = int(std::min(double(1 << 18), std::max(8.0, std::ceil(16.0 * periods_z))));
  c.max_slices = std::max(c.min_slices, c.max_slices);
  if (q.orders) c.min_orders = c.max_orders = *q.orders;
  if (q.slices) c.min_slices = c.max_slices = *q.slices;
  return solveRcwaConverged(p, c);
}
}  // namespace

RcwaGratingAnswer solveRcwaGrating(const RcwaGratingRequest& q) {
  RcwaGratingAnswer a;
  std::vector<RcwaConvergedResult> runs;
  if (q.polarization != GratingPolarization::P) runs.push_back(solveOne(q, RcwaPolarization::TE));
  if (q.polarization != GratingPolarization::S) runs.push_back(solveOne(q, RcwaPolarization::TM));
  a.orders = runs.front().result.orders;  // same propagating set for s and p
  if (runs.size() == 2)
    for (std::size_t i = 0; i < a.orders.size(); ++i)
      a.orders[i].efficiency = 0.5 * (runs[0].result.orders[i].efficiency + runs[1].result.orders[i].efficiency);
  RcwaProblem probe;  // geometry only, for Kogelnik's order
  probe.n0 = q.n0;
  probe.period_nm = q.period_nm;
  probe.slant_deg = q.slant_deg;
  probe.wavelength_nm = q.wavelength_nm;
  probe.setFilmAngleDeg(q.probe_deg);
  a.kogelnik_order = kogelnikDiffractedOrder(probe);
  for (const RcwaOrder& o : a.orders) {
    a.total_efficiency += o.efficiency;
    if (o.order == a.kogelnik_order.order && o.reflected == a.kogelnik_order.reflected) a.efficiency = o.efficiency;
  }
  for (const auto& r : runs) {
    a.orders_used = std::max(a.orders_used, r.orders);
    a.slices_used = std::max(a.slices_used, r.slices);
    a.solves += r.solves;
    a.converged = a.converged && r.converged;
    a.last_change = std::max(a.last_change, r.last_change);
  }
  return a;
}

nlohmann::json rcwaAnswerJson(const RcwaGratingAnswer& a) {
  nlohmann::json orders = nlohmann::json::array();
  for (const RcwaOrder& o : a.orders)
    orders.push_back({{"order", o.order},
                      {"side", o.reflected ? "reflected" : "transmitted"},
                      {"efficiency", o.efficiency},
                      {"angle_deg", o.angle_deg}});
  return {{"efficiency", a.efficiency},
          {"total_efficiency", a.total_efficiency},
          {"orders", orders},
          {"rcwa",
           {{"orders", a.orders_used},
            {"slices", a.slices_used},
            {"converged", a.converged},
            {"last_change", a.last_change},
            {"solves", a.solves},
            {"kogelnik_order", a.kogelnik_order.order},
            {"kogelnik_side", a.kogelnik_order.reflected ? "reflected" : "transmitted"}}}};
}

}  // namespace fovea::rigorous
