#include "model/physics/grating_request.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "model/io/json_input.h"

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
  if (g.film.thickness_um > 1e7)
    return err("thickness_um", "thickness must be at most 1e7 µm = 10 m (got " + num(g.film.thickness_um) + ")");
  if (!(g.period_nm > 0.0)) return err("period_nm", "fringe period must be positive (got " + num(g.period_nm) + ")");
  if (!(g.wavelength_nm > 0.0))
    return err("wavelength_nm", "wavelength must be positive (got " + num(g.wavelength_nm) + ")");
  if (!(g.period_nm >= 1e-6 * g.wavelength_nm))
    return err("period_nm", "degenerate fringe period: must be at least 1e-6 wavelengths (got " + num(g.period_nm) +
                                " nm at " + num(g.wavelength_nm) + " nm)");
  if (!(std::abs(g.probe_deg) < 90.0))
    return err("probe_deg", "probe angle inside the film must lie in (-90, 90) degrees (got " + num(g.probe_deg) + ")");
  if (r.absorption_per_mm < 0.0)
    return err("absorption_per_mm", "absorption must be >= 0 (got " + num(r.absorption_per_mm) + ")");
  if (r.orders && (*r.orders < 0 || *r.orders > 400))
    return err("orders", "must be an integer in [0, 400] (got " + std::to_string(*r.orders) + ")");
  if (r.slices && (*r.slices < 1 || *r.slices > (1 << 24)))
    return err("slices", "must be an integer in [1, 16777216] (got " + std::to_string(*r.slices) + ")");
  return std::nullopt;
}

namespace {
// "a number", "an array", "the string \"abc…\"": names a value without dumping it (a value can be
// megabytes long or nested thousands of levels deep).
std::string describeValue(const nlohmann::json& v) {
  if (v.is_string()) return "the string \"" + printableExcerpt(v.get_ref<const std::string&>()) + "\"";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_null()) return "null";
  return "a number";
}

// An optional integer key; a message when present but not an integer (1 and 1.0 are accepted).
std::optional<GratingArgError> optionalInteger(const nlohmann::json& j, const char* key, std::optional<int>& out) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return std::nullopt;
  const double v = it->is_number() ? it->get<double>() : std::nan("");
  if (!(std::floor(v) == v && std::abs(v) <= 1e9))
    return GratingArgError{
        key, std::string(key) + ": must be an integer (got " + (it->is_number() ? num(v) : describeValue(*it)) + ")"};
  out = int(v);
  return std::nullopt;
}
}  // namespace

std::variant<GratingRequest, GratingArgError> gratingRequestFromJson(const nlohmann::json& j) {
  if (!j.is_object()) return GratingArgError{"", "expected a JSON object per line, got " + describeValue(j)};
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
    if (!it->is_number())
      return GratingArgError{key, std::string(key) + ": must be a number (got " + describeValue(*it) + ")"};
    *dst = it->get<double>();
  }
  if (const auto it = j.find("absorption_per_mm"); it != j.end() && !it->is_null()) {
    if (!it->is_number())
      return GratingArgError{"absorption_per_mm",
                             "absorption_per_mm: must be a number (got " + describeValue(*it) + ")"};
    r.absorption_per_mm = it->get<double>();
  }
  if (const auto it = j.find("polarization"); it != j.end() && !it->is_null()) {
    const auto p = it->is_string() ? parsePolarization(it->get<std::string>()) : std::nullopt;
    if (!p)
      return GratingArgError{"polarization",
                             "polarization: unknown polarisation " + describeValue(*it) + " (s, p or unpolarized)"};
    g.polarization = *p;
  }
  if (const auto it = j.find("model"); it != j.end() && !it->is_null()) {
    if (!it->is_string()) return GratingArgError{"model", "model: must be a string (got " + describeValue(*it) + ")"};
    r.model = it->get<std::string>();
  }
  if (auto e = optionalInteger(j, "orders", r.orders)) return *e;
  if (auto e = optionalInteger(j, "slices", r.slices)) return *e;
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
  requireFiniteNumbers(j, r);
  return j;
}

void requireFiniteNumbers(const nlohmann::json& answer, const GratingRequest& r) {
  for (const auto& [key, v] : answer.items())
    if (v.is_number_float() && !std::isfinite(v.get<double>()))
      throw std::domain_error(key + ": no finite answer (" + num(v.get<double>()) + ") for this grating (period_nm " +
                              num(r.grating.period_nm) + ", wavelength_nm " + num(r.grating.wavelength_nm) +
                              ", thickness_um " + num(r.grating.film.thickness_um) + ")");
}

}  // namespace fovea
