// The stock lens catalogue shipped in resources/lenses/catalog.json, compiled in so the
// CLI and GUI work without the resource tree (a test keeps the two byte-identical).
#include "model/analysis/lens_catalog.h"

namespace fovea {

const char* defaultLensCatalogJson() {
  return R"json({
  "format": "fovea-lens-catalog",
  "version": 1,
  "notes": "Stock positive singlets, each with its real glass: Thorlabs LA1xxx plano-convex and LB1xxx bi-convex in N-BK7, LA4xxx plano-convex in UV fused silica (UVFS). Focal lengths and diameters are the catalogue values, taken at 587.6 nm (the LA4xxx radii of Thorlabs' Zemax files give f within 0.5 % of nominal there, inside the 1 % tolerance); centre thicknesses are approximate for N-BK7, from the Zemax files for UVFS. Glass names: model/analysis/optical_glass.h.",
  "lenses": [
    {"part": "LA1540", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 15.0, "diameter_mm": 12.7, "center_thickness_mm": 5.1, "glass": "N-BK7"},
    {"part": "LA1074", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 20.0, "diameter_mm": 12.7, "center_thickness_mm": 3.9, "glass": "N-BK7"},
    {"part": "LA1951", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 25.4, "diameter_mm": 25.4, "center_thickness_mm": 11.7, "glass": "N-BK7"},
    {"part": "LA1805", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 30.0, "diameter_mm": 25.4, "center_thickness_mm": 9.0, "glass": "N-BK7"},
    {"part": "LA1027", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 35.0, "diameter_mm": 25.4, "center_thickness_mm": 7.7, "glass": "N-BK7"},
    {"part": "LA1422", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 40.0, "diameter_mm": 25.4, "center_thickness_mm": 6.6, "glass": "N-BK7"},
    {"part": "LA1131", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 50.0, "diameter_mm": 25.4, "center_thickness_mm": 5.3, "glass": "N-BK7"},
    {"part": "LA1134", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 60.0, "diameter_mm": 25.4, "center_thickness_mm": 4.7, "glass": "N-BK7"},
    {"part": "LA1608", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 75.0, "diameter_mm": 25.4, "center_thickness_mm": 4.1, "glass": "N-BK7"},
    {"part": "LA1509", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 100.0, "diameter_mm": 25.4, "center_thickness_mm": 3.6, "glass": "N-BK7"},
    {"part": "LA1433", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 150.0, "diameter_mm": 25.4, "center_thickness_mm": 3.4, "glass": "N-BK7"},
    {"part": "LA4148", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 50.0, "diameter_mm": 25.4, "center_thickness_mm": 5.82, "glass": "UVFS"},
    {"part": "LA4380", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 100.0, "diameter_mm": 25.4, "center_thickness_mm": 3.78, "glass": "UVFS"},
    {"part": "LA4874", "vendor": "Thorlabs", "shape": "plano-convex", "focal_length_mm": 150.0, "diameter_mm": 25.4, "center_thickness_mm": 3.17, "glass": "UVFS"},
    {"part": "LB1761", "vendor": "Thorlabs", "shape": "bi-convex", "focal_length_mm": 25.0, "diameter_mm": 25.4, "center_thickness_mm": 11.7, "glass": "N-BK7"},
    {"part": "LB1471", "vendor": "Thorlabs", "shape": "bi-convex", "focal_length_mm": 50.0, "diameter_mm": 25.4, "center_thickness_mm": 5.3, "glass": "N-BK7"},
    {"part": "LB1676", "vendor": "Thorlabs", "shape": "bi-convex", "focal_length_mm": 100.0, "diameter_mm": 25.4, "center_thickness_mm": 3.6, "glass": "N-BK7"}
  ]
}
)json";
}

}  // namespace fovea
