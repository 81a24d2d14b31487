#pragma once
// Polylines for the 3-D view: the geometry (open or closed through its first point) and an
// unlit, single-colour line actor of it (overlays, handles, marks).
#include <array>
#include <vector>

#include <vtkSmartPointer.h>
#include <Eigen/Core>

class vtkActor;
class vtkPolyData;

namespace fovea::viz {

vtkSmartPointer<vtkPolyData> polylineData(const std::vector<Eigen::Vector3d>& pts, bool closed);
vtkSmartPointer<vtkActor> flatLineActor(const std::vector<Eigen::Vector3d>& pts, const std::array<double, 3>& rgb,
                                        double width, bool closed);

}  // namespace fovea::viz
