#pragma once
// RCWA problems shared by the RCWA tests (tests/model/tst_rcwa.cpp) and their benchmarks
// (benchmarks/bench_rcwa.cpp), so the timings are of the very case the tests check. Plain C++:
// no Qt, since the benchmarks do not link it.
#include "model/rigorous/rcwa.h"

namespace fovea::testing {

// A strong slanted grating (n1 0.06, 3 um, 420 nm period, 60 deg slant, 532 nm) with several
// propagating orders, lit from the cover at -7.5 deg: near Bragg for order +1 (film angle about
// -5 deg).
inline rigorous::RcwaProblem strongSlanted(rigorous::RcwaPolarization pol) {
  rigorous::RcwaProblem p;
  p.n0 = 1.5;
  p.n1 = 0.06;
  p.thickness_um = 3.0;
  p.period_nm = 420.0;
  p.slant_deg = 60.0;
  p.wavelength_nm = 532.0;
  p.n_cover = 1.0;
  p.n_substrate = 1.6;
  p.polarization = pol;
  p.setCoverAngleDeg(-7.5);
  return p;
}

}  // namespace fovea::testing
