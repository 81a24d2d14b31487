#include "model/physics/grating.h"

#include <algorithm>
#include <cctype>

namespace fovea {

std::optional<Polarization> parsePolarization(const std::string& text) {
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (t == "s" || t == "te") return Polarization::S;
  if (t == "p" || t == "tm") return Polarization::P;
  if (t == "u" || t == "unpolarized" || t == "unpolarised") return Polarization::Unpolarized;
  return std::nullopt;
}

const char* polarizationName(Polarization p) {
  switch (p) {
    case Polarization::S:
      return "s";
    case Polarization::P:
      return "p";
    case Polarization::Unpolarized:
      return "unpolarized";
  }
  return "?";
}

PlanarDiffraction diffractPlanar(const PlanarGrating& g) {
  return diffractPlanarT<double>(g);
}

}  // namespace fovea
