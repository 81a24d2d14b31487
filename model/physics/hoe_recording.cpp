#include "model/physics/hoe_recording.h"

#include <numbers>

namespace fovea {

LayerModel makeLayerModel(const Hoe& hoe, const HoeLayer& layer) {
  const Frame nominal = frameOf(hoe.pose);
  LayerModel m;
  m.reference_local = nominal.toLocal(toVec(layer.recording.reference_point_mm));
  m.signal_local = nominal.toLocal(toVec(layer.recording.signal_point_mm));
  m.reference_medium_index = m.reference_local.z() > 0.0 ? hoe.substrate_index : hoe.cover_index;
  m.signal_medium_index = m.signal_local.z() > 0.0 ? hoe.substrate_index : hoe.cover_index;
  m.k0_recording = 2.0 * std::numbers::pi / (layer.recording.wavelength_nm * 1e-3);
  m.n_recording = layer.n0 - layer.recording_n0_delta;
  m.shrink_kz_scale = 1.0 / (1.0 + layer.shrinkage_percent / 100.0);
  m.phase_conjugate = layer.recording.phase_conjugate;
  m.film.n0 = layer.n0;
  m.film.n1 = layer.n1;
  m.film.thickness_um = layer.thickness_um;
  m.film.alpha_per_um = 0.5 * layer.absorption_per_mm * 1e-3;  // intensity 1/mm -> amplitude 1/µm
  m.offset_um = layer.offset_um;
  return m;
}

RecordedGrating recordAt(const LayerModel& m, double u_mm, double v_mm) {
  RecordedGrating g;
  const Eigen::Vector3d r(u_mm, v_mm, 0.0);
  const Eigen::Vector3d to_r_from_p = r - m.reference_local, to_f_from_r = m.signal_local - r;
  if (to_r_from_p.squaredNorm() == 0.0 || to_f_from_r.squaredNorm() == 0.0) return g;
  const double k0 = m.k0_recording, n = m.n_recording;
  Eigen::Vector3d k_ref, k_sig;
  if (!m.phase_conjugate) {
    // Direct: reference diverging from P towards r, signal leaving r converging to F.
    if (!waveInFilm(to_r_from_p.normalized(), k0, m.reference_medium_index, n, k_ref)) return g;
    if (!waveInFilm(to_f_from_r.normalized(), k0, m.signal_medium_index, n, k_sig)) return g;
  } else {
    // B.1.2: the film sees the time-reversed pair: a wave diverging from F (towards r) and a
    // wave converging to P (from r). Their wave vectors are -k_sig and -k_ref, so the fringe
    // set {+-(k_a - k_b)} is the direct one; orient it as k_sig - k_ref for reconstruction by
    // the (forward) reference.
    Eigen::Vector3d k_from_f, k_to_p;
    if (!waveInFilm((-to_f_from_r).normalized(), k0, m.signal_medium_index, n, k_from_f)) return g;
    if (!waveInFilm((-to_r_from_p).normalized(), k0, m.reference_medium_index, n, k_to_p)) return g;
    k_sig = -k_from_f;
    k_ref = -k_to_p;
  }
  g.valid = true;
  g.k_reference = k_ref;
  g.k_signal = k_sig;
  g.k_recorded = k_sig - k_ref;
  g.k_recorded.z() *= m.shrink_kz_scale;
  return g;
}

LayerDiffraction diffractLayer(const LayerModel& m, const Eigen::Vector3d& k_recorded, const Eigen::Vector3d& probe_dir,
                               double n_in, double cover_index, double substrate_index, double lambda_nm,
                               Polarization pol) {
  LayerDiffraction out;
  const double lambda_um = lambda_nm * 1e-3;
  const double k0 = 2.0 * std::numbers::pi / lambda_um;
  Eigen::Vector3d rho;
  if (!waveInFilm(probe_dir, k0, n_in, m.film.n0, rho)) return out;
  out.entered = true;
  // sigma = rho - K_kogelnik = rho + K_rec.
  out.grating = diffract3d(rho, -k_recorded, m.film, lambda_um, pol);
  if (out.grating.evanescent) return out;
  const Eigen::Vector3d& kd = out.grating.diffracted;
  out.out_index = kd.z() < 0.0 ? cover_index : substrate_index;
  const double tx = kd.x() / (k0 * out.out_index), ty = kd.y() / (k0 * out.out_index);
  const double t2 = tx * tx + ty * ty;
  if (t2 >= 1.0) {
    out.tir = true;
    return out;
  }
  out.exits = true;
  out.out_dir = Eigen::Vector3d(tx, ty, (kd.z() < 0.0 ? -1.0 : 1.0) * std::sqrt(1.0 - t2));
  return out;
}

}  // namespace fovea
