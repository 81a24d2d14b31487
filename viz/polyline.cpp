#include "viz/polyline.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>

namespace fovea::viz {

vtkSmartPointer<vtkPolyData> polylineData(const std::vector<Eigen::Vector3d>& pts, bool closed) {
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  for (const auto& p : pts) points->InsertNextPoint(p.x(), p.y(), p.z());
  vtkNew<vtkCellArray> lines;
  const auto n = static_cast<vtkIdType>(pts.size());
  lines->InsertNextCell(closed ? n + 1 : n);
  for (vtkIdType i = 0; i < n; ++i) lines->InsertCellPoint(i);
  if (closed) lines->InsertCellPoint(0);
  data->SetPoints(points);
  data->SetLines(lines);
  return data;
}

vtkSmartPointer<vtkActor> flatLineActor(const std::vector<Eigen::Vector3d>& pts, const std::array<double, 3>& rgb,
                                        double width, bool closed) {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(polylineData(pts, closed));
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(rgb[0], rgb[1], rgb[2]);
  actor->GetProperty()->SetLineWidth(static_cast<float>(width));
  actor->GetProperty()->LightingOff();
  return actor;
}

}  // namespace fovea::viz
