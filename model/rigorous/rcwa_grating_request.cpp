#include "model/rigorous/rcwa_grating_request.h"

#include "model/rigorous/rcwa_grating.h"

namespace fovea::rigorous {

namespace {
GratingPolarization rcwaPolarization(Polarization p) {
  switch (p) {
    case Polarization::S:
      return GratingPolarization::S;
    case Polarization::P:
      return GratingPolarization::P;
    case Polarization::Unpolarized:
      return GratingPolarization::Unpolarized;
  }
  return GratingPolarization::S;
}
}  // namespace

nlohmann::json rcwaGratingJson(const GratingRequest& r) {
  nlohmann::json j = kogelnikGratingJson(r);
  RcwaGratingRequest q;
  q.n0 = r.grating.film.n0;
  q.n1 = r.grating.film.n1;
  q.thickness_um = r.grating.film.thickness_um;
  q.period_nm = r.grating.period_nm;
  q.slant_deg = r.grating.slant_deg;
  q.probe_deg = r.grating.probe_deg;
  q.wavelength_nm = r.grating.wavelength_nm;
  q.polarization = rcwaPolarization(r.grating.polarization);
  q.absorption_per_mm = r.absorption_per_mm;
  q.orders = r.orders;
  q.slices = r.slices;
  const RcwaGratingAnswer a = solveRcwaGrating(q);
  const nlohmann::json answer = rcwaAnswerJson(a);
  j["kogelnik_efficiency"] = j["efficiency"];
  j["efficiency"] = a.efficiency;
  j["total_efficiency"] = a.total_efficiency;
  double zero = 0.0;
  for (const RcwaOrder& o : a.orders)
    if (o.order == 0 && !o.reflected) zero = o.efficiency;
  j["zero_order"] = zero;
  j["orders"] = answer["orders"];
  j["rcwa"] = answer["rcwa"];
  j["model"] = "rcwa";
  requireFiniteNumbers(j, r);
  return j;
}

std::vector<nlohmann::json> errorMapRequests(const KogelnikRcwaGrid& grid) {
  std::vector<nlohmann::json> lines;
  for (const KogelnikRcwaPoint& pt : kogelnikRcwaCases(grid)) {
    const PlanarCase& c = pt.grating;
    nlohmann::json j;
    j["n0"] = c.n0;
    j["n1"] = c.n1;
    j["thickness_um"] = c.thickness_um;
    j["period_nm"] = c.period_nm;
    j["slant_deg"] = c.slant_deg;
    j["probe_deg"] = c.probe_deg;
    j["wavelength_nm"] = c.wavelength_nm;
    j["polarization"] = c.te ? "s" : "p";
    j["geometry"] = pt.geometry;
    j["xi_target"] = pt.xi_target;
    j["rho"] = pt.rho;
    lines.push_back(std::move(j));
  }
  return lines;
}

}  // namespace fovea::rigorous
