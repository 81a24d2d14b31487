#include "model/physics/kogelnik.h"

namespace fovea::kogelnik {

// The double instantiation lives here (one copy of the complex arithmetic in the library).
Result absorbing(double c_r, double c_s, double vartheta, double kappa, double alpha, double d) {
  return absorbingT<double>(c_r, c_s, vartheta, kappa, alpha, d);
}

}  // namespace fovea::kogelnik
