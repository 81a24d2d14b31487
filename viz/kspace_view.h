#pragma once
// The grating-vector cloud (seed A.1, Fig. S2) as a 3-D scatter in k-space (rad/um, HOE
// local frame: z is the film normal): for every sampled plate point the grating vector
// recorded there (small points in the layer's recording colour) and the grating vector the
// probe needs to be Bragg matched into the wave it is diffracted into (larger points
// coloured by that layer's efficiency, gray below 0.1). Bragg-matched probes sit on the
// recorded surface; mismatched ones spread along k_z (model/physics/grating_cloud.h). The
// mismatch is a fraction of |K|, so it is drawn exaggerated x kMismatchExaggeration (said
// in the legend).

#include <vector>

#include <vtkSmartPointer.h>

#include "model/physics/grating_cloud.h"
#include "viz/vtk_gl_widget.h"

class vtkActor;
class vtkCubeAxesActor;
class vtkScalarBarActor;
class vtkTextActor;

namespace fovea::viz {

class KSpaceView : public VtkGlWidget {
  Q_OBJECT
 public:
  explicit KSpaceView(QWidget* parent = nullptr);
  ~KSpaceView() override;

  // Replaces the cloud; samples of hidden wavelengths are left out. Resets the camera the
  // first time (or when `resetCamera`).
  void setCloud(const std::vector<GratingVectorSample>& samples, const std::vector<double>& hidden_wavelengths_nm,
                bool resetCamera = false);
  int recordedPoints() const { return recorded_; }
  int probePoints() const { return probe_; }
  // Largest |K_probe,z - K_rec,z| of the shown samples (rad/um).
  double maxDephasing() const { return maxDephasing_; }
  void resetCamera();
  static constexpr double kMismatchExaggeration = 10.0;

 private:
  double exaggeration_ = kMismatchExaggeration;
  vtkSmartPointer<vtkActor> recordedActor_, probeActor_;
  vtkSmartPointer<vtkCubeAxesActor> axes_;
  vtkSmartPointer<vtkScalarBarActor> bar_;
  vtkSmartPointer<vtkTextActor> legend_;
  int recorded_ = 0, probe_ = 0;
  double maxDephasing_ = 0;
  bool framed_ = false;
};

}  // namespace fovea::viz
