// The trace pipeline's stages (trace_stages.h), except the coupled wave
// (trace_coupled_wave.cpp).
#include "model/physics/trace_stages.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "model/physics/trace_internal.h"
#include "model/physics/trace_memo.h"

namespace fovea::detail {

std::string wavelengthLabel(double nm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%gnm", nm);
  return buf;
}

LayerSetup layerSetup(const Scene& scene) {
  const std::size_t nl = scene.hoe_layers.size();
  LayerSetup out;
  out.label.resize(nl);
  for (std::size_t i = 0; i < nl; ++i) {
    const std::string& name = scene.hoe_layers[i].name;
    const bool unique = !name.empty() && std::count_if(scene.hoe_layers.begin(), scene.hoe_layers.end(),
                                                       [&](const HoeLayer& l) { return l.name == name; }) == 1;
    out.label[i] = unique ? name : "#" + std::to_string(i);
  }
  out.order.resize(nl);
  std::iota(out.order.begin(), out.order.end(), 0);
  std::stable_sort(out.order.begin(), out.order.end(),
                   [&](int a, int b) { return scene.hoe_layers[a].offset_um < scene.hoe_layers[b].offset_um; });
  // Memoised stages hold only what their keys cover (a diffraction stage knows n0, not n1 or
  // the thickness): the coupled wave reads the films from here.
  out.film.resize(nl);
  for (std::size_t i = 0; i < nl; ++i) out.film[i] = makeLayerModel(scene.hoe, scene.hoe_layers[i]).film;
  return out;
}

// ---- geometry ---------------------------------------------------------------------------
std::uint64_t geometryKey(const Scene& scene, const TraceOptions& o) {
  return Hasher("geometry")
      .add(scene.projector.pose)
      .add(scene.projector.fov_deg)
      .add(scene.projector.pixels)
      .add(o.rays)
      .add(o.source_shift_mm)
      .add(scene.hoe.pose)
      .add(scene.hoe.size_mm)
      .add(o.hoe_shift_mm)
      .value();
}

std::shared_ptr<GeometryData> computeGeometry(const Scene& scene, const TraceOptions& o) {
  auto geo = std::make_shared<GeometryData>();
  GeometryData& g = *geo;
  const Frame nominal = frameOf(scene.hoe.pose);
  g.plate = nominal;
  g.plate.origin += o.hoe_shift_mm[0] * nominal.x() + o.hoe_shift_mm[1] * nominal.y();
  g.source = projectorSource(scene.projector, o.source_shift_mm);
  g.source_local = g.plate.toLocal(g.source);
  g.grid = projectorRays(scene.projector, o.rays);
  const std::size_t n = g.grid.size();
  g.hoe_point.assign(n, Eigen::Vector3d::Zero());
  g.has_point.assign(n, 0);
  const double half_w = 0.5 * scene.hoe.size_mm[0], half_h = 0.5 * scene.hoe.size_mm[1];
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Vector3d d = g.plate.axes.transpose() * g.grid[j].direction;
    if (d.z() == 0.0) continue;
    const double t = -g.source_local.z() / d.z();
    if (!(t > 0.0)) continue;
    const Eigen::Vector3d p = g.source_local + t * d;
    g.hoe_point[j] = g.plate.toBench(p);
    g.has_point[j] = 1;
    if (std::abs(p.x()) > half_w || std::abs(p.y()) > half_h) continue;  // culled: misses the aperture
    g.hit_index.push_back(static_cast<int>(j));
    g.hit_dir.push_back(d);
    g.hit_u.push_back(p.x());
    g.hit_v.push_back(p.y());
  }
  return geo;
}

double incidentIndex(const Scene& scene, const GeometryData& g) {
  return g.source_local.z() < 0.0 ? scene.hoe.cover_index : scene.hoe.substrate_index;
}

// ---- recording per layer -----------------------------------------------------------------
std::uint64_t recordingKey(const Scene& scene, std::size_t layer) {
  const HoeLayer& l = scene.hoe_layers[layer];
  return Hasher("recording")
      .add(l.recording.wavelength_nm)
      .add(l.recording.reference_point_mm)
      .add(l.recording.signal_point_mm)
      .add(l.recording.phase_conjugate)
      .add(l.n0)
      .add(l.recording_n0_delta)
      .add(l.shrinkage_percent)
      .add(scene.hoe.pose)
      .add(scene.hoe.cover_index)
      .add(scene.hoe.substrate_index)
      .value();
}

std::shared_ptr<RecordingData> computeRecording(const Scene& scene, std::size_t layer) {
  auto r = std::make_shared<RecordingData>();
  r->model = makeLayerModel(scene.hoe, scene.hoe_layers[layer]);
  return r;
}

// ---- diffraction per layer and wavelength ------------------------------------------------
std::uint64_t diffractionKey(const Scene& scene, std::size_t layer, std::uint64_t recording_key,
                             std::uint64_t geometry_key, double wavelength_nm) {
  return Hasher("diffraction")
      .add(recording_key)
      .add(geometry_key)
      .add(scene.hoe_layers[layer].n0)
      .add(wavelength_nm)
      .add(scene.hoe.cover_index)
      .add(scene.hoe.substrate_index)
      .value();
}

std::uint64_t fringesKey(std::uint64_t recording_key, std::uint64_t geometry_key) {
  return Hasher("fringes").add(recording_key).add(geometry_key).value();
}

std::shared_ptr<FringeData> computeFringes(const GeometryData& g, const RecordingData& r) {
  const std::size_t nh = g.hits();
  auto f = std::make_shared<FringeData>();
  f->k_recorded.resize(nh);
  f->valid.assign(nh, 0);
  forRange(nh, [&](std::size_t b, std::size_t e) {
    for (std::size_t h = b; h < e; ++h) {
      // The recording sampled where this ray meets the plate (plate-local u, v).
      const RecordedGrating rg = recordAt(r.model, g.hit_u[h], g.hit_v[h]);
      f->valid[h] = rg.valid;
      f->k_recorded[h] = rg.k_recorded;
    }
  });
  return f;
}

std::shared_ptr<DiffractionData> computeDiffraction(const Scene& scene, const GeometryData& g,
                                                    const FringeData& fringes, const FilmGrating& film,
                                                    double wavelength_nm) {
  const std::size_t nh = g.hits();
  const double n_cover = scene.hoe.cover_index, n_sub = scene.hoe.substrate_index;
  const double n_in = incidentIndex(scene, g);
  auto d = std::make_shared<DiffractionData>();
  d->lambda_um = wavelength_nm * 1e-3;
  d->flags.assign(nh, 0);
  d->obliquity.resize(nh);
  d->out_dir.resize(nh);
  forRange(nh, [&](std::size_t b, std::size_t e) {
    for (std::size_t h = b; h < e; ++h) {
      if (!fringes.valid[h]) continue;
      const LayerGeometryT<double> lg =
          layerGeometryT<double>(film, fringes.k_recorded[h], g.hit_dir[h], n_in, n_cover, n_sub, d->lambda_um);
      std::uint8_t f = kValid;
      if (lg.entered) f |= kEntered;
      if (lg.evanescent) f |= kEvanescent;
      if (lg.exits) f |= kExits;
      if (lg.tir) f |= kTir;
      d->flags[h] = f;
      d->obliquity[h] = {lg.geometry.c_r, lg.geometry.c_s, lg.geometry.vartheta, lg.geometry.p_factor};
      d->out_dir[h] = lg.out_dir;
    }
  });
  return d;
}

std::uint64_t eyeKey(const Scene& scene, const std::array<double, 2>& gaze) {
  return Hasher("eye")
      .add(scene.eye.eyeball_diameter_mm)
      .add(scene.eye.pupil_diameter_mm)
      .add(scene.eye.relief_mm)
      .add(scene.eye.lateral_offset_mm)
      .add(gaze)
      .add(scene.hoe.pose)
      .value();
}

// ---- stack per wavelength ----------------------------------------------------------------
std::uint64_t stackKey(std::uint64_t geometry_key, const std::vector<int>& order,
                       const std::vector<std::uint64_t>& coupled_wave_keys, const LayerCoupledWaves& cw) {
  Hasher hs("stack");
  hs.add(geometry_key);
  for (int i : order) hs.add(i).add(coupled_wave_keys[i]).add(static_cast<std::uint64_t>(cw[i]->done_count));
  return hs.value();
}

std::shared_ptr<StackData> computeStack(const GeometryData& g, const std::vector<int>& order,
                                        const LayerDiffractions& dif, const LayerCoupledWaves& cw) {
  const std::size_t nh = g.hits(), nl = order.size();
  auto s = std::make_shared<StackData>();
  s->flags.assign(nh, 0);
  s->eff.assign(nh, 0.0);
  s->xi.assign(nh, 0.0);
  s->nu.assign(nh, 0.0);
  s->layer.assign(nh, -1);
  s->out_dir.assign(nh, Eigen::Vector3d::Zero());
  const bool source_eye_side = g.source_local.z() < 0.0;
  forRange(nh, [&](std::size_t b, std::size_t e) {
    for (std::size_t h = b; h < e; ++h) {
      bool evaluated = true;
      for (std::size_t i = 0; i < nl && evaluated; ++i) evaluated = cw[i]->done[h] != 0;
      if (!evaluated) continue;
      const bool forward = g.hit_dir[h].z() > 0.0;
      double power = 1.0, best = -1.0, eff = 0.0;
      bool any_evanescent = false, tir = false, exits = false, towards = false;
      int layer = -1;
      for (std::size_t k = 0; k < nl; ++k) {
        const int li = forward ? order[k] : order[nl - 1 - k];
        const std::uint8_t f = dif[li]->flags[h];
        if (!(f & kValid)) continue;
        if (!(f & kEntered)) break;  // cannot enter the stack at all
        const CoupledWaveData& c = *cw[li];
        const double contribution = power * c.eff[h];
        any_evanescent = any_evanescent || (f & kEvanescent);
        const bool lexits = (f & kExits) != 0, ltir = (f & kTir) != 0;
        if (lexits) eff += contribution;
        if (contribution > best && (lexits || ltir)) {
          best = contribution;
          layer = li;
          tir = ltir;
          exits = lexits;
          s->xi[h] = c.xi[h];
          s->nu[h] = c.nu[h];
          if (lexits) {
            const Eigen::Vector3d& ld = dif[li]->out_dir[h];
            s->out_dir[h] = g.plate.axes * ld;
            towards = (ld.z() < 0.0) == source_eye_side;
          }
        }
        power *= c.zero[h];
      }
      std::uint8_t sf = kSEvaluated;
      if (tir) exits = false;
      if (exits) sf |= kSExits;
      if (tir) sf |= kSTir;
      if (towards) sf |= kSTowardsEye;
      if (layer < 0 && any_evanescent) sf |= kSEvanescent;
      s->flags[h] = sf;
      s->eff[h] = eff;
      s->layer[h] = layer;
    }
  });
  return s;
}

// ---- pupil ---------------------------------------------------------------------------------
std::uint64_t pupilKey(std::uint64_t eye_key, const std::vector<std::uint64_t>& stack_keys) {
  Hasher hp("pupil");
  hp.add(eye_key);
  for (std::uint64_t k : stack_keys) hp.add(k);
  return hp.value();
}

void computePupil(PupilData& p, const GeometryData& g, const Stacks& stacks, const EyePlacement& eye,
                  const std::array<double, 2>& gaze) {
  const std::size_t nw = stacks.size(), nh = g.hits();
  p.eye = eye;
  p.eye_axes = rotationFromDeg({gaze[0], gaze[1], 0.0});
  p.in_pupil.assign(nw, {});
  p.radius.assign(nw, {});
  p.field.assign(nw, {});
  for (std::size_t w = 0; w < nw; ++w) {
    p.in_pupil[w].assign(nh, 0);
    p.radius[w].assign(nh, 0.0);
    p.field[w].assign(nh, {0.0, 0.0});
    const StackData& s = *stacks[w];
    forRange(nh, [&](std::size_t b, std::size_t e) {
      for (std::size_t h = b; h < e; ++h) {
        if (!(s.flags[h] & kSExits)) continue;
        const PupilCrossing c = crossPupil(eye, g.hoe_point[g.hit_index[h]], s.out_dir[h]);
        p.radius[w][h] = c.radius_mm;
        if (!c.in_pupil) continue;
        p.in_pupil[w][h] = 1;
        p.field[w][h] = fieldAngleDeg(p.eye_axes, s.out_dir[h]);
      }
    });
  }
}

// ---- FOV -----------------------------------------------------------------------------------
std::uint64_t fovKey(std::uint64_t pupil_key, double efficiency_threshold) {
  return Hasher("fov").add(pupil_key).add(efficiency_threshold).value();
}

void computeFov(FovData& f, const PupilData& pupil, const Stacks& stacks, std::size_t hits,
                double efficiency_threshold) {
  const std::size_t nw = stacks.size();
  FovAccumulator all;
  std::vector<FovAccumulator> per(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    const StackData& s = *stacks[w];
    for (std::size_t h = 0; h < hits; ++h) {
      if (!pupil.in_pupil[w][h] || !(s.eff[h] >= efficiency_threshold)) continue;
      all.add(pupil.field[w][h], -s.out_dir[h]);
      per[w].add(pupil.field[w][h], -s.out_dir[h]);
    }
  }
  f.all = all.result();
  f.efficient = all.count;
  f.per.resize(nw);
  f.per_efficient.resize(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    f.per[w] = per[w].result();
    f.per_efficient[w] = per[w].count;
  }
}

// ---- analyses ------------------------------------------------------------------------------
std::uint64_t analysesKey(std::uint64_t pupil_key, bool cull_to_pupil) {
  return Hasher("analyses").add(pupil_key).add(cull_to_pupil).value();
}

void computeAnalyses(AnalysesData& a, const PupilData& pupil, const Stacks& stacks, std::size_t hits,
                     bool cull_to_pupil) {
  const std::size_t nw = stacks.size();
  a = {};
  a.per_in_pupil.assign(nw, 0);
  a.per_mean.assign(nw, 0.0);
  double sum_all = 0, sum2_all = 0, sum_hoe = 0;
  for (std::size_t w = 0; w < nw; ++w) {
    const StackData& s = *stacks[w];
    double sum = 0;
    for (std::size_t h = 0; h < hits; ++h) {
      sum_hoe += s.eff[h];
      if (!pupil.in_pupil[w][h]) continue;
      ++a.per_in_pupil[w];
      sum += s.eff[h];
      sum2_all += s.eff[h] * s.eff[h];
    }
    a.in_pupil += a.per_in_pupil[w];
    sum_all += sum;
    a.per_mean[w] = a.per_in_pupil[w] ? sum / a.per_in_pupil[w] : 0.0;
  }
  a.mean_pupil = a.in_pupil ? sum_all / a.in_pupil : 0.0;
  const std::size_t on_hoe = hits * nw;
  a.mean_hoe = cull_to_pupil ? std::numeric_limits<double>::quiet_NaN() : (on_hoe ? sum_hoe / on_hoe : 0.0);
  if (a.in_pupil > 0 && sum_all > 0) {
    const double mean = sum_all / a.in_pupil;
    const double var = std::max(0.0, sum2_all / a.in_pupil - mean * mean);
    a.uniformity = std::max(0.0, 1.0 - std::sqrt(var) / mean);
  }
}

// ---- result ------------------------------------------------------------------------------
TraceResult assembleResult(const TraceOptions& o, const std::vector<double>& wavelengths,
                           const std::array<double, 2>& gaze, const GeometryData& g, const Stacks& stacks,
                           const PupilData& pupil, const FovData& fov, const AnalysesData& an) {
  const std::size_t nw = wavelengths.size(), nh = g.hits();
  TraceResult res;
  res.gaze_deg = gaze;
  res.fov_deg = fov.all;
  res.rays = static_cast<int>(g.grid.size() * nw);
  res.rays_on_hoe = static_cast<int>(nh * nw);
  res.rays_in_pupil = an.in_pupil;
  res.rays_efficient = fov.efficient;
  res.mean_efficiency = an.mean_pupil;
  res.mean_efficiency_on_hoe = an.mean_hoe;
  res.efficiency_uniformity = an.uniformity;
  res.per_wavelength.resize(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    WavelengthTrace& wt = res.per_wavelength[w];
    wt.wavelength_nm = wavelengths[w];
    wt.fov_deg = fov.per[w];
    wt.rays = static_cast<int>(g.grid.size());
    wt.rays_in_pupil = an.per_in_pupil[w];
    wt.rays_efficient = fov.per_efficient[w];
    wt.mean_efficiency = an.per_mean[w];
  }
  if (o.keep_field_rays) {
    res.field_rays.resize(nh * nw);
    for (std::size_t w = 0; w < nw; ++w) {
      const StackData& s = *stacks[w];
      for (std::size_t h = 0; h < nh; ++h) {
        FieldRay& r = res.field_rays[w * nh + h];
        r.wavelength_nm = wavelengths[w];
        r.efficiency = s.eff[h];
        r.pixel = g.grid[g.hit_index[h]].pixel;
        r.in_pupil = pupil.in_pupil[w][h] != 0;
        if (r.in_pupil) r.field_deg = pupil.field[w][h];
      }
    }
  }
  if (o.keep_rays) {
    res.ray_list.resize(g.grid.size() * nw);
    for (std::size_t w = 0; w < nw; ++w) {
      std::size_t h = 0;
      for (std::size_t j = 0; j < g.grid.size(); ++j) {
        TracedRay& r = res.ray_list[w * g.grid.size() + j];
        const ProjectorRay& pr = g.grid[j];
        r.source = g.source;
        r.projector_direction = pr.direction;
        r.pixel = pr.pixel;
        r.wavelength_nm = wavelengths[w];
        if (g.has_point[j]) r.hoe_point = g.hoe_point[j];
        if (h >= nh || g.hit_index[h] != static_cast<int>(j)) continue;
        const StackData& s = *stacks[w];
        r.hits_hoe = true;
        r.culled = !(s.flags[h] & kSEvaluated);
        r.efficiency = s.eff[h];
        r.layer = s.layer[h];
        r.xi = s.xi[h];
        r.nu = s.nu[h];
        r.tir = (s.flags[h] & kSTir) != 0;
        r.exits = (s.flags[h] & kSExits) != 0;
        r.towards_eye = (s.flags[h] & kSTowardsEye) != 0;
        r.evanescent = (s.flags[h] & kSEvanescent) != 0;
        r.out_direction = s.out_dir[h];  // the last exiting dominant layer's (as before: zero if none)
        if (r.exits) {
          r.field_deg = fieldAngleDeg(pupil.eye_axes, r.out_direction);
          r.pupil_radius_mm = pupil.radius[w][h];
          r.in_pupil = pupil.in_pupil[w][h] != 0;
        }
        ++h;
      }
    }
  }
  return res;
}

}  // namespace fovea::detail
