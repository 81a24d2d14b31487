#include "model/analysis/grating_sweep.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "model/analysis/analysis_json.h"
#include "model/rigorous/rcwa_grating.h"

namespace fovea {

namespace {
rigorous::RcwaGratingRequest rcwaRequest(const GratingRequest& req) {
  const PlanarGrating& g = req.grating;
  rigorous::RcwaGratingRequest rr;
  rr.n0 = g.film.n0;
  rr.n1 = g.film.n1;
  rr.thickness_um = g.film.thickness_um;
  rr.period_nm = g.period_nm;
  rr.slant_deg = g.slant_deg;
  rr.probe_deg = g.probe_deg;
  rr.wavelength_nm = g.wavelength_nm;
  rr.absorption_per_mm = req.absorption_per_mm;
  rr.polarization = g.polarization == Polarization::S   ? rigorous::GratingPolarization::S
                    : g.polarization == Polarization::P ? rigorous::GratingPolarization::P
                                                        : rigorous::GratingPolarization::Unpolarized;
  return rr;
}
}  // namespace

std::optional<nlohmann::json> probeAngleSweep(const GratingRequest& request, const ProbeSweepOptions& options,
                                              const StudyControl& control) {
  if (auto e = validateGratingRequest(request, false)) throw std::invalid_argument(e->message);
  const int n = options.samples;
  const double span = options.span_deg, centre = request.grating.probe_deg;
  nlohmann::json out;
  out["center"] = kogelnikGratingJson(request);
  out["models"] = options.with_rcwa ? nlohmann::json{"kogelnik", "rcwa"} : nlohmann::json{"kogelnik"};
  nlohmann::json samples = nlohmann::json::array();
  for (int i = 0; i < n; ++i) {
    if (control.cancelled()) return std::nullopt;
    const double probe = centre - span + 2.0 * span * i / std::max(1, n - 1);
    nlohmann::json s{{"probe_deg", probe}, {"detuning_deg", probe - centre}};
    GratingRequest r = request;
    r.grating.probe_deg = probe;
    if (std::abs(probe) >= 90.0 || validateGratingRequest(r, false)) {
      s["kogelnik_efficiency"] = nullptr;
    } else {
      const nlohmann::json k = kogelnikGratingJson(r);
      s["kogelnik_efficiency"] = k["efficiency"];
      s["xi"] = k["xi"];
      s["nu"] = k["nu"];
    }
    if (options.with_rcwa) {
      try {
        const auto a = rigorous::solveRcwaGrating(rcwaRequest(r));
        s["rcwa_efficiency"] = a.efficiency;
        s["rcwa_converged"] = a.converged;
      } catch (const std::exception&) {
        s["rcwa_efficiency"] = nullptr;
      }
    }
    samples.push_back(s);
    if (control.on_progress) control.on_progress(double(i + 1) / n);
  }
  out["samples"] = samples;
  return out;
}

std::optional<nlohmann::json> kogelnikVsRcwaStudy(const rigorous::KogelnikRcwaGrid& grid, const std::string& grid_name,
                                                  const StudyControl& control) {
  std::vector<rigorous::KogelnikRcwaPoint> all;
  const auto n = grid.geometries.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (control.cancelled()) return std::nullopt;
    rigorous::KogelnikRcwaGrid one = grid;
    one.geometries = {grid.geometries[i]};
    auto pts = rigorous::kogelnikVsRcwa(one);
    all.insert(all.end(), pts.begin(), pts.end());
    if (control.on_progress) control.on_progress(double(i + 1) / n);
  }
  if (control.cancelled()) return std::nullopt;
  nlohmann::json j = kogelnikVsRcwaJson(all);
  j["grid"] = grid_name;
  return j;
}

}  // namespace fovea
