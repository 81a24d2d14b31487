#include "model/analysis/optical_glass.h"

#include <cmath>

namespace fovea {

const std::vector<OpticalGlass>& opticalGlasses() {
  // Coefficients copied digit for digit from the sources named in `source`.
  static const std::vector<OpticalGlass> glasses = {
      {"N-BK7",
       "SCHOTT data sheet N-BK7 (Zemax catalogue 2017-01-20)",
       {1.03961212, 0.231792344, 1.01046945},
       {0.00600069867, 0.0200179144, 103.560653},
       300.0,
       2500.0},
      {"N-SF11",
       "SCHOTT data sheet N-SF11 (Zemax catalogue 2017-01-20)",
       {1.73759695, 0.313747346, 1.89878101},
       {0.013188707, 0.0623068142, 155.23629},
       370.0,
       2500.0},
      {"N-SF5",
       "SCHOTT data sheet N-SF5 (Zemax catalogue 2017-01-20)",
       {1.52481889, 0.187085527, 1.42729015},
       {0.011254756, 0.0588995392, 129.141675},
       370.0,
       2500.0},
      {"N-LAK22",
       "SCHOTT data sheet N-LAK22 (Zemax catalogue 2017-01-20)",
       {1.14229781, 0.535138441, 1.04088385},
       {0.00585778594, 0.0198546147, 100.834017},
       310.0,
       2500.0},
      // Malitson gives the resonance wavelengths 0.0684043, 0.1162414, 9.896161 um; C_i are
      // their squares.
      {"UVFS",
       "I. H. Malitson, JOSA 55, 1205 (1965), fused silica at 20 C",
       {0.6961663, 0.4079426, 0.8974794},
       {0.0684043 * 0.0684043, 0.1162414 * 0.1162414, 9.896161 * 9.896161},
       210.0,
       3710.0},
  };
  return glasses;
}

std::string knownGlassNames() {
  std::string out;
  for (const OpticalGlass& g : opticalGlasses()) out += (out.empty() ? "" : ", ") + g.name;
  return out;
}

const OpticalGlass& findOpticalGlass(const std::string& name) {
  for (const OpticalGlass& g : opticalGlasses())
    if (g.name == name) return g;
  throw UnknownGlassError("unknown glass \"" + name + "\" (known: " + knownGlassNames() + ")");
}

double refractiveIndex(const OpticalGlass& glass, double wavelength_nm) {
  const double l2 = (wavelength_nm * 1e-3) * (wavelength_nm * 1e-3);
  double n2 = 1.0;
  for (std::size_t i = 0; i < 3; ++i) n2 += glass.b[i] * l2 / (l2 - glass.c[i]);
  return std::sqrt(n2);
}

double abbeNumberD(const OpticalGlass& glass) {
  return (refractiveIndex(glass, kFraunhoferDNm) - 1.0) /
         (refractiveIndex(glass, kFraunhoferFNm) - refractiveIndex(glass, kFraunhoferCNm));
}

}  // namespace fovea
