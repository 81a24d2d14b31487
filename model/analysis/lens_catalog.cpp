#include "model/analysis/lens_catalog.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "model/analysis/optical_glass.h"
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
    l.focal_length_mm = number("focal_length_mm", true, 0);
    l.diameter_mm = number("diameter_mm", true, 0);
    l.center_thickness_mm = number("center_thickness_mm", false, 3.0);
    if (!e.contains("glass")) throw LensCatalogError(at + ".glass: missing (known: " + knownGlassNames() + ")");
    if (!e["glass"].is_string()) throw LensCatalogError(at + ".glass: must be a glass name");
    l.glass = e["glass"].get<std::string>();
    try {
      (void)findOpticalGlass(l.glass);
    } catch (const UnknownGlassError& err) {
      throw LensCatalogError(at + ".glass: " + err.what());
    }
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
  return refractiveIndex(findOpticalGlass(glass), wavelength_nm);
}

}  // namespace fovea
