#pragma once
// The trace as a dependency graph of memoised stages ("skip what a scene doesn't need"). Each
// stage's result is stored under a 64-bit hash of exactly the inputs it reads (scene fields,
// options, and the keys of the stages it consumes), so a run recomputes only the stages whose
// inputs changed. The stages are one function each in trace_stages.h (the coupled wave in
// trace_coupled_wave.cpp), the keys and memo tables in trace_memo.h; run() only chains them:
//
//   geometry                 projector pose/FOV/pixels, rays, source shift, HOE pose/size/shift:
//                            the projector ray grid and where each ray meets the plate
//                            (rays that miss the aperture stop here)
//   recording:<layer>        that layer's recording (points, wavelength, conjugation, n0,
//                            index change, shrinkage) + HOE nominal pose/indices: the fringe
//                            field K_rec(u, v) in plate-local coordinates. Not the rays nor the
//                            HOE shift: a rigid lateral shift carries the recorded grating with
//                            the plate, so moving the plate never re-records
//   diffraction:<layer>@<λ>  recording + geometry + that layer's n0 + λ + cover/substrate
//                            indices: K_rec sampled at every plate hit (once per layer and
//                            geometry, shared by the wavelengths), obliquities, dephasing and
//                            the diffracted direction (no Kogelnik)
//   coupled_wave:<layer>@<λ> diffraction + n1, thickness, absorption, polarisation: Kogelnik
//                            per ray; with cull_to_pupil only for the rays that some layer
//                            sends into the pupil (the eye is then an input, evaluated rays are
//                            kept and a gaze move adds only the newly reachable ones)
//   stack:<λ>                the layers' coupled-wave results in depth order: efficiency and
//                            dominant direction of every ray
//   pupil                    eye (relief, offset, diameters, gaze) + HOE pose + stacks
//   fov                      pupil + threshold
//   analyses                 pupil + threshold: counts, means, uniformity, per wavelength
//
// Moving the gaze reruns pupil, fov and analyses only (and, with cull_to_pupil, the coupled
// wave of rays that newly reach the pupil); editing one layer recomputes that layer's
// recording/diffraction/coupled-wave stages and the stacks, never the other layers' ones;
// wavelengths that are not asked for are not evaluated.
//
// One pipeline is not thread-safe; use one per thread (TracePipelinePool hands them out).

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "model/physics/trace.h"

namespace fovea {

struct TraceStats {
  std::vector<std::string> stages_recomputed;  // in pipeline order
  // Coupled-wave (Kogelnik) solves in this run: one ray through one layer at one wavelength
  // (an unpolarised solve counts once although it solves s and p).
  long long evaluations = 0;
};

class TracePipeline {
 public:
  TracePipeline();
  ~TracePipeline();
  TracePipeline(TracePipeline&&) noexcept;
  TracePipeline& operator=(TracePipeline&&) noexcept;

  TraceResult run(const Scene& scene, const TraceOptions& options, TraceStats* stats = nullptr);
  void clear();  // forget every memoised stage

  struct State;

 private:
  std::unique_ptr<State> state_;
};

// Pipelines for parallel callers (gaze studies): acquire() lends one (a free one, or a new
// one), the handle returns it on destruction. Thread-safe.
class TracePipelinePool {
 public:
  class Handle {
   public:
    Handle(TracePipelinePool* pool, std::unique_ptr<TracePipeline> p) : pool_(pool), p_(std::move(p)) {}
    Handle(Handle&&) = default;
    ~Handle();
    TracePipeline& operator*() { return *p_; }
    TracePipeline* operator->() { return p_.get(); }

   private:
    TracePipelinePool* pool_;
    std::unique_ptr<TracePipeline> p_;
  };
  Handle acquire();

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<TracePipeline>> free_;
};

}  // namespace fovea
