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

}  // namespace fovea
