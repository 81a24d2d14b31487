// Registry definitions of the planar-grating analyses of the studio (grating_sweep.h).
// Neither has a generated fovea-cli command: `fovea-cli grating` answers one probe angle
// with the same option names and is written by hand (app/cli/cmd_grating.cpp); the
// Kogelnik-vs-RCWA map is the one of `bench/bench_rcwa.cpp` and docs/benchmarks.md.
#include "model/analysis/grating_sweep.h"
#include "model/analysis/study_analyses.h"

namespace fovea::analysis {

AnalysisDefinition gratingSweepAnalysis() {
  AnalysisDefinition d;
  d.id = "grating";
  d.title = "Planar grating: efficiency vs probe angle";
  d.description =
      "One planar volume grating (the fovea-cli grating request) swept over the probe angle, with Kogelnik's closed "
      "forms and optionally converged RCWA.";
  d.parameters = {number("n0", "n0", "", 1.5, 1.0, 4.0, 4, "mean refractive index"),
                  number("n1", "n1", "", 0.02, 0.0, 1.0, 5, "index modulation amplitude"),
                  number("thickness-um", "Thickness", "um", 16.0, 0.0, 10000, 3, "film thickness"),
                  number("period-nm", "Period", "nm", 177.333, 1.0, 1e6, 3, "fringe period"),
                  number("slant-deg", "Slant", "deg", 0.0, -180, 180, 3, "angle of K from the film normal"),
                  number("probe-deg", "Probe (centre)", "deg", 0.0, -89.9, 89.9, 3, "probe angle inside the medium"),
                  number("wavelength-nm", "Wavelength", "nm", 532.0, 1, 100000, 2, "vacuum wavelength"),
                  choice("polarization", "Polarisation", {"unpolarized", "s", "p"}, "s", "probe light"),
                  number("absorption-per-mm", "Absorption", "1/mm", 0.0, 0, 1e6, 4, "intensity absorption"),
                  number("span-deg", "Probe span (±)", "deg", 5.0, 0.01, 89, 3, "probe angles swept around the centre"),
                  integer("samples", "Samples", 201, 3, 20001, "probe angles"),
                  choice("model", "Model", {"kogelnik", "kogelnik+rcwa"}, "kogelnik",
                         "kogelnik+rcwa adds converged RCWA (slower)")};
  for (auto& p : d.parameters)
    p.studio_only = p.name == "span-deg" || p.name == "samples" || p.name == "model";  // the CLI answers one probe
  d.plots = {"efficiency-vs-angle"};
  d.cli_generated = false;
  d.takes_scene = false;
  d.run = [](const Scene&, const nlohmann::json& v, const StudyControl& control) {
    GratingRequest req;
    PlanarGrating& g = req.grating;
    g.film.n0 = numberOf(v, "n0");
    g.film.n1 = numberOf(v, "n1");
    g.film.thickness_um = numberOf(v, "thickness-um");
    g.period_nm = numberOf(v, "period-nm");
    g.slant_deg = numberOf(v, "slant-deg");
    g.probe_deg = numberOf(v, "probe-deg");
    g.wavelength_nm = numberOf(v, "wavelength-nm");
    g.polarization = *parsePolarization(textOf(v, "polarization"));
    req.absorption_per_mm = numberOf(v, "absorption-per-mm");
    ProbeSweepOptions o;
    o.span_deg = numberOf(v, "span-deg");
    o.samples = integerOf(v, "samples");
    o.with_rcwa = textOf(v, "model") == "kogelnik+rcwa";
    return probeAngleSweep(req, o, control);
  };
  return d;
}

AnalysisDefinition kogelnikVsRcwaAnalysis() {
  AnalysisDefinition d;
  d.id = "kogelnik-vs-rcwa";
  d.title = "Kogelnik vs RCWA: error and run time";
  d.description =
      "Kogelnik's two-wave closed forms against converged RCWA over geometry, thickness, n1 and detuning: error by "
      "the validity parameter rho and the time of each model (docs/benchmarks.md).";
  d.parameters = {choice("grid", "Grid", {"quick", "full"}, "quick",
                         "quick: 24 points; full: the 240 points of docs/benchmarks.md")};
  d.plots = {"time-vs-error"};
  d.cli_twin = d.cli_generated = false;
  d.run = [](const Scene&, const nlohmann::json& v, const StudyControl& control) {
    const std::string grid = textOf(v, "grid");
    return kogelnikVsRcwaStudy(grid == "full" ? rigorous::KogelnikRcwaGrid{} : rigorous::KogelnikRcwaGrid::quick(),
                               grid, control);
  };
  return d;
}

}  // namespace fovea::analysis
