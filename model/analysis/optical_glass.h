#pragma once
// Optical glasses of the stock lens catalogue by their makers' Sellmeier coefficients:
//   n^2(lambda) = 1 + sum_i B_i lambda^2 / (lambda^2 - C_i),   lambda in um, C_i in um^2.
// Sources (docs/references.md): SCHOTT optical glass data sheets / Zemax catalogue
// 2017-01-20 (N-BK7, N-SF11, N-SF5, N-LAK22); I. H. Malitson, JOSA 55, 1205 (1965) for
// fused silica (the UV fused silica of Thorlabs' LA4xxx lenses, Corning 7980).

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace fovea {

struct OpticalGlass {
  std::string name;                                     // as the catalogue spells it: "N-BK7", "UVFS", ...
  std::string source;                                   // the data sheet the coefficients come from
  std::array<double, 3> b{};                            // Sellmeier B_i (dimensionless)
  std::array<double, 3> c{};                            // Sellmeier C_i (um^2)
  double min_wavelength_nm = 0, max_wavelength_nm = 0;  // where the data sheet says the formula holds
};

class UnknownGlassError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Fraunhofer lines of the Abbe number V_d = (n_d - 1) / (n_F - n_C).
constexpr double kFraunhoferDNm = 587.5618;  // helium d
constexpr double kFraunhoferFNm = 486.1327;  // hydrogen F
constexpr double kFraunhoferCNm = 656.2725;  // hydrogen C

// Every glass the catalogue knows, in a fixed order.
const std::vector<OpticalGlass>& opticalGlasses();
// Throws UnknownGlassError "unknown glass \"X\" (known: N-BK7, ...)".
const OpticalGlass& findOpticalGlass(const std::string& name);
// "N-BK7, N-SF11, ..." for messages.
std::string knownGlassNames();

// Refractive index at `wavelength_nm` (Sellmeier, in air as the data sheets give it).
double refractiveIndex(const OpticalGlass& glass, double wavelength_nm);
double abbeNumberD(const OpticalGlass& glass);

}  // namespace fovea
