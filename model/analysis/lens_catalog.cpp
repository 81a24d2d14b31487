#include "model/analysis/lens_catalog.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "model/io/json_input.h"

namespace fovea {

std::vector<StockLens> parseLensCatalog(std::string_view text, const std::string& source) {
  auto parsed = parseJsonText(text);
  if (const auto* e = std::get_if<JsonInputError>(&parsed)) throw LensCatalogError(describe(*e, source));
  nlohmann::json j = std::get<nlohmann::json>(std::move(parsed));
  if (!j.is_object() || !j.contains("lenses") || !j["lenses"].is_array())
    throw LensCatalogError(source + ": expected an object with a \"lenses\" array");
  std::vector<StockLens> out;
  for (std::size_t i = 0; i < j["lenses"].size(); ++i) {
    const auto& e = j["lenses"][i];
    const std::string at = source + ": lenses[" + std::to_string(i) + "]";
    if (!e.is_object()) throw LensCatalogError(at + ": must be an object");
    auto number = [&](const char* key, bool required, double fallback) {
      if (!e.contains(key)) {
        if (required) throw LensCatalogError(at + "." + key + ": missing");
        return fallback;
      }
      if (!e[key].is_number()) throw LensCatalogError(at + "." + key + ": must be a number");
      const double v = e[key].get<double>();
      if (!std::isfinite(v) || v <= 0) throw LensCatalogError(at + "." + key + ": must be > 0, got " + e[key].dump());
      return v;
    };
    StockLens l;
    l.part = e.value("part", "lens " + std::to_string(i));
    l.vendor = e.value("vendor", "");
    l.shape = e.value("shape", "");
    l.glass = e.value("glass", "N-BK7");
    l.focal_length_mm = number("focal_length_mm", true, 0);
    l.diameter_mm = number("diameter_mm", true, 0);
    l.center_thickness_mm = number("center_thickness_mm", false, 3.0);
    if (l.glass != "N-BK7") throw LensCatalogError(at + ".glass: unknown glass \"" + l.glass + "\" (known: N-BK7)");
    out.push_back(l);
  }
  if (out.empty()) throw LensCatalogError(source + ": the catalogue lists no lens");
  return out;
}

std::vector<StockLens> loadLensCatalogFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LensCatalogError(path.string() + ": cannot read the file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parseLensCatalog(ss.str(), path.filename().string());
}

std::vector<StockLens> defaultLensCatalog() {
  return parseLensCatalog(defaultLensCatalogJson(), "catalog.json");
}

double glassIndex(const std::string& glass, double wavelength_nm) {
  (void)glass;  // only N-BK7 passes the catalogue loader
  // Schott N-BK7 Sellmeier, lambda in um.
  const double l2 = (wavelength_nm * 1e-3) * (wavelength_nm * 1e-3);
  const double n2 = 1.0 + 1.03961212 * l2 / (l2 - 0.00600069867) + 0.231792344 * l2 / (l2 - 0.0200179144) +
                    1.01046945 * l2 / (l2 - 103.560653);
  return std::sqrt(n2);
}

}  // namespace fovea
