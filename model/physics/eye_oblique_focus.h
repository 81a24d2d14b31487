#pragma once
// The schematic eye off its axis (issue 29): oblique astigmatism and field curvature of the
// Navarro eye (schematic_eye.h) for a narrow beam along the chief ray, by Coddington's equations.
//
// The paraxial eye (schematic_eye.h) has one ray matrix for every field angle. A Maxwellian
// pixel beam is narrow (about 1 mm at the pupil) and enters near the pupil centre, so what the
// eye does to it off axis is the focus of a thin pencil along the chief ray: its tangential and
// sagittal foci, which the four conic surfaces split (oblique astigmatism) and which the curved
// retina meets at different distances (field curvature).
//
// Method, in the meridional plane (y up, z from the corneal vertex towards the retina):
//  - the real chief ray: the ray at field angle theta in air that crosses the stop (the lens'
//    front vertex plane) at its centre, found by secant iteration on where it crosses the
//    paraxial entrance-pupil plane (pupil aberration makes that point move off axis);
//  - at each surface (conic: sag z = c r^2 / (1 + sqrt(1 - (1+Q) c^2 r^2))) Snell's law for
//    the ray and Coddington's equations for the pencil (Welford, "Aberrations of Optical
//    Systems", ch. 10; Born & Wolf 4.6), written with the curvatures v = 1/distance along the ray:
//      tangential  n' cos^2 I' v_t' = n cos^2 I v_t + (n' cos I' - n cos I) k_m
//      sagittal    n' v_s'          = n v_s         + (n' cos I' - n cos I) k_s
//    with the surface's principal curvatures at the hit point (derived from the sag z(r):
//    k_s = z' / (r sqrt(1 + z'^2)), k_m = z'' / (1 + z'^2)^(3/2)):
//      k_s = c / (1 - Q c^2 r^2)^(1/2),  k_m = c / (1 - Q c^2 r^2)^(3/2)
//    and the transfer by a distance d along the ray v -> v / (1 - d v);
//  - the retina: the sphere of Escudero-Sanz & Navarro (1999), radius -12 mm, vertex at the
//    axial length (schematic_eye.h); the distance along the chief ray to it, d_r;
//  - the vergence at the entrance pupil (an object point 1/V along the chief ray from where it
//    crosses the paraxial entrance-pupil plane; V < 0: in front) that each pencil focuses on the
//    retina, v'(V) = 1/d_r after the last surface, by secant iteration (the chain is a Moebius
//    map of V, so it converges in a few steps).
// On axis both equal the paraxial eye's focus (-accommodation, at 555 nm); the result is given
// relative to it, as the extra power a thin astigmatic lens at the entrance pupil would add to
// the paraxial eye to focus like the real one at theta:
//      P_t = V_axis - V_t,  P_s = V_axis - V_s  (diopters; > 0: the eye is stronger there).
// Indices are the reference-wavelength ones (the chromatic difference is a thin lens at the
// pupil in schematic_eye.h, the same at every field to this order).
// A beam that enters off the pupil centre: the same pencil along the ray at theta that crosses
// the paraxial entrance-pupil plane h from the chief ray's crossing, in the meridional plane
// (pupil_offset_mm; h > 0 towards the side the ray travels to). On axis this is the zonal
// pencil of the eye's spherical aberration (its tangential power grows about three times as fast
// as its sagittal, as W040 rho^4 curves 12 and 4 W040 h^2); eyePencilPower (below) extends it to
// an offset across the meridional plane, and the retinal image (retinal_psf.h peripheralSpotAt)
// gives each pixel beam the pencil where it enters the pupil. Departures, all stated: a skew
// offset's cross-plane part takes Seidel's form, not a traced skew pencil; the coma across a
// beam's own width is not modelled; the retina's local magnification (distortion) is not applied.

namespace fovea {

struct SchematicEyeState;

// The chief ray's pencil at one field angle and entrance-pupil vergence, after the last surface.
struct ChiefRayFoci {
  bool valid = false;
  double pupil_height_mm = 0;  // where the ray (the chief ray + the offset) crosses the paraxial entrance-pupil plane
  double last_hit_y_mm = 0, last_hit_z_mm = 0;  // on the lens' back surface
  double direction_y = 0, direction_z = 1;      // unit, in the vitreous
  double tangential_mm = 0, sagittal_mm = 0;    // focus distances from the last hit along the ray (inf: collimated)
  double retina_mm = 0;                         // distance from the last hit along the ray to the retina
};

inline constexpr double kMaxPupilOffsetMm = 4.0;  // an 8 mm pupil

// theta in degrees (-60..60, the eye's axis = the line of sight); vergence in diopters;
// pupil_offset_mm: where the ray crosses the entrance-pupil plane, from the chief ray's crossing,
// in the meridional plane (0: the chief ray).
ChiefRayFoci navarroChiefRayFoci(const SchematicEyeState& eye, double field_deg, double vergence_d,
                                 double pupil_offset_mm = 0);

struct EyeObliqueFocus {
  bool valid = false;
  double field_deg = 0;
  double pupil_offset_mm = 0;
  double tangential_d = 0, sagittal_d = 0;              // entrance-pupil vergences focused on the retina (D)
  double axis_d = 0;                                    // the same on axis (= -accommodation at 555 nm)
  double power_tangential_d = 0, power_sagittal_d = 0;  // V_axis - V_t, V_axis - V_s
  double astigmatism_d = 0;                             // |P_t - P_s|
};

// Relative to the axis's chief-ray pencil (axis_d), so a decentred beam's powers carry the
// spherical aberration at its height. Throws std::invalid_argument for a field beyond 60 deg or a
// pupil offset beyond 4 mm.
EyeObliqueFocus eyeObliqueFocus(const SchematicEyeState& eye, double field_deg, double pupil_offset_mm = 0);

// The extra power (D) of the pencil of a beam at field theta that crosses the entrance-pupil
// plane (h_m, h_s) from the chief ray's crossing: h_m in the meridional plane (towards the side
// the ray travels to), h_s across it; the 2 x 2 power in that (meridional, sagittal) basis.
// Exact (traced) for h_s = 0, and on the axis for any direction (rotational symmetry). A skew
// offset takes the Seidel form of the Hessian of W040 rho^4 + W131 theta (rho . tau) rho^2 at h,
// its coefficients measured by the meridional traces at +|h| and -|h| (even part E: spherical
// aberration, 12 and 4 W040 |h|^2; odd part O: coma, 6 and 2 W131 theta |h|), with c = h_m/|h|,
// s = h_s/|h|:
//   P_mm = P_t(0) + E_t c^2 + E_s s^2 + O_t c,   P_ss = P_s(0) + E_s c^2 + E_t s^2 + O_s c,
//   P_ms = (E_t - E_s) c s + O_s s.
struct EyePencilPower {
  bool valid = false;
  double meridional_d = 0, sagittal_d = 0, cross_d = 0;
};
EyePencilPower eyePencilPower(const SchematicEyeState& eye, double field_deg, double offset_meridional_mm,
                              double offset_sagittal_mm);

}  // namespace fovea
