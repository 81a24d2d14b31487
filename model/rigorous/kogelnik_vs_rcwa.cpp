#include "model/rigorous/kogelnik_vs_rcwa.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "model/units.h"

namespace fovea::rigorous {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Probe angle θ ≥ θ_B at which ξ(θ) = target: bracket by doubling steps, then bisect.
double probeForXi(PlanarCase c, double bragg_deg, double xi_target) {
  if (xi_target <= 0.0) return bragg_deg;
  auto xi = [&](double deg) {
    c.probe_deg = deg;
    return kogelnikXi(c);
  };
  double lo = 0.0, hi = 1e-4;
  while (xi(bragg_deg + hi) < xi_target && bragg_deg + 2 * hi < 89.0) {
    lo = hi;
    hi *= 2;
  }
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (xi(bragg_deg + mid) < xi_target ? lo : hi) = mid;
  }
  return bragg_deg + 0.5 * (lo + hi);
}
}  // namespace

KogelnikRcwaGrid KogelnikRcwaGrid::quick() {
  KogelnikRcwaGrid g;
  g.geometries = {{"transmission, unslanted, thin (θB 2°)", 90.0, 2.0},
                  {"transmission, slanted 60° (θB 10°)", 60.0, 10.0},
                  {"reflection, slanted 30° (θB 0°)", 30.0, 0.0}};
  g.thickness_um = {5.0, 20.0};
  g.n1 = {0.005, 0.05};
  g.detuning_xi = {0.0, 2.0};
  g.kogelnik_repeats = 200;
  return g;
}

std::vector<KogelnikRcwaPoint> kogelnikRcwaCases(const KogelnikRcwaGrid& grid) {
  std::vector<KogelnikRcwaPoint> out;
  for (const GratingGeometry& geo : grid.geometries) {
    const double period_nm =
        grid.wavelength_nm / (2.0 * grid.n0 * std::cos(degToRad(geo.slant_deg - geo.bragg_probe_deg)));
    for (double d : grid.thickness_um)
      for (double n1 : grid.n1)
        for (double xi : grid.detuning_xi) {
          KogelnikRcwaPoint pt;
          pt.geometry = geo.name;
          PlanarCase& c = pt.grating;
          c.n0 = grid.n0;
          c.n1 = n1;
          c.thickness_um = d;
          c.period_nm = period_nm;
          c.slant_deg = geo.slant_deg;
          c.wavelength_nm = grid.wavelength_nm;
          c.te = grid.te;
          c.probe_deg = probeForXi(c, geo.bragg_probe_deg, xi);
          pt.xi_target = xi;
          pt.detuning_deg = c.probe_deg - geo.bragg_probe_deg;
          pt.rho = rhoParameter(c);
          pt.klein_q = kleinQ(c);
          out.push_back(pt);
        }
  }
  return out;
}

std::vector<KogelnikRcwaPoint> kogelnikVsRcwa(const KogelnikRcwaGrid& grid, const KogelnikEvaluator& evaluator) {
  const KogelnikEvaluator kog = evaluator ? evaluator : KogelnikEvaluator(&kogelnikClosedForm);
  std::vector<KogelnikRcwaPoint> out;
  for (KogelnikRcwaPoint pt : kogelnikRcwaCases(grid)) {
    const PlanarCase& c = pt.grating;
    const double d = c.thickness_um, period_nm = c.period_nm;
    // Kogelnik, timed as the fastest of 5 batches (the machine is shared: the minimum is the
    // cost, the rest is interference). The sink keeps the loop from being optimised away.
    volatile double sink = 0.0;
    const int reps = std::max(1, grid.kogelnik_repeats / 5);
    pt.kogelnik_ns = 1e300;
    for (int batch = 0; batch < 5; ++batch) {
      const auto t0 = Clock::now();
      for (int i = 0; i < reps; ++i) sink = sink + kog(c).efficiency;
      pt.kogelnik_ns = std::min(pt.kogelnik_ns, msSince(t0) * 1e6 / reps);
    }
    pt.kogelnik = kog(c);

    // RCWA, converged on Kogelnik's wave; slices start at 16 per fringe period along z so
    // that a coarse staircase cannot "converge" by aliasing.
    const RcwaProblem prob = rcwaProblemOf(c);
    const KogelnikOrder ko = kogelnikDiffractedOrder(prob);
    RcwaConvergence conv;
    conv.tolerance = grid.rcwa_tolerance;
    conv.target_order = ko.order;
    conv.target_reflected = ko.reflected;
    const double cos_slant = std::abs(std::cos(c.slant_deg * kPi / 180.0));
    const double periods_z = d * 1e3 * cos_slant / period_nm;
    conv.min_slices = std::max(8, int(std::ceil(16.0 * periods_z)));
    conv.max_slices = std::max(conv.min_slices, conv.max_slices);
    auto t0 = Clock::now();
    const RcwaConvergedResult rc = solveRcwaConverged(prob, conv);
    pt.rcwa_ms = msSince(t0);
    t0 = Clock::now();
    (void)solveRcwaConverged(prob, conv);  // second run: fastest of two, as above
    pt.rcwa_ms = std::min(pt.rcwa_ms, msSince(t0));
    pt.rcwa_single_ms = 1e300;
    for (int rep = 0; rep < 2; ++rep) {
      t0 = Clock::now();
      (void)solveRcwa(prob, {rc.orders, rc.slices, false});
      pt.rcwa_single_ms = std::min(pt.rcwa_single_ms, msSince(t0));
    }
    pt.rcwa_efficiency = rc.result.efficiency(ko.order, ko.reflected);
    pt.rcwa_total = rc.result.total_efficiency;
    pt.rcwa_other_orders = pt.rcwa_total - pt.rcwa_efficiency;
    if (ko.order != 0)
      pt.rcwa_other_orders -= rc.result.efficiency(0, true) + rc.result.efficiency(0, false);
    else
      pt.rcwa_other_orders -= rc.result.efficiency(0, false);
    pt.rcwa_orders = rc.orders;
    pt.rcwa_slices = rc.slices;
    pt.rcwa_solves = rc.solves;
    pt.rcwa_converged = rc.converged;
    pt.abs_error = std::abs(pt.kogelnik.efficiency - pt.rcwa_efficiency);
    if (grid.with_linearised) {
      RcwaProblem lin = prob;
      lin.linearised_permittivity = true;
      pt.rcwa_linearised_efficiency = solveRcwaConverged(lin, conv).result.efficiency(ko.order, ko.reflected);
      pt.abs_error_linearised = std::abs(pt.kogelnik.efficiency - pt.rcwa_linearised_efficiency);
    }
    out.push_back(pt);
  }
  return out;
}

std::vector<RhoBinSummary> summariseByRho(const std::vector<KogelnikRcwaPoint>& points) {
  const std::vector<double> edges{0.0, 1.0, 10.0, 100.0, 1e3, 1e300};
  std::vector<RhoBinSummary> rows;
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    RhoBinSummary s;
    s.rho_min = edges[b];
    s.rho_max = edges[b + 1];
    std::vector<double> errs;
    for (const auto& p : points)
      if (p.rho >= s.rho_min && p.rho < s.rho_max) {
        errs.push_back(p.abs_error);
        s.max_error_linearised = std::max(s.max_error_linearised, p.abs_error_linearised);
        if (p.kogelnik.nu <= 0.5 * kPi) s.max_error_weak = std::max(s.max_error_weak, p.abs_error);
        s.mean_kogelnik_ns += p.kogelnik_ns;
        s.mean_rcwa_ms += p.rcwa_ms;
      }
    s.points = int(errs.size());
    if (errs.empty()) continue;
    std::sort(errs.begin(), errs.end());
    s.max_error = errs.back();
    s.median_error = errs[errs.size() / 2];
    s.mean_kogelnik_ns /= s.points;
    s.mean_rcwa_ms /= s.points;
    rows.push_back(s);
  }
  return rows;
}

std::string kogelnikVsRcwaMarkdown(const std::vector<KogelnikRcwaPoint>& points) {
  std::ostringstream o;
  char buf[640];
  o << "| ρ range | points | max abs(Δη) | median abs(Δη) | max abs(Δη) at ν ≤ π/2 | max abs(Δη), linearised ε | "
       "Kogelnik (ns) | RCWA converged (ms) | RCWA/Kogelnik time |\n";
  o << "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& s : summariseByRho(points)) {
    const std::string hi = s.rho_max > 1e299 ? "∞" : std::to_string(int(s.rho_max));
    std::snprintf(buf, sizeof buf, "| %g – %s | %d | %.2e | %.2e | %.2e | %.2e | %.0f | %.2f | %.1e |\n", s.rho_min,
                  hi.c_str(), s.points, s.max_error, s.median_error, s.max_error_weak, s.max_error_linearised,
                  s.mean_kogelnik_ns, s.mean_rcwa_ms, s.mean_rcwa_ms * 1e6 / std::max(1e-3, s.mean_kogelnik_ns));
    o << buf;
  }
  o << "\n| geometry | Λ (nm) | d (µm) | n1 | ξ | Δθ (°) | ρ | Q | ν | η Kogelnik | η RCWA | abs(Δη) | abs(Δη) lin. | "
       "other orders | N | M | RCWA (ms) |\n";
  o << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& p : points) {
    std::snprintf(
        buf, sizeof buf,
        "| %s | %.1f | %g | %g | %g | %.3f | %.3g | %.3g | %.3g | %.4f | %.4f | %.1e | %.1e | %.1e | %d | %d | "
        "%.2f |\n",
        p.geometry.c_str(), p.grating.period_nm, p.grating.thickness_um, p.grating.n1, p.xi_target, p.detuning_deg,
        p.rho, p.klein_q, p.kogelnik.nu, p.kogelnik.efficiency, p.rcwa_efficiency, p.abs_error, p.abs_error_linearised,
        std::max(0.0, p.rcwa_other_orders), p.rcwa_orders, p.rcwa_slices, p.rcwa_ms);
    o << buf;
  }
  return o.str();
}

}  // namespace fovea::rigorous
