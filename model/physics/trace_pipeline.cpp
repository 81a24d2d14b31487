#include "model/physics/trace_pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "model/physics/eye_model.h"
#include "model/physics/hoe_recording.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace_internal.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

namespace {

// ---- Keys ------------------------------------------------------------------------------
// 64-bit hash of a sequence of values (splitmix64 finaliser chained); -0 and +0 hash alike.
class Hasher {
 public:
  explicit Hasher(const char* tag) { add(std::string(tag)); }
  Hasher& add(std::uint64_t v) {
    h_ = mix(h_ ^ v);
    return *this;
  }
  Hasher& add(double v) {
    if (v == 0.0) v = 0.0;
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return add(bits);
  }
  Hasher& add(int v) { return add(static_cast<std::uint64_t>(static_cast<std::int64_t>(v))); }
  Hasher& add(bool v) { return add(static_cast<std::uint64_t>(v ? 0x5bd1e995u : 0x1b873593u)); }
  Hasher& add(const std::string& s) {
    add(static_cast<std::uint64_t>(s.size()));
    for (std::size_t i = 0; i < s.size(); i += 8) {
      std::uint64_t w = 0;
      std::memcpy(&w, s.data() + i, std::min<std::size_t>(8, s.size() - i));
      add(w);
    }
    return *this;
  }
  template <class T, std::size_t N>
  Hasher& add(const std::array<T, N>& a) {
    for (const T& v : a) add(v);
    return *this;
  }
  Hasher& add(const Pose& p) { return add(p.position_mm).add(p.rotation_deg); }
  std::uint64_t value() const { return h_; }

 private:
  static std::uint64_t mix(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t h_ = 0x243f6a8885a308d3ULL;
};

// ---- Stage data ------------------------------------------------------------------------
struct GeometryData {
  Frame plate;
  Eigen::Vector3d source = Eigen::Vector3d::Zero(), source_local = Eigen::Vector3d::Zero();
  std::vector<ProjectorRay> grid;
  std::vector<Eigen::Vector3d> hoe_point;  // per grid ray, where it meets the plate plane
  std::vector<std::uint8_t> has_point;     // the ray meets the plate plane (t > 0)
  std::vector<int> hit_index;              // grid index of every ray inside the aperture, ascending
  std::vector<Eigen::Vector3d> hit_dir;    // its direction in the plate frame
  std::vector<double> hit_u, hit_v;        // plate coordinates of the hit (mm)
};

// The recorded fringes of one layer in plate-local coordinates: K_rec(u, v) in closed form
// (hoe_recording.h). A rigid lateral shift of the plate carries them with it, so nothing here
// depends on the shift or on the rays; the diffraction stage samples it at the hits.
struct RecordingData {
  LayerModel model;
};

enum : std::uint8_t { kEntered = 1, kEvanescent = 2, kExits = 4, kTir = 8, kValid = 16 };

struct Obliquity {
  double c_r, c_s, vartheta, p_factor;
};

struct DiffractionData {
  double lambda_um = 0;
  std::vector<std::uint8_t> flags;       // per hit: kValid | kEntered | kEvanescent | kExits | kTir
  std::vector<Obliquity> obliquity;      // per hit (meaningful when entered)
  std::vector<Eigen::Vector3d> out_dir;  // per hit, local frame, when kExits
};

struct CoupledWaveData {
  std::vector<double> eff, zero, nu, xi;
  std::vector<std::uint8_t> done;
  long long done_count = 0;
};

enum : std::uint8_t { kSEvaluated = 1, kSExits = 2, kSTir = 4, kSTowardsEye = 8, kSEvanescent = 16 };

struct StackData {
  std::vector<std::uint8_t> flags;  // per hit
  std::vector<double> eff, xi, nu;
  std::vector<int> layer;
  std::vector<Eigen::Vector3d> out_dir;  // bench frame, when kSExits
};

struct PupilData {
  // per wavelength, per hit
  std::vector<std::vector<std::uint8_t>> in_pupil;
  std::vector<std::vector<double>> radius;
  std::vector<std::vector<std::array<double, 2>>> field;
  EyePlacement eye;
  Eigen::Matrix3d eye_axes = Eigen::Matrix3d::Identity();
};

struct FovData {
  FovDeg all;
  std::vector<FovDeg> per;
  int efficient = 0;
  std::vector<int> per_efficient;
};

struct AnalysesData {
  int in_pupil = 0;
  std::vector<int> per_in_pupil;
  double mean_pupil = 0, mean_hoe = 0, uniformity = 0;
  std::vector<double> per_mean;
};

// Memo table of one stage type: results by key, least recently used evicted beyond the
// entries of the current run plus `kKeepOld` older ones.
template <class D>
class Memo {
 public:
  std::shared_ptr<D> find(std::uint64_t key, std::uint64_t run) {
    auto it = map_.find(key);
    if (it == map_.end()) return nullptr;
    it->second.last_used = run;
    return it->second.data;
  }
  void put(std::uint64_t key, std::shared_ptr<D> d, std::uint64_t run) { map_[key] = {std::move(d), run}; }
  void evict(std::uint64_t run) {
    constexpr std::size_t kKeepOld = 6;
    std::vector<std::pair<std::uint64_t, std::uint64_t>> old;  // last_used, key
    for (const auto& [k, e] : map_)
      if (e.last_used != run) old.emplace_back(e.last_used, k);
    if (old.size() <= kKeepOld) return;
    std::sort(old.begin(), old.end());
    for (std::size_t i = 0; i + kKeepOld < old.size(); ++i) map_.erase(old[i].second);
  }
  void clear() { map_.clear(); }

 private:
  struct Entry {
    std::shared_ptr<D> data;
    std::uint64_t last_used = 0;
  };
  std::unordered_map<std::uint64_t, Entry> map_;
};

template <class D>
struct Single {
  std::uint64_t key = 0;
  bool valid = false;
  D data;
};

template <class F>
void forRange(std::size_t n, F&& f) {
  constexpr std::size_t kGrain = 512;
  if (n <= kGrain) {
    f(std::size_t{0}, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); });
}

std::string wavelengthLabel(double nm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%gnm", nm);
  return buf;
}

}  // namespace

struct TracePipeline::State {
  std::uint64_t run = 0;
  Memo<GeometryData> geometry;
  Memo<RecordingData> recording;
  Memo<DiffractionData> diffraction;
  Memo<CoupledWaveData> coupled_wave;
  Memo<StackData> stack;
  Single<PupilData> pupil;
  Single<FovData> fov;
  Single<AnalysesData> analyses;

  void evict() {
    geometry.evict(run);
    recording.evict(run);
    diffraction.evict(run);
    coupled_wave.evict(run);
    stack.evict(run);
  }
};

TracePipeline::TracePipeline() : state_(std::make_unique<State>()) {}
TracePipeline::~TracePipeline() = default;
TracePipeline::TracePipeline(TracePipeline&&) noexcept = default;
TracePipeline& TracePipeline::operator=(TracePipeline&&) noexcept = default;

void TracePipeline::clear() {
  state_ = std::make_unique<State>();
}

TraceResult TracePipeline::run(const Scene& scene, const TraceOptions& o, TraceStats* stats) {
  State& st = *state_;
  ++st.run;
  TraceStats local;
  TraceStats& ts = stats ? *stats : local;
  ts = {};
  const std::vector<double> wavelengths = detail::tracedWavelengths(scene, o);
  const std::size_t nw = wavelengths.size();
  const double n_cover = scene.hoe.cover_index, n_sub = scene.hoe.substrate_index;

  // ---- geometry -------------------------------------------------------------------------
  const std::uint64_t geometry_key = Hasher("geometry")
                                         .add(scene.projector.pose)
                                         .add(scene.projector.fov_deg)
                                         .add(scene.projector.pixels)
                                         .add(o.rays)
                                         .add(o.source_shift_mm)
                                         .add(scene.hoe.pose)
                                         .add(scene.hoe.size_mm)
                                         .add(o.hoe_shift_mm)
                                         .value();
  std::shared_ptr<GeometryData> geo = st.geometry.find(geometry_key, st.run);
  if (!geo) {
    ts.stages_recomputed.push_back("geometry");
    geo = std::make_shared<GeometryData>();
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
    st.geometry.put(geometry_key, geo, st.run);
  }
  const GeometryData& g = *geo;
  const std::size_t nh = g.hit_index.size();
  const double n_in = g.source_local.z() < 0.0 ? n_cover : n_sub;

  // ---- layers: labels and depth order -----------------------------------------------------
  const std::size_t nl = scene.hoe_layers.size();
  std::vector<std::string> label(nl);
  for (std::size_t i = 0; i < nl; ++i) {
    const std::string& name = scene.hoe_layers[i].name;
    const bool unique = !name.empty() && std::count_if(scene.hoe_layers.begin(), scene.hoe_layers.end(),
                                                       [&](const HoeLayer& l) { return l.name == name; }) == 1;
    label[i] = unique ? name : "#" + std::to_string(i);
  }
  std::vector<int> order(nl);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return scene.hoe_layers[a].offset_um < scene.hoe_layers[b].offset_um; });

  // The processed films as the scene has them now (memoised stages hold only what their keys
  // cover: a diffraction stage knows n0, not n1 or the thickness).
  std::vector<FilmGrating> film(nl);
  for (std::size_t i = 0; i < nl; ++i) film[i] = makeLayerModel(scene.hoe, scene.hoe_layers[i]).film;

  // ---- recording per layer ----------------------------------------------------------------
  std::vector<std::uint64_t> recording_key(nl);
  std::vector<std::shared_ptr<RecordingData>> rec(nl);
  if (nw > 0) {
    for (std::size_t i = 0; i < nl; ++i) {
      const HoeLayer& l = scene.hoe_layers[i];
      recording_key[i] = Hasher("recording")
                             .add(l.recording.wavelength_nm)
                             .add(l.recording.reference_point_mm)
                             .add(l.recording.signal_point_mm)
                             .add(l.recording.phase_conjugate)
                             .add(l.n0)
                             .add(l.recording_n0_delta)
                             .add(l.shrinkage_percent)
                             .add(scene.hoe.pose)
                             .add(n_cover)
                             .add(n_sub)
                             .value();
      rec[i] = st.recording.find(recording_key[i], st.run);
      if (rec[i]) continue;
      ts.stages_recomputed.push_back("recording:" + label[i]);
      auto r = std::make_shared<RecordingData>();
      r->model = makeLayerModel(scene.hoe, l);
      st.recording.put(recording_key[i], r, st.run);
      rec[i] = r;
    }
  }

  // ---- diffraction per layer and wavelength ----------------------------------------------
  std::vector<std::vector<std::uint64_t>> diffraction_key(nw, std::vector<std::uint64_t>(nl));
  std::vector<std::vector<std::shared_ptr<DiffractionData>>> dif(nw, std::vector<std::shared_ptr<DiffractionData>>(nl));
  for (std::size_t w = 0; w < nw; ++w) {
    for (std::size_t i = 0; i < nl; ++i) {
      const HoeLayer& l = scene.hoe_layers[i];
      diffraction_key[w][i] = Hasher("diffraction")
                                  .add(recording_key[i])
                                  .add(geometry_key)
                                  .add(l.n0)
                                  .add(wavelengths[w])
                                  .add(n_cover)
                                  .add(n_sub)
                                  .value();
      dif[w][i] = st.diffraction.find(diffraction_key[w][i], st.run);
      if (dif[w][i]) continue;
      ts.stages_recomputed.push_back("diffraction:" + label[i] + "@" + wavelengthLabel(wavelengths[w]));
      auto d = std::make_shared<DiffractionData>();
      d->lambda_um = wavelengths[w] * 1e-3;
      const FilmGrating& film_i = film[i];
      d->flags.assign(nh, 0);
      d->obliquity.resize(nh);
      d->out_dir.resize(nh);
      const RecordingData& r = *rec[i];
      forRange(nh, [&](std::size_t b, std::size_t e) {
        for (std::size_t h = b; h < e; ++h) {
          // The recording sampled where this ray meets the plate (plate-local u, v).
          const RecordedGrating rg = recordAt(r.model, g.hit_u[h], g.hit_v[h]);
          if (!rg.valid) continue;
          const LayerGeometryT<double> lg =
              layerGeometryT<double>(film_i, rg.k_recorded, g.hit_dir[h], n_in, n_cover, n_sub, d->lambda_um);
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
      st.diffraction.put(diffraction_key[w][i], d, st.run);
      dif[w][i] = d;
    }
  }

  // ---- eye (read by the cull and by the pupil stage) -------------------------------------
  const std::array<double, 2> gaze = o.gaze_deg ? *o.gaze_deg : scene.eye.gaze_deg;
  const std::uint64_t eye_key = Hasher("eye")
                                    .add(scene.eye.eyeball_diameter_mm)
                                    .add(scene.eye.pupil_diameter_mm)
                                    .add(scene.eye.relief_mm)
                                    .add(scene.eye.lateral_offset_mm)
                                    .add(gaze)
                                    .add(scene.hoe.pose)
                                    .value();
  const EyePlacement eye = placeEye(scene, gaze[0], gaze[1]);

  // ---- coupled wave per layer and wavelength (with the pupil cull) ------------------------
  std::vector<std::vector<std::uint64_t>> cw_key(nw, std::vector<std::uint64_t>(nl));
  std::vector<std::vector<std::shared_ptr<CoupledWaveData>>> cw(nw, std::vector<std::shared_ptr<CoupledWaveData>>(nl));
  std::vector<std::uint8_t> need(nh);
  for (std::size_t w = 0; w < nw; ++w) {
    // Which rays need the coupled wave: every plate hit, or with the cull only those that some
    // layer's diffracted order sends through the pupil (no other ray can enter the eye).
    if (!o.cull_to_pupil) {
      std::fill(need.begin(), need.end(), std::uint8_t{1});
    } else {
      forRange(nh, [&](std::size_t b, std::size_t e) {
        for (std::size_t h = b; h < e; ++h) {
          std::uint8_t n = 0;
          for (std::size_t i = 0; i < nl && !n; ++i) {
            if (!(dif[w][i]->flags[h] & kExits)) continue;
            const Eigen::Vector3d dir = g.plate.axes * dif[w][i]->out_dir[h];
            n = crossPupil(eye, g.hoe_point[g.hit_index[h]], dir).in_pupil;
          }
          need[h] = n;
        }
      });
    }
    for (std::size_t i = 0; i < nl; ++i) {
      const HoeLayer& l = scene.hoe_layers[i];
      cw_key[w][i] = Hasher("coupled_wave")
                         .add(diffraction_key[w][i])
                         .add(l.n1)
                         .add(l.thickness_um)
                         .add(l.absorption_per_mm)
                         .add(static_cast<int>(o.polarization))
                         .value();
      std::shared_ptr<CoupledWaveData> c = st.coupled_wave.find(cw_key[w][i], st.run);
      if (!c) {
        c = std::make_shared<CoupledWaveData>();
        c->eff.assign(nh, 0.0);
        c->zero.assign(nh, 1.0);
        c->nu.assign(nh, 0.0);
        c->xi.assign(nh, 0.0);
        c->done.assign(nh, 0);
        st.coupled_wave.put(cw_key[w][i], c, st.run);
      }
      cw[w][i] = c;
      const DiffractionData& d = *dif[w][i];
      // Rays to solve: needed, entered the film, not yet solved.
      std::vector<int> todo;
      for (std::size_t h = 0; h < nh; ++h)
        if (need[h] && !c->done[h] && (d.flags[h] & kEntered)) todo.push_back(static_cast<int>(h));
      for (std::size_t h = 0; h < nh; ++h)  // rays that never enter need no solve: mark them
        if (need[h] && !c->done[h] && !(d.flags[h] & kEntered)) {
          c->done[h] = 1;
          ++c->done_count;
        }
      if (todo.empty()) continue;
      ts.stages_recomputed.push_back("coupled_wave:" + label[i] + "@" + wavelengthLabel(wavelengths[w]));
      ts.evaluations += static_cast<long long>(todo.size());
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
          const kogelnik::Result k = layerCoupledWaveT<double>(film[i], dg, d.lambda_um, o.polarization);
          c->eff[h] = k.efficiency;
          c->zero[h] = k.zero_order;
          c->nu[h] = k.nu;
          c->xi[h] = k.xi;
          c->done[h] = 1;
        }
      });
      c->done_count += static_cast<long long>(todo.size());
    }
  }

  // ---- stack per wavelength ----------------------------------------------------------------
  std::vector<std::uint64_t> stack_key(nw);
  std::vector<std::shared_ptr<StackData>> stk(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    Hasher hs("stack");
    hs.add(geometry_key);
    for (int i : order) hs.add(i).add(cw_key[w][i]).add(static_cast<std::uint64_t>(cw[w][i]->done_count));
    stack_key[w] = hs.value();
    stk[w] = st.stack.find(stack_key[w], st.run);
    if (stk[w]) continue;
    ts.stages_recomputed.push_back("stack:" + wavelengthLabel(wavelengths[w]));
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
        for (std::size_t i = 0; i < nl && evaluated; ++i) evaluated = cw[w][i]->done[h] != 0;
        if (!evaluated) continue;
        const bool forward = g.hit_dir[h].z() > 0.0;
        double power = 1.0, best = -1.0, eff = 0.0;
        bool any_evanescent = false, tir = false, exits = false, towards = false;
        int layer = -1;
        for (std::size_t k = 0; k < nl; ++k) {
          const int li = forward ? order[k] : order[nl - 1 - k];
          const std::uint8_t f = dif[w][li]->flags[h];
          if (!(f & kValid)) continue;
          if (!(f & kEntered)) break;  // cannot enter the stack at all
          const CoupledWaveData& c = *cw[w][li];
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
              const Eigen::Vector3d& ld = dif[w][li]->out_dir[h];
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
    st.stack.put(stack_key[w], s, st.run);
    stk[w] = s;
  }

  // ---- pupil -----------------------------------------------------------------------------
  Hasher hp("pupil");
  hp.add(eye_key);
  for (std::size_t w = 0; w < nw; ++w) hp.add(stack_key[w]);
  const std::uint64_t pupil_key = hp.value();
  if (!st.pupil.valid || st.pupil.key != pupil_key) {
    ts.stages_recomputed.push_back("pupil");
    PupilData& p = st.pupil.data;
    p.eye = eye;
    p.eye_axes = rotationFromDeg({gaze[0], gaze[1], 0.0});
    p.in_pupil.assign(nw, {});
    p.radius.assign(nw, {});
    p.field.assign(nw, {});
    for (std::size_t w = 0; w < nw; ++w) {
      p.in_pupil[w].assign(nh, 0);
      p.radius[w].assign(nh, 0.0);
      p.field[w].assign(nh, {0.0, 0.0});
      const StackData& s = *stk[w];
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
    st.pupil.key = pupil_key;
    st.pupil.valid = true;
    st.fov.valid = st.analyses.valid = false;
  }
  const PupilData& pupil = st.pupil.data;

  // ---- FOV -------------------------------------------------------------------------------
  const std::uint64_t fov_key = Hasher("fov").add(pupil_key).add(o.efficiency_threshold).value();
  if (!st.fov.valid || st.fov.key != fov_key) {
    ts.stages_recomputed.push_back("fov");
    FovData& f = st.fov.data;
    detail::FovAccumulator all;
    std::vector<detail::FovAccumulator> per(nw);
    for (std::size_t w = 0; w < nw; ++w) {
      const StackData& s = *stk[w];
      for (std::size_t h = 0; h < nh; ++h) {
        if (!pupil.in_pupil[w][h] || !(s.eff[h] >= o.efficiency_threshold)) continue;
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
    st.fov.key = fov_key;
    st.fov.valid = true;
  }

  // ---- analyses ----------------------------------------------------------------------------
  const std::uint64_t analyses_key = Hasher("analyses").add(pupil_key).add(o.cull_to_pupil).value();
  if (!st.analyses.valid || st.analyses.key != analyses_key) {
    ts.stages_recomputed.push_back("analyses");
    AnalysesData& a = st.analyses.data;
    a = {};
    a.per_in_pupil.assign(nw, 0);
    a.per_mean.assign(nw, 0.0);
    double sum_all = 0, sum2_all = 0, sum_hoe = 0;
    for (std::size_t w = 0; w < nw; ++w) {
      const StackData& s = *stk[w];
      double sum = 0;
      for (std::size_t h = 0; h < nh; ++h) {
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
    const std::size_t on_hoe = nh * nw;
    a.mean_hoe = o.cull_to_pupil ? std::numeric_limits<double>::quiet_NaN() : (on_hoe ? sum_hoe / on_hoe : 0.0);
    if (a.in_pupil > 0 && sum_all > 0) {
      const double mean = sum_all / a.in_pupil;
      const double var = std::max(0.0, sum2_all / a.in_pupil - mean * mean);
      a.uniformity = std::max(0.0, 1.0 - std::sqrt(var) / mean);
    }
    st.analyses.key = analyses_key;
    st.analyses.valid = true;
  }
  const FovData& fov = st.fov.data;
  const AnalysesData& an = st.analyses.data;

  // ---- result ------------------------------------------------------------------------------
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
      const StackData& s = *stk[w];
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
        const StackData& s = *stk[w];
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
  st.evict();
  return res;
}

TracePipelinePool::Handle::~Handle() {
  if (!p_ || !pool_) return;
  std::lock_guard<std::mutex> lock(pool_->mutex_);
  pool_->free_.push_back(std::move(p_));
}

TracePipelinePool::Handle TracePipelinePool::acquire() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (free_.empty()) return Handle(this, std::make_unique<TracePipeline>());
  std::unique_ptr<TracePipeline> p = std::move(free_.back());
  free_.pop_back();
  return Handle(this, std::move(p));
}

}  // namespace fovea
