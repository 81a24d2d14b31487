// The stock lens catalogue shipped in resources/lenses/catalog.json, compiled in so the
// CLI and GUI work without the resource tree (a test keeps the two byte-identical).
#include "model/analysis/lens_catalog.h"

namespace fovea {

const char* defaultLensCatalogJson() {
  return R"json({
  "format": "fovea-lens-catalog",
  "version": 1,
  "notes": "Stock N-BK7 positive singlets (Thorlabs LA plano-convex, LB bi-convex). Focal lengths and diameters are the catalogue values at 587.6 nm; centre thicknesses are approximate (they only set the thin-lens reference plane).",
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
    {"part": "LB1761", "vendor": "Thorlabs", "shape": "bi-convex", "focal_length_mm": 25.0, "diameter_mm": 25.4, "center_thickness_mm": 11.7, "glass": "N-BK7"},
    {"part": "LB1471", "vendor": "Thorlabs", "shape": "bi-convex", "focal_length_mm": 50.0, "diameter_mm": 25.4, "center_thickness_mm": 5.3, "glass": "N-BK7"},
    {"part": "LB1676", "vendor": "Thorlabs", "shape": "bi-convex", "focal_length_mm": 100.0, "diameter_mm": 25.4, "center_thickness_mm": 3.6, "glass": "N-BK7"}
  ]
}
)json";
}

}  // namespace fovea
