#include "model/physics/schematic_eye.h"

#include <cmath>
#include <stdexcept>

#include "model/units.h"

namespace fovea {

RayMatrix operator*(const RayMatrix& l, const RayMatrix& e) {
  return {l.A * e.A + l.B * e.C, l.A * e.B + l.B * e.D, l.C * e.A + l.D * e.C, l.C * e.B + l.D * e.D};
}
RayMatrix freeSpace(double length_mm, double index) {
  return {1.0, length_mm / index, 0.0, 1.0};
}
RayMatrix refraction(double n_before, double n_after, double radius_mm) {
  return {1.0, 0.0, -(n_after - n_before) / radius_mm, 1.0};
}
RayMatrix thinLens(double power_per_mm) {
  return {1.0, 0.0, -power_per_mm, 1.0};
}

std::complex<double> transformQ(const RayMatrix& m, std::complex<double> q) {
  return (m.A * q + m.B) / (m.C * q + m.D);
}

double gaussianRadiusMm(std::complex<double> q, double lambda_mm) {
  // 1/q^ = n/R - i lambda0 / (pi w^2)
  const double im = std::imag(1.0 / q);
  return std::sqrt(-lambda_mm / (kPi * im));
}

double chromaticRefractionD(double wavelength_nm) {
  return 1.68524 - 633.46 / (wavelength_nm - 214.102);
}

NavarroSurfaces navarroSurfaces(double a) {
  const double l = std::log(1.0 + a);
  return {{7.72, 6.50, 10.2 - 1.75 * l, -6.0 + 0.2294 * l},
          {-0.26, 0.0, -3.1316 - 0.34 * l, -1.0 - 0.125 * l},
          {0.55, 3.05 - 0.05 * l, 4.0 + 0.1 * l},
          {1.3771, 1.3374, 1.42 + 9e-5 * (10.0 * a + a * a), 1.3360}};
}

namespace {

// Corneal vertex (air side) to the stop plane (the lens' front vertex, aqueous side).
RayMatrix navarroCorneaToStop(const NavarroSurfaces& s) {
  RayMatrix m = refraction(1.0, s.n[0], s.R[0]);
  m = freeSpace(s.t[0], s.n[0]) * m;
  m = refraction(s.n[0], s.n[1], s.R[1]) * m;
  return freeSpace(s.t[1], s.n[1]) * m;
}

// Corneal vertex (air side) to the lens' back vertex (vitreous side).
RayMatrix navarroCorneaToLensBack(const NavarroSurfaces& s) {
  RayMatrix m = navarroCorneaToStop(s);
  m = refraction(s.n[1], s.n[2], s.R[2]) * m;
  m = freeSpace(s.t[2], s.n[2]) * m;
  return refraction(s.n[2], s.n[3], s.R[3]) * m;
}

// Axial length that makes the relaxed eye emmetropic at the reference wavelength: a ray
// (y, nu) = (1, 0) leaves the lens at (A, C) and meets the axis after d = -A n / C.
double navarroAxialLength() {
  const NavarroSurfaces s = navarroSurfaces(0.0);
  const RayMatrix m = navarroCorneaToLensBack(s);
  return s.t[0] + s.t[1] + s.t[2] - m.A * s.n[3] / m.C;
}

SchematicEyeState navarroBuildEye(double lens_a, double wavelength_nm) {
  const NavarroSurfaces s = navarroSurfaces(lens_a);
  SchematicEyeState e;
  e.lens_parameter_d = lens_a;
  e.wavelength_nm = wavelength_nm;
  e.axial_length_mm = navarroAxialLength();
  e.vitreous_index = s.n[3];
  const RayMatrix stop = navarroCorneaToStop(s);
  // Chief ray (y, u) at the cornea aimed at the stop centre: A y + B u = 0, so it crosses the
  // axis (the entrance pupil) B/A behind the vertex.
  e.entrance_pupil_mm = stop.B / stop.A;
  const double vitreous = e.axial_length_mm - (s.t[0] + s.t[1] + s.t[2]);
  const double chroma_per_mm =
      -(chromaticRefractionD(wavelength_nm) - chromaticRefractionD(kEyeReferenceWavelengthNm)) / 1000.0;
  e.pupil_to_retina = freeSpace(vitreous, s.n[3]) * navarroCorneaToLensBack(s) * freeSpace(-e.entrance_pupil_mm) *
                      thinLens(chroma_per_mm);
  e.retina_mm_per_rad = e.pupil_to_retina.B;
  e.power_d = -e.pupil_to_retina.C * 1000.0;
  return e;
}

}  // namespace

SchematicEyeState navarroEye(double accommodation_d, double wavelength_nm) {
  if (!std::isfinite(accommodation_d) || accommodation_d < 0.0 || accommodation_d > 10.0)
    throw std::invalid_argument("accommodation must be within 0..10 D");
  if (!std::isfinite(wavelength_nm) || wavelength_nm < 380.0 || wavelength_nm > 1000.0)
    throw std::invalid_argument("wavelength must be within 380..1000 nm");
  // In focus at the reference wavelength: a ray of the on-axis point of vergence V at the
  // entrance pupil has slope u = -V y (a point L in front: V = -1/L, u = y/L), so every such
  // ray (y, -V y) must reach the retina at (A - B V) y = 0.
  const double v = -accommodation_d / 1000.0;
  auto miss = [&](double a) {
    const RayMatrix m = navarroBuildEye(a, kEyeReferenceWavelengthNm).pupil_to_retina;
    return m.A - m.B * v;
  };
  double lo = 0.0, hi = 15.0;
  if (accommodation_d > 0.0) {
    // miss() > 0 for the relaxed eye (image behind the retina) and falls as the lens gains power.
    for (int i = 0; i < 80; ++i) {
      const double mid = 0.5 * (lo + hi);
      (miss(mid) > 0.0 ? lo : hi) = mid;
    }
  } else {
    hi = 0.0;
  }
  SchematicEyeState e = navarroBuildEye(0.5 * (lo + hi), wavelength_nm);
  e.accommodation_d = accommodation_d;
  return e;
}

double defocusD(const SchematicEyeState& eye, double vergence_d) {
  const double focus = -eye.accommodation_d +
                       (chromaticRefractionD(eye.wavelength_nm) - chromaticRefractionD(kEyeReferenceWavelengthNm));
  return vergence_d - focus;
}

}  // namespace fovea
