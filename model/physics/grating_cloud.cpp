#include "model/physics/grating_cloud.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "model/physics/hoe_recording.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

std::vector<GratingVectorSample> gratingVectorCloud(const Scene& scene, const std::vector<TracedRay>& rays,
                                                    const std::array<double, 2>& hoe_shift_mm, std::size_t max_samples,
                                                    Polarization polarization) {
  std::vector<GratingVectorSample> out;
  if (scene.hoe_layers.empty() || max_samples == 0) return out;
  const Frame nominal = frameOf(scene.hoe.pose);
  Frame plate = nominal;
  plate.origin += hoe_shift_mm[0] * nominal.x() + hoe_shift_mm[1] * nominal.y();
  std::vector<LayerModel> layers;
  for (const auto& l : scene.hoe_layers) layers.push_back(makeLayerModel(scene.hoe, l));

  std::size_t on_plate = 0;
  for (const auto& r : rays) on_plate += r.hits_hoe ? 1 : 0;
  const std::size_t stride = std::max<std::size_t>(1, (on_plate + max_samples - 1) / max_samples);
  std::size_t seen = 0;
  for (const TracedRay& r : rays) {
    if (!r.hits_hoe) continue;
    if (seen++ % stride != 0) continue;
    // The layer recorded nearest this wavelength (its own colour in an RGB stack).
    int li = 0;
    for (int i = 1; i < static_cast<int>(scene.hoe_layers.size()); ++i)
      if (std::abs(scene.hoe_layers[i].recording.wavelength_nm - r.wavelength_nm) <
          std::abs(scene.hoe_layers[li].recording.wavelength_nm - r.wavelength_nm))
        li = i;
    const LayerModel& m = layers[static_cast<std::size_t>(li)];
    const Eigen::Vector3d p = plate.toLocal(r.hoe_point);
    const RecordedGrating g = recordAt(m, p.x(), p.y());
    if (!g.valid) continue;
    const Eigen::Vector3d d = plate.axes.transpose() * r.projector_direction;
    const Eigen::Vector3d source_local = plate.toLocal(r.source);
    const double n_in = source_local.z() < 0.0 ? scene.hoe.cover_index : scene.hoe.substrate_index;
    const double k0 = 2.0 * std::numbers::pi / (r.wavelength_nm * 1e-3);
    Eigen::Vector3d rho;
    if (!waveInFilm(d, k0, n_in, m.film.n0, rho)) continue;
    const LayerDiffraction ld = diffractLayer(m, g.k_recorded, d, n_in, scene.hoe.cover_index,
                                              scene.hoe.substrate_index, r.wavelength_nm, polarization);
    if (!ld.entered || ld.grating.evanescent) continue;
    GratingVectorSample s;
    s.plate_point_mm = Eigen::Vector3d(p.x(), p.y(), 0.0);
    s.k_recorded = g.k_recorded;
    s.k_probe = ld.grating.diffracted - rho;
    s.wavelength_nm = r.wavelength_nm;
    s.efficiency = ld.grating.kogelnik.efficiency;
    s.layer = li;
    out.push_back(s);
  }
  return out;
}

}  // namespace fovea
