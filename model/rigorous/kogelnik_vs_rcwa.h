#pragma once
// Where is Kogelnik good enough, and what does it save? An error map of Kogelnik's two-wave
// theory against converged RCWA over thickness, n1, detuning and geometry (slant + Bragg
// angle), with the validity parameter ρ = λ²/(Λ² n0 n1) and the time of each model
// (docs/benchmarks.md, "Run time against error"). Used by benchmarks/bench_rcwa.cpp and docs/benchmarks.md.

#include <functional>
#include <string>
#include <vector>

#include "model/rigorous/planar_case.h"

namespace fovea::rigorous {

struct GratingGeometry {
  std::string name;
  double slant_deg = 90.0;
  double bragg_probe_deg = 0.0;  // probe angle (inside) at which the grating is Bragg-matched;
                                 // fixes the period: Λ = λ/(2 n0 cos(φ − θ_B))
};

struct KogelnikRcwaGrid {
  double n0 = 1.5;
  double wavelength_nm = 532.0;
  bool te = true;
  std::vector<GratingGeometry> geometries{
      {"transmission, unslanted, thin (θB 2°)", 90.0, 2.0}, {"transmission, unslanted (θB 20°)", 90.0, 20.0},
      {"transmission, slanted 60° (θB 10°)", 60.0, 10.0},   {"reflection, slanted 30° (θB 0°)", 30.0, 0.0},
      {"reflection, unslanted (θB 0°)", 0.0, 0.0},
  };
  std::vector<double> thickness_um{2.0, 5.0, 20.0, 50.0};
  std::vector<double> n1{0.002, 0.01, 0.03, 0.06};
  // Detuning as Kogelnik's dephasing ξ (0 = on Bragg); the probe angle that gives it is solved
  // for on the θ > θ_B side.
  std::vector<double> detuning_xi{0.0, 1.5, 4.0};
  double rcwa_tolerance = 1e-4;  // absolute, on the diffracted efficiency
  int kogelnik_repeats = 2000;   // evaluations timed per point (fastest of 5 batches)
  // Also solve RCWA with Kogelnik's linearised ε = n0² + 2 n0 n1 cos K·r: the error against it
  // is the two-wave/slowly-varying-envelope error alone, without the dropped O(n1²) terms.
  bool with_linearised = true;
  // The few-point grid of `fovea-cli bench --quick` / CI-sized runs.
  static KogelnikRcwaGrid quick();
};

struct KogelnikRcwaPoint {
  std::string geometry;
  PlanarCase grating;  // the probe angle includes the detuning
  double xi_target = 0.0;
  double detuning_deg = 0.0;  // probe − Bragg angle
  double rho = 0.0, klein_q = 0.0;
  KogelnikEvaluation kogelnik;
  double rcwa_efficiency = 0.0;    // Kogelnik's diffracted wave (order +1, or 0 reflected when K_x = 0)
  double rcwa_total = 0.0;         // sum over every propagating order (1: lossless check)
  double rcwa_other_orders = 0.0;  // power in orders Kogelnik ignores (neither 0 T/R nor its wave)
  int rcwa_orders = 0, rcwa_slices = 0, rcwa_solves = 0;
  bool rcwa_converged = false;
  double abs_error = 0.0;                   // |η_Kogelnik − η_RCWA|
  double rcwa_linearised_efficiency = 0.0;  // RCWA with the linearised ε (when with_linearised)
  double abs_error_linearised = 0.0;        // |η_Kogelnik − η_RCWA,linearised|
  double kogelnik_ns = 0.0;                 // one Kogelnik evaluation
  double rcwa_ms = 0.0;                     // converged RCWA (all solves of the convergence loop)
  double rcwa_single_ms = 0.0;              // one RCWA solve at the converged orders and slices
};

// The grid's points without solving anything: geometry, grating (probe angle solved for the
// detuning), xi_target, detuning_deg, rho, klein_q. kogelnikVsRcwa evaluates exactly these.
std::vector<KogelnikRcwaPoint> kogelnikRcwaCases(const KogelnikRcwaGrid& grid);

using KogelnikEvaluator = std::function<KogelnikEvaluation(const PlanarCase&)>;

// Evaluates every grid point (geometries × thickness × n1 × detuning). `kogelnik` defaults to
// the closed forms (kogelnikClosedForm). Deterministic except for the timing fields.
std::vector<KogelnikRcwaPoint> kogelnikVsRcwa(const KogelnikRcwaGrid& grid, const KogelnikEvaluator& kogelnik = {});

// Error by ρ decade: rows {ρ range, points, max |Δη|, median |Δη|, mean Kogelnik ns, mean RCWA ms}.
struct RhoBinSummary {
  double rho_min = 0.0, rho_max = 0.0;
  int points = 0;
  double max_error = 0.0, median_error = 0.0, mean_kogelnik_ns = 0.0, mean_rcwa_ms = 0.0;
  double max_error_linearised = 0.0;
  double max_error_weak = 0.0;  // over the points with ν ≤ π/2 (up to the first full conversion)
};
std::vector<RhoBinSummary> summariseByRho(const std::vector<KogelnikRcwaPoint>& points);

// Markdown tables (summary by ρ, then every point) for docs/benchmarks.md.
std::string kogelnikVsRcwaMarkdown(const std::vector<KogelnikRcwaPoint>& points);

}  // namespace fovea::rigorous
