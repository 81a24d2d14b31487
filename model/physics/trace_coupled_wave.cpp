// The coupled-wave stage of the trace pipeline (trace_stages.h): Kogelnik per ray for one layer
// at one wavelength, with the pupil cull.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "model/physics/kogelnik_batch.h"
#include "model/physics/trace_memo.h"
#include "model/physics/trace_stages.h"

namespace fovea::detail {

namespace {

// Ten arrays of doubles, uninitialised, reused across calls of one thread.
class BatchScratch {
 public:
  void reserve(std::size_t n) {
    if (n <= capacity_) return;
    capacity_ = n;
    data_ = std::make_unique_for_overwrite<double[]>(10 * n);
  }
  double* at(int k) { return data_.get() + k * capacity_; }

 private:
  std::size_t capacity_ = 0;
  std::unique_ptr<double[]> data_;
};

// Kogelnik for the hits todo[b, e) of a lossless film through the SIMD batch (kogelnik_batch.h):
// the same closed forms as layerCoupledWaveT (eta and the zero order within 1e-15 of it; nu and
// xi by the scalar's own expressions, so bit for bit), s and p solved as two batches.
void solveLosslessBatch(CoupledWaveData& c, const DiffractionData& d, const FilmGrating& film, Polarization pol,
                        const std::vector<int>& todo, std::size_t b, std::size_t e) {
  const std::size_t n = e - b;
  const double kappa = std::numbers::pi * film.n1 / d.lambda_um;  // Kogelnik Eq. 8, as layerCoupledWaveT
  const double thickness = film.thickness_um;
  // Per-thread scratch, grown once (no zero-filling per call).
  thread_local BatchScratch scratch;
  scratch.reserve(n);
  double *c_r = scratch.at(0), *c_s = scratch.at(1), *vt = scratch.at(2), *k_s = scratch.at(3), *k_p = scratch.at(4),
         *th = scratch.at(5), *eta = scratch.at(6), *zero = scratch.at(7), *eta_p = scratch.at(8),
         *zero_p = scratch.at(9);
  std::fill(th, th + n, thickness);
  for (std::size_t t = 0; t < n; ++t) {
    const Obliquity& q = d.obliquity[static_cast<std::size_t>(todo[b + t])];
    c_r[t] = q.c_r;
    c_s[t] = q.c_s;
    vt[t] = q.vartheta;
    k_s[t] = kappa;
    k_p[t] = kappa * q.p_factor;
  }
  kogelnik::losslessBatch(c_r, c_s, vt, pol == Polarization::P ? k_p : k_s, th, eta, zero, n);
  if (pol == Polarization::Unpolarized) kogelnik::losslessBatch(c_r, c_s, vt, k_p, th, eta_p, zero_p, n);
  for (std::size_t t = 0; t < n; ++t) {
    const std::size_t h = static_cast<std::size_t>(todo[b + t]);
    // losslessT's nu and xi (zero where it returns early), by its expressions.
    double nu_s = 0, nu_p = 0, xi = 0;
    const double acs = std::abs(c_s[t]);
    if (c_r[t] > 0.0 && thickness > 0.0 && !(acs < kogelnik::kGrazingCs)) {
      const double root = std::sqrt(c_r[t] * acs);
      nu_s = std::abs(k_s[t]) * thickness / root;
      nu_p = std::abs(k_p[t]) * thickness / root;
      xi = std::abs(vt[t]) * thickness / (2.0 * acs);
    }
    double ef = eta[t], zo = zero[t], nu = pol == Polarization::P ? nu_p : nu_s;
    if (pol == Polarization::Unpolarized) {  // detail::polarised: the mean of s and p
      ef = 0.5 * (ef + eta_p[t]);
      zo = 0.5 * (zo + zero_p[t]);
      nu = 0.5 * (nu_s + nu_p);
    }
    if (d.flags[h] & kEvanescent) {  // layerCoupledWaveT: an evanescent order carries nothing
      zo = std::min(1.0, zo + ef);
      ef = 0.0;
    }
    c.eff[h] = ef;
    c.zero[h] = zo;
    c.nu[h] = nu;
    c.xi[h] = xi;
    c.done[h] = 1;
  }
}

}  // namespace

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
  if (!(film.alpha_per_um > 0.0)) {
    // Lossless film (every shipped scene): the SIMD batch.
    forRange(todo.size(), [&](std::size_t b, std::size_t e) { solveLosslessBatch(c, d, film, pol, todo, b, e); });
  } else {
    // Absorbing film: the scalar matrix-exponential path (kogelnik::absorbingT).
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
  }
  c.done_count += static_cast<long long>(todo.size());
  return static_cast<long long>(todo.size());
}

}  // namespace fovea::detail
