#pragma once
// The grating-vector cloud of seed A.1 / Fig. S2: at every plate point a projector ray hits,
// the grating vector recorded there (K_rec = k_signal - k_reference, hoe_recording.h) and
// the grating vector the probe actually needs to be Bragg matched into the wave it is
// diffracted into, K_probe = k_diffracted - rho (both inside the film, rad/um, HOE local
// frame). Kogelnik's coupled-wave theory keeps the tangential part of the diffracted wave
// (sigma_t = rho_t + K_rec,t) and puts it on the index sphere, so K_probe - K_rec lies along
// the film normal: the recorded points form a surface, the probe's spread out along local z
// — the "grating vector cloud along the z-axis" of the seed (Uchida's beta-value method).
// |K_probe,z - K_rec,z| is the dephasing that lowers the efficiency.

#include <vector>

#include <Eigen/Core>

#include "model/physics/trace.h"
#include "model/scene/scene.h"

namespace fovea {

struct GratingVectorSample {
  Eigen::Vector3d plate_point_mm = Eigen::Vector3d::Zero();  // plate coordinates (local, z = 0)
  Eigen::Vector3d k_recorded = Eigen::Vector3d::Zero();      // K_rec of the layer there (rad/um, local)
  Eigen::Vector3d k_probe = Eigen::Vector3d::Zero();         // k_diffracted - rho (rad/um, local)
  double wavelength_nm = 0.0;
  double efficiency = 0.0;  // this layer's diffraction efficiency for the probe
  int layer = -1;           // index in scene.hoe_layers
};

// One sample per ray of `rays` (from diffractScene/traceScene) that hits the plate, taken on
// the layer recorded at the wavelength nearest the ray's, with the plate shifted by
// hoe_shift_mm (local x, y) as in the trace. Rays whose probe cannot enter the film, whose
// recording beams cannot, or whose diffracted order is evanescent give no sample. At most
// max_samples samples, taken evenly over the rays.
std::vector<GratingVectorSample> gratingVectorCloud(const Scene& scene, const std::vector<TracedRay>& rays,
                                                    const std::array<double, 2>& hoe_shift_mm,
                                                    std::size_t max_samples = 6000,
                                                    Polarization polarization = Polarization::Unpolarized);

}  // namespace fovea
