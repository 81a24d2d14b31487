#pragma once
// Stock convex lenses for beam shaping (resources/lenses/catalog.json).

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fovea {

struct StockLens {
  std::string part, vendor, shape, glass = "N-BK7";
  double focal_length_mm = 50.0;  // at the d line, 587.6 nm
  double diameter_mm = 25.4;
  double center_thickness_mm = 3.0;
};

class LensCatalogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses a catalogue; throws LensCatalogError "<source>: lenses[3].focal_length_mm: must be > 0".
// Every lens names its glass ("glass": one of knownGlassNames()); an unknown or missing one is
// an error naming it.
std::vector<StockLens> parseLensCatalog(std::string_view text, const std::string& source);
std::vector<StockLens> loadLensCatalogFile(const std::filesystem::path& path);
const char* defaultLensCatalogJson();
std::vector<StockLens> defaultLensCatalog();

// Refractive index of a catalogue glass at `wavelength_nm` (Sellmeier, model/analysis/
// optical_glass.h); throws UnknownGlassError naming a glass it does not know.
double glassIndex(const std::string& glass, double wavelength_nm);

}  // namespace fovea
