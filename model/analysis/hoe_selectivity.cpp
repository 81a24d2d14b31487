#include "model/analysis/hoe_selectivity.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "model/physics/hoe_recording.h"
#include "model/physics/projector_rays.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea {

namespace {

double closestWavelength(const std::vector<double>& available, double target) {
  double best = target, dist = INFINITY;
  for (double w : available)
    if (std::abs(w - target) < dist) dist = std::abs(w - target), best = w;
  return best;
}

SelectivitySample sampleAt(const LayerModel& m, const RecordedGrating& g, const Eigen::Vector3d& dir, double n_in,
                           const Hoe& hoe, double lambda_nm, Polarization pol, double x) {
  SelectivitySample s;
  s.x = x;
  const LayerDiffraction d =
      diffractLayer(m, g.k_recorded, dir, n_in, hoe.cover_index, hoe.substrate_index, lambda_nm, pol);
  s.entered = d.entered;
  if (!d.entered) return s;
  // The light that leaves the film in the diffracted order (0 when evanescent or trapped).
  s.efficiency = d.exits ? d.grating.kogelnik.efficiency : 0.0;
  // Kogelnik's xi is |vartheta| d / (2 |c_S|); keep the sign of the dephasing so the Bragg
  // condition shows as a sign change.
  s.xi = std::copysign(d.grating.kogelnik.xi, d.grating.vartheta);
  s.nu = d.grating.kogelnik.nu;
  return s;
}

std::size_t peakIndex(const std::vector<SelectivitySample>& c) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < c.size(); ++i)
    if (c[i].efficiency > c[best].efficiency) best = i;
  return best;
}

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(static_cast<std::size_t>(std::max(n, 1)));
  if (n <= 1) {
    v[0] = 0.5 * (a + b);
    return v;
  }
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = a + (b - a) * i / (n - 1);
  return v;
}

}  // namespace

std::optional<double> fullWidthHalfMax(const std::vector<SelectivitySample>& c) {
  if (c.size() < 3) return std::nullopt;
  const std::size_t p = peakIndex(c);
  const double half = 0.5 * c[p].efficiency;
  if (!(half > 0.0)) return std::nullopt;
  auto crossing = [&](std::size_t inside, std::size_t outside) {
    const double y0 = c[inside].efficiency, y1 = c[outside].efficiency;
    const double t = (y0 - half) / (y0 - y1);
    return c[inside].x + t * (c[outside].x - c[inside].x);
  };
  std::optional<double> left, right;
  for (std::size_t i = p; i > 0; --i)
    if (c[i - 1].efficiency < half) {
      left = crossing(i, i - 1);
      break;
    }
  for (std::size_t i = p; i + 1 < c.size(); ++i)
    if (c[i + 1].efficiency < half) {
      right = crossing(i, i + 1);
      break;
    }
  if (!left || !right) return std::nullopt;
  return *right - *left;
}

SelectivityResult analyzeSelectivity(const Scene& scene, const SelectivityOptions& o) {
  SelectivityResult out;
  out.point_mm = o.point_mm;
  const Frame plate = frameOf(scene.hoe.pose);
  const Eigen::Vector3d source_local = plate.toLocal(projectorSource(scene.projector, 0.0));
  const Eigen::Vector3d point(o.point_mm[0], o.point_mm[1], 0.0);
  const Eigen::Vector3d nominal = (point - source_local).normalized();
  const double n_in = source_local.z() < 0.0 ? scene.hoe.cover_index : scene.hoe.substrate_index;
  // Film normal on the probe's side of travel, and the axis that tilts the probe away from it.
  const Eigen::Vector3d normal(0.0, 0.0, nominal.z() >= 0.0 ? 1.0 : -1.0);
  Eigen::Vector3d axis = normal.cross(nominal);
  axis = axis.norm() > 1e-12 ? axis.normalized() : Eigen::Vector3d::UnitY();
  const double incidence_deg = std::acos(std::clamp(std::abs(nominal.z()), 0.0, 1.0)) / kDeg;

  for (const HoeLayer& layer : scene.hoe_layers) {
    LayerSelectivity ls;
    ls.name = layer.name;
    ls.recording_wavelength_nm = layer.recording.wavelength_nm;
    ls.probe_wavelength_nm = closestWavelength(scene.projector.wavelengths_nm, layer.recording.wavelength_nm);
    ls.incidence_deg = incidence_deg;
    const LayerModel m = makeLayerModel(scene.hoe, layer);
    const RecordedGrating g = recordAt(m, point.x(), point.y());
    ls.valid = g.valid;
    if (g.valid) {
      for (double delta : linspace(-o.angle_span_deg, o.angle_span_deg, o.angle_samples)) {
        const Eigen::Vector3d dir = Eigen::AngleAxisd(delta * kDeg, axis) * nominal;
        ls.angle.push_back(sampleAt(m, g, dir, n_in, scene.hoe, ls.probe_wavelength_nm, o.polarization, delta));
      }
      const double w0 = ls.probe_wavelength_nm;
      for (double w : linspace(w0 - o.wavelength_span_nm, w0 + o.wavelength_span_nm, o.wavelength_samples)) {
        if (!(w > 0.0)) continue;
        ls.spectrum.push_back(sampleAt(m, g, nominal, n_in, scene.hoe, w, o.polarization, w));
      }
      const SelectivitySample nom = sampleAt(m, g, nominal, n_in, scene.hoe, w0, o.polarization, 0.0);
      ls.nominal_efficiency = nom.efficiency;
      ls.nominal_xi = nom.xi;
      if (!ls.angle.empty()) {
        const auto& pk = ls.angle[peakIndex(ls.angle)];
        ls.peak_detuning_deg = pk.x;
        ls.peak_angle_efficiency = pk.efficiency;
        ls.angular_fwhm_deg = fullWidthHalfMax(ls.angle);
      }
      if (!ls.spectrum.empty()) {
        const auto& pk = ls.spectrum[peakIndex(ls.spectrum)];
        ls.peak_wavelength_nm = pk.x;
        ls.peak_spectral_efficiency = pk.efficiency;
        ls.spectral_fwhm_nm = fullWidthHalfMax(ls.spectrum);
      }
    }
    out.layers.push_back(std::move(ls));
  }
  return out;
}

}  // namespace fovea
