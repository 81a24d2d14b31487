#include "model/physics/trace_pipeline.h"

#include "model/physics/trace_internal.h"
#include "model/physics/trace_memo.h"
#include "model/physics/trace_stages.h"

namespace fovea {

using namespace detail;

struct TracePipeline::State {
  std::uint64_t run = 0;
  Memo<GeometryData> geometry;
  Memo<RecordingData> recording;
  Memo<FringeData> fringes;
  Memo<DiffractionData> diffraction;
  Memo<CoupledWaveData> coupled_wave;
  Memo<StackData> stack;
  Single<PupilData> pupil;
  Single<FovData> fov;
  Single<AnalysesData> analyses;

  void evict() {
    geometry.evict(run);
    recording.evict(run);
    fringes.evict(run);
    diffraction.evict(run);
    coupled_wave.evict(run);
    stack.evict(run);
  }
};

namespace {

// The memoised result under `key`, or compute() stored under it (and `name()` recorded).
template <class D, class Compute, class Name>
std::shared_ptr<D> memoised(Memo<D>& memo, std::uint64_t key, std::uint64_t run, TraceStats& ts, Name&& name,
                            Compute&& compute) {
  std::shared_ptr<D> d = memo.find(key, run);
  if (d) return d;
  ts.stages_recomputed.push_back(name());
  d = compute();
  memo.put(key, d, run);
  return d;
}

}  // namespace

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
  const std::vector<double> wavelengths = tracedWavelengths(scene, o);
  const std::size_t nw = wavelengths.size(), nl = scene.hoe_layers.size();
  const LayerSetup layers = layerSetup(scene);
  const auto at = [&](std::size_t i, std::size_t w) { return layers.label[i] + "@" + wavelengthLabel(wavelengths[w]); };

  // geometry
  const std::uint64_t geometry_key = geometryKey(scene, o);
  const std::shared_ptr<GeometryData> geo = memoised(
      st.geometry, geometry_key, st.run, ts, [] { return std::string("geometry"); },
      [&] { return computeGeometry(scene, o); });
  const GeometryData& g = *geo;
  const std::size_t nh = g.hits();

  // recording per layer
  std::vector<std::uint64_t> recording_key(nl);
  std::vector<std::shared_ptr<RecordingData>> rec(nl);
  if (nw > 0)
    for (std::size_t i = 0; i < nl; ++i) {
      recording_key[i] = recordingKey(scene, i);
      rec[i] = memoised(
          st.recording, recording_key[i], st.run, ts, [&] { return "recording:" + layers.label[i]; },
          [&] { return computeRecording(scene, i); });
    }

  // diffraction per layer and wavelength
  std::vector<std::vector<std::uint64_t>> diffraction_key(nw, std::vector<std::uint64_t>(nl));
  std::vector<LayerDiffractions> dif(nw, LayerDiffractions(nl));
  std::vector<std::shared_ptr<FringeData>> fringes(nl);  // looked up when a diffraction reruns
  const auto fringesOf = [&](std::size_t i) -> const FringeData& {
    if (!fringes[i]) {
      const std::uint64_t key = fringesKey(recording_key[i], geometry_key);
      fringes[i] = st.fringes.find(key, st.run);
      if (!fringes[i]) {
        fringes[i] = computeFringes(g, *rec[i]);
        st.fringes.put(key, fringes[i], st.run);
      }
    }
    return *fringes[i];
  };
  for (std::size_t w = 0; w < nw; ++w)
    for (std::size_t i = 0; i < nl; ++i) {
      diffraction_key[w][i] = diffractionKey(scene, i, recording_key[i], geometry_key, wavelengths[w]);
      dif[w][i] = memoised(
          st.diffraction, diffraction_key[w][i], st.run, ts, [&] { return "diffraction:" + at(i, w); },
          [&] { return computeDiffraction(scene, g, fringesOf(i), layers.film[i], wavelengths[w]); });
    }

  // the eye (read by the cull and by the pupil stage)
  const std::array<double, 2> gaze = o.gaze_deg ? *o.gaze_deg : scene.eye.gaze_deg;
  const std::uint64_t eye_key = eyeKey(scene, gaze);
  const EyePlacement eye = placeEye(scene, gaze[0], gaze[1]);

  // coupled wave per layer and wavelength (with the pupil cull); grown in place, so memoised
  // entries are created empty and solved for the rays this run needs
  std::vector<std::vector<std::uint64_t>> cw_key(nw, std::vector<std::uint64_t>(nl));
  std::vector<LayerCoupledWaves> cw(nw, LayerCoupledWaves(nl));
  std::vector<std::uint8_t> need;
  for (std::size_t w = 0; w < nw; ++w) {
    coupledWaveNeed(g, dif[w], eye, o.cull_to_pupil, need);
    for (std::size_t i = 0; i < nl; ++i) {
      cw_key[w][i] = coupledWaveKey(scene, i, diffraction_key[w][i], o.polarization);
      std::shared_ptr<CoupledWaveData> c = st.coupled_wave.find(cw_key[w][i], st.run);
      if (!c) {
        c = newCoupledWave(nh);
        st.coupled_wave.put(cw_key[w][i], c, st.run);
      }
      cw[w][i] = c;
      const long long solved = solveCoupledWave(*c, *dif[w][i], layers.film[i], o.polarization, need);
      if (solved == 0) continue;
      ts.stages_recomputed.push_back("coupled_wave:" + at(i, w));
      ts.evaluations += solved;
    }
  }

  // stack per wavelength
  std::vector<std::uint64_t> stack_key(nw);
  Stacks stk(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    stack_key[w] = stackKey(geometry_key, layers.order, cw_key[w], cw[w]);
    stk[w] = memoised(
        st.stack, stack_key[w], st.run, ts, [&] { return "stack:" + wavelengthLabel(wavelengths[w]); },
        [&] { return computeStack(g, layers.order, dif[w], cw[w]); });
  }

  // pupil, FOV, analyses: only their latest result is kept
  const std::uint64_t pupil_key = pupilKey(eye_key, stack_key);
  if (!st.pupil.holds(pupil_key)) {
    ts.stages_recomputed.push_back("pupil");
    computePupil(st.pupil.data, g, stk, eye, gaze);
    st.pupil.store(pupil_key);
    st.fov.valid = st.analyses.valid = false;
  }
  const std::uint64_t fov_key = fovKey(pupil_key, o.efficiency_threshold);
  if (!st.fov.holds(fov_key)) {
    ts.stages_recomputed.push_back("fov");
    computeFov(st.fov.data, st.pupil.data, stk, nh, o.efficiency_threshold);
    st.fov.store(fov_key);
  }
  const std::uint64_t analyses_key = analysesKey(pupil_key, o.cull_to_pupil);
  if (!st.analyses.holds(analyses_key)) {
    ts.stages_recomputed.push_back("analyses");
    computeAnalyses(st.analyses.data, st.pupil.data, stk, nh, o.cull_to_pupil);
    st.analyses.store(analyses_key);
  }

  TraceResult res = assembleResult(o, wavelengths, gaze, g, stk, st.pupil.data, st.fov.data, st.analyses.data);
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
