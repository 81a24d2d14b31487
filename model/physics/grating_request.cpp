#include "model/physics/grating_request.h"

#include <cmath>
#include <sstream>

namespace fovea {

std::string cliFlag(const std::string& key) {
  std::string f = "--" + key;
  for (char& c : f)
    if (c == '_') c = '-';
  return f;
}

namespace {
std::string num(double v) {
  std::ostringstream ss;
  ss << v;
  return ss.str();
}
}  // namespace

std::optional<GratingArgError> validateGratingRequest(const GratingRequest& r, bool flags) {
  const auto name = [flags](const char* key) { return flags ? cliFlag(key) : std::string(key); };
  const auto err = [&](const char* key, const std::string& what) {
    return GratingArgError{key, name(key) + ": " + what};
  };
  const PlanarGrating& g = r.grating;
  const std::pair<const char*, double> values[] = {{"n0", g.film.n0},
                                                   {"n1", g.film.n1},
                                                   {"thickness_um", g.film.thickness_um},
                                                   {"period_nm", g.period_nm},
                                                   {"slant_deg", g.slant_deg},
                                                   {"probe_deg", g.probe_deg},
                                                   {"wavelength_nm", g.wavelength_nm},
                                                   {"absorption_per_mm", r.absorption_per_mm}};
  for (const auto& [key, v] : values)
    if (!std::isfinite(v)) return err(key, "must be a finite number (got " + num(v) + ")");
  if (!(g.film.n0 > 0.0)) return err("n0", "mean index must be positive (got " + num(g.film.n0) + ")");
  if (g.film.n1 < 0.0) return err("n1", "index modulation must be >= 0 (got " + num(g.film.n1) + ")");
  if (!(g.film.n1 < g.film.n0))
    return err("n1", "index modulation must be smaller than " + name("n0") + " (" + num(g.film.n1) +
                         " >= " + num(g.film.n0) + ")");
  if (g.film.thickness_um < 0.0)
    return err("thickness_um", "thickness must be >= 0 (got " + num(g.film.thickness_um) + ")");
  if (!(g.period_nm > 0.0)) return err("period_nm", "fringe period must be positive (got " + num(g.period_nm) + ")");
  if (!(g.wavelength_nm > 0.0))
    return err("wavelength_nm", "wavelength must be positive (got " + num(g.wavelength_nm) + ")");
  if (!(std::abs(g.probe_deg) < 90.0))
    return err("probe_deg", "probe angle inside the film must lie in (-90, 90) degrees (got " + num(g.probe_deg) + ")");
  if (r.absorption_per_mm < 0.0)
    return err("absorption_per_mm", "absorption must be >= 0 (got " + num(r.absorption_per_mm) + ")");
  return std::nullopt;
}

std::variant<GratingRequest, GratingArgError> gratingRequestFromJson(const nlohmann::json& j) {
  if (!j.is_object()) return GratingArgError{"", "expected a JSON object per line"};
  GratingRequest r;
  PlanarGrating& g = r.grating;
  const std::pair<const char*, double*> required[] = {{"n0", &g.film.n0},
                                                      {"n1", &g.film.n1},
                                                      {"thickness_um", &g.film.thickness_um},
                                                      {"period_nm", &g.period_nm},
                                                      {"slant_deg", &g.slant_deg},
                                                      {"probe_deg", &g.probe_deg},
                                                      {"wavelength_nm", &g.wavelength_nm}};
  for (const auto& [key, dst] : required) {
    const auto it = j.find(key);
    if (it == j.end()) return GratingArgError{key, std::string(key) + ": missing"};
    if (!it->is_number()) return GratingArgError{key, std::string(key) + ": must be a number (got " + it->dump() + ")"};
    *dst = it->get<double>();
  }
  if (const auto it = j.find("absorption_per_mm"); it != j.end() && !it->is_null()) {
    if (!it->is_number()) return GratingArgError{"absorption_per_mm", "absorption_per_mm: must be a number"};
    r.absorption_per_mm = it->get<double>();
  }
  if (const auto it = j.find("polarization"); it != j.end() && !it->is_null()) {
    const auto p = it->is_string() ? parsePolarization(it->get<std::string>()) : std::nullopt;
    if (!p) return GratingArgError{"polarization", "polarization: unknown polarisation " + it->dump() + " (s or p)"};
    g.polarization = *p;
  }
  if (const auto it = j.find("model"); it != j.end() && !it->is_null()) {
    if (!it->is_string()) return GratingArgError{"model", "model: must be a string"};
    r.model = it->get<std::string>();
  }
  if (auto e = validateGratingRequest(r, false)) return *e;
  return r;
}

PlanarGrating planarGratingOf(const GratingRequest& r) {
  PlanarGrating g = r.grating;
  g.film.alpha_per_um = 0.5 * r.absorption_per_mm * 1e-3;  // intensity 1/mm -> amplitude 1/µm
  return g;
}

nlohmann::json kogelnikGratingJson(const GratingRequest& r) {
  const PlanarDiffraction d = diffractPlanar(planarGratingOf(r));
  const GratingDiffraction& g = d.grating;
  nlohmann::json j;
  j["efficiency"] = g.kogelnik.efficiency;
  j["type"] = g.reflection() ? "reflection" : "transmission";
  j["nu"] = g.kogelnik.nu;
  j["xi"] = g.kogelnik.xi;
  j["diffracted_deg"] = d.diffracted_deg ? nlohmann::json(*d.diffracted_deg) : nlohmann::json(nullptr);
  j["zero_order"] = g.kogelnik.zero_order;
  j["evanescent"] = g.evanescent;
  j["c_r"] = g.c_r;
  j["c_s"] = g.c_s;
  j["dephasing_per_um"] = g.vartheta;
  j["polarization"] = polarizationName(r.grating.polarization);
  j["model"] = "kogelnik";
  return j;
}

}  // namespace fovea
