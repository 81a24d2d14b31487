#pragma once
// An accommodating schematic eye for retinal image quality (issue 29), paraxial.
//
// Surfaces: the Navarro, Santamaria & Bescos (1985) accommodation-dependent schematic eye
// (J. Opt. Soc. Am. A 2, 1273), used here paraxially as a thick four-surface system (the
// conic constants only matter off the paraxial region and are not used). With the lens
// parameter A (diopters of accommodation stimulus in Navarro's formulae), distances in mm:
//   cornea      R1 = 7.72, t = 0.55, n = 1.3771;   R2 = 6.50, aqueous t = 3.05 - 0.05 ln(1+A), n = 1.3374
//   lens        R3 = 10.2 - 1.75 ln(1+A),  t = 4.0 + 0.1 ln(1+A),  n = 1.42 + 9e-5 (10 A + A^2)
//               R4 = -6.0 + 0.2294 ln(1+A), vitreous n = 1.3360 to the retina.
// The iris (aperture stop) sits at the lens' front vertex. Departures, all stated:
//  - the retina is placed at the paraxial focus of the unaccommodated eye at the reference
//    wavelength (555 nm), so the relaxed eye is exactly emmetropic (Navarro's tabulated
//    vitreous, 16.40 mm, gives the same to within ~0.1 D);
//  - "accommodation D" is the vergence, at the entrance pupil, of the object the eye is
//    focused on at 555 nm: D = 1/distance (m) from the pupil plane. A is found for it by
//    bisection (A and D differ by a few percent; Navarro's A is a stimulus value);
//  - dispersion: the chromatic difference of refraction of the "chromatic eye" of Thibos,
//    Ye, Zhang & Bradley (1992, Appl. Opt. 31, 3594), Rx(lambda) = 1.68524 - 633.46/(lambda - 214.102)
//    (diopters, lambda in nm), relative to 555 nm, added as a thin lens at the entrance pupil
//    of power -(Rx(lambda) - Rx(555)); the indices above are the reference-wavelength ones.
//
// Ray-transfer matrices act on reduced rays (y, n u): translation by t in index n is
// [[1, t/n], [0, 1]], refraction at radius R from n to n' is [[1, 0], [-(n'-n)/R, 1]], a thin
// lens of power P is [[1, 0], [-P, 1]] (powers in 1/mm). A Gaussian beam's reduced complex
// radius q^ = q/n transforms as q^' = (A q^ + B)/(C q^ + D) and its 1/e^2 intensity radius is
// w^2 = -lambda0 / (pi Im(1/q^)) (Siegman, "Lasers", ch. 20; lambda0 the vacuum wavelength,
// or M^2 lambda0 for an embedded Gaussian).
//
// The trace (eye_model.h, placeEye) keeps its pupil disc as the aperture; this eye is placed
// with its entrance pupil on that disc, so both agree where light enters.

#include <complex>

namespace fovea {

struct RayMatrix {
  double A = 1, B = 0, C = 0, D = 1;
};
RayMatrix operator*(const RayMatrix& later, const RayMatrix& earlier);
RayMatrix freeSpace(double length_mm, double index = 1.0);
RayMatrix refraction(double n_before, double n_after, double radius_mm);
RayMatrix thinLens(double power_per_mm);

// q^' = (A q^ + B) / (C q^ + D).
std::complex<double> transformQ(const RayMatrix& m, std::complex<double> q_reduced);
// 1/e^2 intensity radius (mm) of a beam of reduced complex radius q^ and (effective) vacuum
// wavelength lambda_mm.
double gaussianRadiusMm(std::complex<double> q_reduced, double lambda_mm);

inline constexpr double kEyeReferenceWavelengthNm = 555.0;

// Thibos et al. (1992) chromatic difference of refraction (diopters), 0 at ~590 nm.
double chromaticRefractionD(double wavelength_nm);

// The Navarro eye's surfaces for lens parameter A (Navarro's formulae above; indices at the
// reference wavelength), with their conic constants, which only the off-axis trace
// (eye_oblique_focus.h) uses: cornea -0.26 and 0, lens -3.1316 - 0.34 ln(1+A) and
// -1 - 0.125 ln(1+A) (Navarro et al. 1985). Surface sag z = c r^2 / (1 + sqrt(1 - (1+Q) c^2 r^2)).
struct NavarroSurfaces {
  double R[4];  // mm
  double Q[4];  // conic constants
  double t[3];  // cornea, aqueous, lens thickness (mm)
  double n[4];  // cornea, aqueous, lens, vitreous
};
NavarroSurfaces navarroSurfaces(double lens_parameter_d);
// The retina of the wide-angle version of the eye (Escudero-Sanz & Navarro 1999, JOSA A 16,
// 1881): a sphere of radius -12 mm, its vertex at the axial length.
inline constexpr double kNavarroRetinaRadiusMm = -12.0;

struct SchematicEyeState {
  double accommodation_d = 0;   // requested: vergence in focus at the entrance pupil (555 nm)
  double lens_parameter_d = 0;  // Navarro's A that achieves it
  double wavelength_nm = kEyeReferenceWavelengthNm;
  double entrance_pupil_mm = 0;  // entrance pupil behind the corneal vertex
  double axial_length_mm = 0;    // corneal vertex to retina
  double vitreous_index = 1.336;
  RayMatrix pupil_to_retina;     // from the entrance-pupil plane (in air) to the retina
  double retina_mm_per_rad = 0;  // B of pupil_to_retina: chief-ray image height per radian
  double power_d = 0;            // equivalent power of the eye (-C * 1000)
};

// The eye accommodated to accommodation_d (0..10 D accepted; the issue asks 0..4) at a wavelength.
SchematicEyeState navarroEye(double accommodation_d, double wavelength_nm = kEyeReferenceWavelengthNm);

// Defocus (diopters) of light arriving with vergence `vergence_d` at the entrance pupil (a
// point at distance L in front of the pupil has vergence -1/L) for the eye `eye`:
// vergence minus the vergence the eye focuses at that wavelength.
double defocusD(const SchematicEyeState& eye, double vergence_d);

}  // namespace fovea
