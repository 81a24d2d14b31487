#pragma once
// The stages of the trace pipeline (trace_pipeline.h documents the graph and what each stage's
// key covers): their data and one function per stage. Each `...Key` function hashes exactly the
// inputs its stage reads; each `compute...` function is the stage's work, free of memo logic.
// Internal to model/physics (trace_pipeline.cpp runs them in order).

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Core>

#include "model/physics/eye_model.h"
#include "model/physics/grating.h"
#include "model/physics/hoe_recording.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"
#include "model/scene/scene_geometry.h"

namespace fovea::detail {

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
  std::size_t hits() const { return hit_index.size(); }
};

// The recorded fringes of one layer in plate-local coordinates: K_rec(u, v) in closed form
// (hoe_recording.h). A rigid lateral shift of the plate carries them with it, so nothing here
// depends on the shift or on the rays; the diffraction stage samples it at the hits.
struct RecordingData {
  LayerModel model;
};

// A layer's recording sampled at the geometry's hits (shared by the layer's diffraction stages
// of every wavelength: the fringes do not depend on the probe).
struct FringeData {
  std::vector<Eigen::Vector3d> k_recorded;  // per hit, K_rec after processing (rad/µm)
  std::vector<std::uint8_t> valid;          // per hit: both recording beams enter the film there
};

// Per-hit flags of DiffractionData::flags.
inline constexpr std::uint8_t kEntered = 1, kEvanescent = 2, kExits = 4, kTir = 8, kValid = 16;

struct Obliquity {
  double c_r, c_s, vartheta, p_factor;
};

struct DiffractionData {
  double lambda_um = 0;
  std::vector<std::uint8_t> flags;       // per hit: kValid | kEntered | kEvanescent | kExits | kTir
  std::vector<Obliquity> obliquity;      // per hit (meaningful when entered)
  std::vector<Eigen::Vector3d> out_dir;  // per hit, local frame, when kExits
};

// Kogelnik per hit; grown in place when the pupil cull lets more rays in (done marks solved).
struct CoupledWaveData {
  std::vector<double> eff, zero, nu, xi;
  std::vector<std::uint8_t> done;
  long long done_count = 0;
};

// Per-ray flags of the stack stage.
inline constexpr std::uint8_t kSEvaluated = 1, kSExits = 2, kSTir = 4, kSTowardsEye = 8, kSEvanescent = 16;

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

// One layer's stage inputs of one wavelength, as the stack reads them.
using LayerDiffractions = std::vector<std::shared_ptr<DiffractionData>>;  // per layer
using LayerCoupledWaves = std::vector<std::shared_ptr<CoupledWaveData>>;  // per layer

// ---- Helpers -----------------------------------------------------------------------------
// f(begin, end) over [0, n), in parallel (TBB) beyond one grain.
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
std::string wavelengthLabel(double nm);  // "532nm"

// The layers as the stages name and order them.
struct LayerSetup {
  std::vector<std::string> label;  // unique name, else "#<index>"
  std::vector<int> order;          // indices by depth (offset_um), stable
  std::vector<FilmGrating> film;   // the processed films as the scene has them now
};
LayerSetup layerSetup(const Scene& scene);

// ---- Stages ------------------------------------------------------------------------------
// geometry: projector grid and plate hits.
std::uint64_t geometryKey(const Scene& scene, const TraceOptions& o);
std::shared_ptr<GeometryData> computeGeometry(const Scene& scene, const TraceOptions& o);
// The index of the medium the projector's rays arrive from.
double incidentIndex(const Scene& scene, const GeometryData& g);

// recording:<layer>
std::uint64_t recordingKey(const Scene& scene, std::size_t layer);
std::shared_ptr<RecordingData> computeRecording(const Scene& scene, std::size_t layer);

// diffraction:<layer>@<λ>, from the layer's fringes at the hits (computed with the first of
// its diffraction stages that reruns, memoised under the recording and geometry keys).
std::uint64_t fringesKey(std::uint64_t recording_key, std::uint64_t geometry_key);
std::shared_ptr<FringeData> computeFringes(const GeometryData& g, const RecordingData& r);
std::uint64_t diffractionKey(const Scene& scene, std::size_t layer, std::uint64_t recording_key,
                             std::uint64_t geometry_key, double wavelength_nm);
std::shared_ptr<DiffractionData> computeDiffraction(const Scene& scene, const GeometryData& g,
                                                    const FringeData& fringes, const FilmGrating& film,
                                                    double wavelength_nm);

// The eye the cull and the pupil stage read (its key includes the HOE pose, which places it).
std::uint64_t eyeKey(const Scene& scene, const std::array<double, 2>& gaze);

// coupled_wave:<layer>@<λ>. `need` marks the hits that need the coupled wave at this
// wavelength: every hit, or with the cull those some layer's diffracted order sends through the
// pupil.
void coupledWaveNeed(const GeometryData& g, const LayerDiffractions& dif, const EyePlacement& eye, bool cull_to_pupil,
                     std::vector<std::uint8_t>& need);
std::uint64_t coupledWaveKey(const Scene& scene, std::size_t layer, std::uint64_t diffraction_key, Polarization pol);
std::shared_ptr<CoupledWaveData> newCoupledWave(std::size_t hits);
// Solves the needed, entered, unsolved hits into `c` (marks needed hits that never enter as
// done); returns the number of Kogelnik solves.
long long solveCoupledWave(CoupledWaveData& c, const DiffractionData& d, const FilmGrating& film, Polarization pol,
                           const std::vector<std::uint8_t>& need);

// stack:<λ>
std::uint64_t stackKey(std::uint64_t geometry_key, const std::vector<int>& order,
                       const std::vector<std::uint64_t>& coupled_wave_keys, const LayerCoupledWaves& cw);
std::shared_ptr<StackData> computeStack(const GeometryData& g, const std::vector<int>& order,
                                        const LayerDiffractions& dif, const LayerCoupledWaves& cw);

// pupil, fov, analyses (per wavelength `stacks`)
using Stacks = std::vector<std::shared_ptr<StackData>>;
std::uint64_t pupilKey(std::uint64_t eye_key, const std::vector<std::uint64_t>& stack_keys);
void computePupil(PupilData& p, const GeometryData& g, const Stacks& stacks, const EyePlacement& eye,
                  const std::array<double, 2>& gaze);
std::uint64_t fovKey(std::uint64_t pupil_key, double efficiency_threshold);
void computeFov(FovData& f, const PupilData& pupil, const Stacks& stacks, std::size_t hits,
                double efficiency_threshold);
std::uint64_t analysesKey(std::uint64_t pupil_key, bool cull_to_pupil);
void computeAnalyses(AnalysesData& a, const PupilData& pupil, const Stacks& stacks, std::size_t hits,
                     bool cull_to_pupil);

// The TraceResult of one run from its stages.
TraceResult assembleResult(const TraceOptions& o, const std::vector<double>& wavelengths,
                           const std::array<double, 2>& gaze, const GeometryData& g, const Stacks& stacks,
                           const PupilData& pupil, const FovData& fov, const AnalysesData& an);

}  // namespace fovea::detail
