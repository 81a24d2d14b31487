// The coupled-wave stage of the trace pipeline (trace_stages.h): Kogelnik per ray for one layer
// at one wavelength, with the pupil cull.
#include <algorithm>

#include "model/physics/trace_memo.h"
#include "model/physics/trace_stages.h"

namespace fovea::detail {

void coupledWaveNeed(const GeometryData& g, const LayerDiffractions& dif, const EyePlacement& eye, bool cull_to_pupil,
                     std::vector<std::uint8_t>& need) {
  const std::size_t nh = g.hits(), nl = dif.size();
  need.resize(nh);
  if (!cull_to_pupil) {
    std::fill(need.begin(), need.end(), std::uint8_t{1});
    return;
  }
  // Only the rays that some layer's diffracted order sends through the pupil can enter the eye.
  forRange(nh, [&](std::size_t b, std::size_t e) {
    for (std::size_t h = b; h < e; ++h) {
      std::uint8_t n = 0;
      for (std::size_t i = 0; i < nl && !n; ++i) {
        if (!(dif[i]->flags[h] & kExits)) continue;
        const Eigen::Vector3d dir = g.plate.axes * dif[i]->out_dir[h];
        n = crossPupil(eye, g.hoe_point[g.hit_index[h]], dir).in_pupil;
      }
      need[h] = n;
    }
  });
}

std::uint64_t coupledWaveKey(const Scene& scene, std::size_t layer, std::uint64_t diffraction_key, Polarization pol) {
  const HoeLayer& l = scene.hoe_layers[layer];
  return Hasher("coupled_wave")
      .add(diffraction_key)
      .add(l.n1)
      .add(l.thickness_um)
      .add(l.absorption_per_mm)
      .add(static_cast<int>(pol))
      .value();
}

std::shared_ptr<CoupledWaveData> newCoupledWave(std::size_t hits) {
  auto c = std::make_shared<CoupledWaveData>();
  c->eff.assign(hits, 0.0);
  c->zero.assign(hits, 1.0);
  c->nu.assign(hits, 0.0);
  c->xi.assign(hits, 0.0);
  c->done.assign(hits, 0);
  return c;
}

long long solveCoupledWave(CoupledWaveData& c, const DiffractionData& d, const FilmGrating& film, Polarization pol,
                           const std::vector<std::uint8_t>& need) {
  const std::size_t nh = c.done.size();
  // Rays to solve: needed, entered the film, not yet solved.
  std::vector<int> todo;
  for (std::size_t h = 0; h < nh; ++h)
    if (need[h] && !c.done[h] && (d.flags[h] & kEntered)) todo.push_back(static_cast<int>(h));
  for (std::size_t h = 0; h < nh; ++h)  // rays that never enter need no solve: mark them
    if (need[h] && !c.done[h] && !(d.flags[h] & kEntered)) {
      c.done[h] = 1;
      ++c.done_count;
    }
  if (todo.empty()) return 0;
  forRange(todo.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t t = b; t < e; ++t) {
      const std::size_t h = static_cast<std::size_t>(todo[t]);
      const Obliquity& q = d.obliquity[h];
      DiffractionGeometryT<double> dg;
      dg.c_r = q.c_r;
      dg.c_s = q.c_s;
      dg.vartheta = q.vartheta;
      dg.p_factor = q.p_factor;
      dg.evanescent = (d.flags[h] & kEvanescent) != 0;
      const kogelnik::Result k = layerCoupledWaveT<double>(film, dg, d.lambda_um, pol);
      c.eff[h] = k.efficiency;
      c.zero[h] = k.zero_order;
      c.nu[h] = k.nu;
      c.xi[h] = k.xi;
      c.done[h] = 1;
    }
  });
  c.done_count += static_cast<long long>(todo.size());
  return static_cast<long long>(todo.size());
}

}  // namespace fovea::detail
