#pragma once
// Pointwise recording of an HOE layer (seed A.1, B.1) and its reconstruction at any point.
//
// Recording: at a plate point r the reference wave diverges from the reference point P (the
// projector) and the signal wave converges to the signal focus F (the pupil centre: Maxwellian
// view). Each beam crosses the film face from the medium in which its construction point lies
// (cover on the eye side, local z < 0; substrate on the world side): its tangential wave vector
// k0 n_outside u_t is conserved, its normal component inside the film follows from the film's
// index *during recording*, n_rec = n0 - recording_n0_delta. The recorded fringes are
//     K_rec = k_signal - k_reference                      (seed A.1; Kogelnik's K is -K_rec)
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

#include <cmath>
#include <numbers>

#include <Eigen/Core>

#include "model/physics/grating.h"
#include "model/scene/scene.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

// Wave vector inside a film of index n_film (rad/µm) of a wave travelling along unit `u` in an
// outside medium of index n_out (tangential part conserved). False if it cannot enter.
template <class T>
inline bool waveInFilmT(const Vec3T<T>& u, T k0, T n_out, T n_film, Vec3T<T>& k) {
  const T kx = k0 * n_out * u.x(), ky = k0 * n_out * u.y();
  const T kz2 = k0 * k0 * n_film * n_film - kx * kx - ky * ky;
  if (!(kz2 > T(0))) return false;
  k = Vec3T<T>(kx, ky, (u.z() < T(0) ? T(-1) : T(1)) * std::sqrt(kz2));
  return true;
}
inline bool waveInFilm(const Eigen::Vector3d& u, double k0, double n_out, double n_film, Eigen::Vector3d& k) {
  return waveInFilmT<double>(u, k0, n_out, n_film, k);
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

template <class T>
struct RecordedGratingT {
  bool valid = false;                       // false if a recording beam cannot enter the film at this point
  Vec3T<T> k_reference = Vec3T<T>::Zero();  // inside the film during recording (rad/µm)
  Vec3T<T> k_signal = Vec3T<T>::Zero();
  Vec3T<T> k_recorded = Vec3T<T>::Zero();  // K_rec after processing (shrinkage)
};
using RecordedGrating = RecordedGratingT<double>;

// The grating at plate point (u, v) mm (local frame, z = 0), evaluated in T.
template <class T>
RecordedGratingT<T> recordAtT(const LayerModel& m, T u_mm, T v_mm) {
  RecordedGratingT<T> g;
  const Vec3T<T> r(u_mm, v_mm, T(0));
  const Vec3T<T> to_r_from_p = r - m.reference_local.cast<T>(), to_f_from_r = m.signal_local.cast<T>() - r;
  if (to_r_from_p.squaredNorm() == T(0) || to_f_from_r.squaredNorm() == T(0)) return g;
  const T k0 = T(m.k0_recording), n = T(m.n_recording);
  const T n_ref = T(m.reference_medium_index), n_sig = T(m.signal_medium_index);
  Vec3T<T> k_ref, k_sig;
  if (!m.phase_conjugate) {
    // Direct: reference diverging from P towards r, signal leaving r converging to F.
    if (!waveInFilmT<T>(to_r_from_p.normalized(), k0, n_ref, n, k_ref)) return g;
    if (!waveInFilmT<T>(to_f_from_r.normalized(), k0, n_sig, n, k_sig)) return g;
  } else {
    // B.1.2: the film sees the time-reversed pair: a wave diverging from F (towards r) and a
    // wave converging to P (from r). Their wave vectors are -k_sig and -k_ref, so the fringe
    // set {+-(k_a - k_b)} is the direct one; orient it as k_sig - k_ref for reconstruction by
    // the (forward) reference.
    Vec3T<T> k_from_f, k_to_p;
    if (!waveInFilmT<T>((-to_f_from_r).normalized(), k0, n_sig, n, k_from_f)) return g;
    if (!waveInFilmT<T>((-to_r_from_p).normalized(), k0, n_ref, n, k_to_p)) return g;
    k_sig = -k_from_f;
    k_ref = -k_to_p;
  }
  g.valid = true;
  g.k_reference = k_ref;
  g.k_signal = k_sig;
  g.k_recorded = k_sig - k_ref;
  g.k_recorded.z() *= T(m.shrink_kz_scale);
  return g;
}
inline RecordedGrating recordAt(const LayerModel& m, double u_mm, double v_mm) {
  return recordAtT<double>(m, u_mm, v_mm);
}

// Reconstruction of one layer by a probe of unit direction `probe_dir` (local frame, in the
// outside medium of index n_in) at wavelength lambda_nm. `k_recorded` from recordAt().
template <class T>
struct LayerDiffractionT {
  bool entered = false;                 // the probe can enter the film
  GratingDiffractionT<T> grating;       // Kogelnik result (efficiency, nu, xi, sigma, diffracted inside)
  bool exits = false;                   // the diffracted order propagates and leaves the film
  bool tir = false;                     // ... but is totally internally reflected at the exit face
  Vec3T<T> out_dir = Vec3T<T>::Zero();  // unit direction after leaving (local frame)
  T out_index = 1;                      // index of the medium it leaves into
};
using LayerDiffraction = LayerDiffractionT<double>;

// Where the diffracted order of a layer goes (no coupled-wave solve): the exit refraction of
// the physical diffracted wave vector kd (inside the film) into cover (kd_z < 0) or substrate.
template <class T>
inline void exitDirectionT(const Vec3T<T>& kd, T k0, T cover_index, T substrate_index, bool& exits, bool& tir,
                           Vec3T<T>& out_dir, T& out_index) {
  out_index = kd.z() < T(0) ? cover_index : substrate_index;
  const T tx = kd.x() / (k0 * out_index), ty = kd.y() / (k0 * out_index);
  const T t2 = tx * tx + ty * ty;
  if (t2 >= T(1)) {
    tir = true;
    return;
  }
  exits = true;
  out_dir = Vec3T<T>(tx, ty, (kd.z() < T(0) ? T(-1) : T(1)) * std::sqrt(T(1) - t2));
}

// The geometric half of diffractLayer (everything before the coupled-wave solve): does the
// probe enter, where does the diffracted order go. The trace pipeline runs it for every ray
// and keeps the coupled-wave step for the rays that can matter.
template <class T>
struct LayerGeometryT {
  bool entered = false, evanescent = false, exits = false, tir = false;
  DiffractionGeometryT<T> geometry;     // c_R, c_S, vartheta, p factor, sigma, diffracted (inside)
  Vec3T<T> out_dir = Vec3T<T>::Zero();  // unit direction after leaving (local frame) when exits
  T out_index = 1;
};

template <class T>
LayerGeometryT<T> layerGeometryT(const FilmGratingT<T>& film, const Vec3T<T>& k_recorded, const Vec3T<T>& probe_dir,
                                 T n_in, T cover_index, T substrate_index, T lambda_um) {
  LayerGeometryT<T> out;
  const T k0 = T(2) * std::numbers::pi_v<T> / lambda_um;
  Vec3T<T> rho;
  if (!waveInFilmT<T>(probe_dir, k0, n_in, film.n0, rho)) return out;
  out.entered = true;
  // sigma = rho - K_kogelnik = rho + K_rec.
  const T beta = T(2) * std::numbers::pi_v<T> * film.n0 / lambda_um;
  out.geometry = diffractionGeometryT<T>(rho, (-k_recorded).eval(), beta);
  out.evanescent = out.geometry.evanescent;
  if (out.evanescent) return out;
  exitDirectionT<T>(out.geometry.diffracted, k0, cover_index, substrate_index, out.exits, out.tir, out.out_dir,
                    out.out_index);
  return out;
}

// The coupled-wave half: Kogelnik for a layer whose geometry is known (evanescent orders carry
// nothing: their share stays in the zero order).
template <class T>
kogelnik::ResultT<T> layerCoupledWaveT(const FilmGratingT<T>& film, const DiffractionGeometryT<T>& g, T lambda_um,
                                       Polarization pol) {
  const T kappa = std::numbers::pi_v<T> * film.n1 / lambda_um;  // Kogelnik Eq. 8, lossless modulation
  kogelnik::ResultT<T> k =
      detail::polarised<T>(g.c_r, g.c_s, g.vartheta, kappa, g.p_factor, film.alpha_per_um, film.thickness_um, pol);
  if (g.evanescent) {
    k.zero_order = std::min(T(1), k.zero_order + k.efficiency);
    k.efficiency = T(0);
  }
  return k;
}

template <class T>
LayerDiffractionT<T> diffractLayerT(const LayerModel& m, const Vec3T<T>& k_recorded, const Vec3T<T>& probe_dir, T n_in,
                                    T cover_index, T substrate_index, T lambda_nm, Polarization pol) {
  LayerDiffractionT<T> out;
  const T lambda_um = lambda_nm * (T(1) / T(1000));
  const FilmGratingT<T> film = m.film.cast<T>();
  const LayerGeometryT<T> lg =
      layerGeometryT<T>(film, k_recorded, probe_dir, n_in, cover_index, substrate_index, lambda_um);
  if (!lg.entered) return out;
  out.entered = true;
  out.grating.kogelnik = layerCoupledWaveT<T>(film, lg.geometry, lambda_um, pol);
  out.grating.c_r = lg.geometry.c_r;
  out.grating.c_s = lg.geometry.c_s;
  out.grating.vartheta = lg.geometry.vartheta;
  out.grating.p_factor = lg.geometry.p_factor;
  out.grating.sigma = lg.geometry.sigma;
  out.grating.diffracted = lg.geometry.diffracted;
  out.grating.evanescent = lg.evanescent;
  out.exits = lg.exits;
  out.tir = lg.tir;
  out.out_dir = lg.out_dir;
  out.out_index = lg.out_index;
  return out;
}
inline LayerDiffraction diffractLayer(const LayerModel& m, const Eigen::Vector3d& k_recorded,
                                      const Eigen::Vector3d& probe_dir, double n_in, double cover_index,
                                      double substrate_index, double lambda_nm, Polarization pol) {
  return diffractLayerT<double>(m, k_recorded, probe_dir, n_in, cover_index, substrate_index, lambda_nm, pol);
}

}  // namespace fovea
