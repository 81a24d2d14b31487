#pragma once
// Pointwise recording of an HOE layer (seed A.1, B.1) and its reconstruction at any point.
//
// Recording: at a plate point r the reference wave diverges from the reference point P (the
// projector) and the signal wave converges to the signal focus F (the pupil centre: Maxwellian
// view). Each beam crosses the film face from the medium in which its construction point lies
// (cover on the eye side, local z < 0; substrate on the world side): its tangential wave vector
// k0 n_outside u_t is conserved, its normal component inside the film follows from the film's
// index *during recording*, n_rec = n0 - recording_n0_delta. The recorded fringes are
//     K_rec = k_signal - k_reference                      (issue 4; Kogelnik's K is -K_rec)
// Phase-conjugate recording (B.1.2) exposes the film to the time-reversed pair (a wave
// diverging from F and one converging to P); their fringes are the same set, shown in
// recordAt() by building those beams explicitly (and checked in tests/model/tst_hoe_trace).
//
// Processing (stated model): the film shrinks (s = shrinkage_percent / 100, s < 0 thinner)
// uniformly along its normal only, so a fringe phase K.r is carried to z (1 + s) and
//     K_z -> K_z / (1 + s),  K_t unchanged;
// the reconstruction then sees the processed mean index n0 (kappa from n1, beta = k0 n0). The
// layer's thickness_um is the processed thickness.
//
// Everything here is in the HOE's local frame (scene.h: local +z is the film normal pointing
// to the world side; the eye and the projector are at local z < 0 in the prototype), with the
// plate at its nominal pose: the fringes are attached to plate coordinates (u, v), so a
// shifted plate carries the grating recorded at (u, v) to its new place.

#include <Eigen/Core>

#include "model/physics/grating.h"
#include "model/scene/scene.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

// Wave vector inside a film of index n_film (rad/µm) of a wave travelling along unit `u` in an
// outside medium of index n_out (tangential part conserved). False if it cannot enter.
inline bool waveInFilm(const Eigen::Vector3d& u, double k0, double n_out, double n_film, Eigen::Vector3d& k) {
  const double kx = k0 * n_out * u.x(), ky = k0 * n_out * u.y();
  const double kz2 = k0 * k0 * n_film * n_film - kx * kx - ky * ky;
  if (!(kz2 > 0.0)) return false;
  k = Eigen::Vector3d(kx, ky, (u.z() < 0.0 ? -1.0 : 1.0) * std::sqrt(kz2));
  return true;
}

// One layer, ready to record and reconstruct: everything that does not depend on the point.
struct LayerModel {
  Eigen::Vector3d reference_local = Eigen::Vector3d::Zero();  // P in the HOE local frame (mm)
  Eigen::Vector3d signal_local = Eigen::Vector3d::Zero();     // F in the HOE local frame (mm)
  double reference_medium_index = 1.0, signal_medium_index = 1.0;
  double k0_recording = 0.0;     // 2 pi / lambda_rec (rad/µm)
  double n_recording = 1.5;      // n0 - recording_n0_delta
  double shrink_kz_scale = 1.0;  // 1 / (1 + s)
  bool phase_conjugate = false;
  FilmGrating film;        // processed film: n0, n1, thickness, amplitude absorption
  double offset_um = 0.0;  // depth in the stack along local +z
};

LayerModel makeLayerModel(const Hoe& hoe, const HoeLayer& layer);

struct RecordedGrating {
  bool valid = false;  // false if a recording beam cannot enter the film at this point
  Eigen::Vector3d k_reference = Eigen::Vector3d::Zero();  // inside the film during recording (rad/µm)
  Eigen::Vector3d k_signal = Eigen::Vector3d::Zero();
  Eigen::Vector3d k_recorded = Eigen::Vector3d::Zero();  // K_rec after processing (shrinkage)
};

// The grating at plate point (u, v) mm (local frame, z = 0).
RecordedGrating recordAt(const LayerModel& m, double u_mm, double v_mm);

// Reconstruction of one layer by a probe of unit direction `probe_dir` (local frame, in the
// outside medium of index n_in) at wavelength lambda_nm. `k_recorded` from recordAt().
struct LayerDiffraction {
  bool entered = false;                               // the probe can enter the film
  GratingDiffraction grating;                         // Kogelnik result (efficiency, nu, xi, sigma, diffracted inside)
  bool exits = false;                                 // the diffracted order propagates and leaves the film
  bool tir = false;                                   // ... but is totally internally reflected at the exit face
  Eigen::Vector3d out_dir = Eigen::Vector3d::Zero();  // unit direction after leaving (local frame)
  double out_index = 1.0;                             // index of the medium it leaves into
};
LayerDiffraction diffractLayer(const LayerModel& m, const Eigen::Vector3d& k_recorded, const Eigen::Vector3d& probe_dir,
                               double n_in, double cover_index, double substrate_index, double lambda_nm,
                               Polarization pol);

}  // namespace fovea
