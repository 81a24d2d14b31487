#include "viz/kspace_view.h"

#include <algorithm>
#include <cmath>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCoordinate.h>
#include <vtkCubeAxesActor.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include "model/color/srgb.h"
#include "viz/efficiency_colors.h"
#include "viz/scene_actors.h"

namespace fovea::viz {

namespace {

vtkSmartPointer<vtkActor> pointActor(double size) {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetScalarModeToUsePointData();
  mapper->SetColorModeToDirectScalars();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetPointSize(static_cast<float>(size));
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetRepresentationToPoints();
  return actor;
}

class Cloud {
 public:
  Cloud() { colors_->SetNumberOfComponents(3); }
  void add(const Eigen::Vector3d& p, const std::array<double, 3>& rgb) {
    const vtkIdType id = points_->InsertNextPoint(p.data());
    verts_->InsertNextCell(1, &id);
    const unsigned char c[3] = {static_cast<unsigned char>(std::lround(rgb[0] * 255)),
                                static_cast<unsigned char>(std::lround(rgb[1] * 255)),
                                static_cast<unsigned char>(std::lround(rgb[2] * 255))};
    colors_->InsertNextTypedTuple(c);
  }
  vtkSmartPointer<vtkPolyData> data() {
    auto d = vtkSmartPointer<vtkPolyData>::New();
    d->SetPoints(points_);
    d->SetVerts(verts_);
    d->GetPointData()->SetScalars(colors_);
    return d;
  }

 private:
  vtkNew<vtkPoints> points_;
  vtkNew<vtkCellArray> verts_;
  vtkNew<vtkUnsignedCharArray> colors_;
};

}  // namespace

KSpaceView::KSpaceView(QWidget* parent) : VtkGlWidget(parent) {
  vtkRenderer* ren = renderer();
  ren->GradientBackgroundOn();
  ren->SetBackground(0.08, 0.09, 0.11);
  ren->SetBackground2(0.20, 0.22, 0.27);
  recordedActor_ = pointActor(3.0);
  probeActor_ = pointActor(3.0);
  ren->AddActor(recordedActor_);
  ren->AddActor(probeActor_);
  axes_ = vtkSmartPointer<vtkCubeAxesActor>::New();
  axes_->SetCamera(ren->GetActiveCamera());
  axes_->SetXTitle("Kx (rad/um)");
  axes_->SetYTitle("Ky (rad/um)");
  axes_->SetZTitle("Kz (rad/um)");
  axes_->SetFlyModeToOuterEdges();
  axes_->SetGridLineLocation(vtkCubeAxesActor::VTK_GRID_LINES_FURTHEST);
  for (int i = 0; i < 3; ++i) {
    axes_->GetTitleTextProperty(i)->SetColor(0.9, 0.9, 0.9);
    axes_->GetLabelTextProperty(i)->SetColor(0.8, 0.8, 0.8);
  }
  axes_->GetXAxesLinesProperty()->SetColor(0.7, 0.7, 0.7);
  axes_->GetYAxesLinesProperty()->SetColor(0.7, 0.7, 0.7);
  axes_->GetZAxesLinesProperty()->SetColor(0.7, 0.7, 0.7);
  axes_->VisibilityOff();
  ren->AddActor(axes_);
  bar_ = efficiencyColorBar();
  bar_->SetTitle("efficiency");
  ren->AddViewProp(bar_);
  legend_ = vtkSmartPointer<vtkTextActor>::New();
  legend_->SetInput("layer colour: recorded K    efficiency colour: K the probe needs (mismatch along Kz drawn x10)");
  legend_->GetTextProperty()->SetFontSize(12);
  legend_->GetTextProperty()->SetColor(0.9, 0.9, 0.9);
  legend_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  legend_->GetPositionCoordinate()->SetValue(0.01, 0.96);
  ren->AddViewProp(legend_);
}

KSpaceView::~KSpaceView() = default;

void KSpaceView::setCloud(const std::vector<GratingVectorSample>& samples, const std::vector<double>& hidden,
                          bool reset) {
  Cloud rec, probe;
  recorded_ = probe_ = 0;
  maxDephasing_ = 0;
  double b[6] = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  auto grow = [&b](const Eigen::Vector3d& p) {
    for (int i = 0; i < 3; ++i) {
      b[2 * i] = std::min(b[2 * i], p[i]);
      b[2 * i + 1] = std::max(b[2 * i + 1], p[i]);
    }
  };
  for (const auto& s : samples) {
    if (std::any_of(hidden.begin(), hidden.end(), [&](double h) { return std::abs(h - s.wavelength_nm) < 1e-6; }))
      continue;
    rec.add(s.k_recorded, color::wavelengthColor(s.wavelength_nm));
    const Eigen::Vector3d drawn = s.k_recorded + exaggeration_ * (s.k_probe - s.k_recorded);
    probe.add(drawn, efficiencyColor(s.efficiency));
    grow(s.k_recorded);
    grow(drawn);
    ++recorded_;
    ++probe_;
    maxDephasing_ = std::max(maxDephasing_, std::abs(s.k_probe.z() - s.k_recorded.z()));
  }
  static_cast<vtkPolyDataMapper*>(recordedActor_->GetMapper())->SetInputData(rec.data());
  static_cast<vtkPolyDataMapper*>(probeActor_->GetMapper())->SetInputData(probe.data());
  if (recorded_ > 0) {
    axes_->SetBounds(b);
    axes_->VisibilityOn();
  } else {
    axes_->VisibilityOff();
  }
  if ((reset || !framed_) && recorded_ > 0) {
    framed_ = true;
    resetCamera();
  }
  requestRender();
}

void KSpaceView::resetCamera() {
  vtkRenderer* ren = renderer();
  double b[6];
  recordedActor_->GetBounds(b);
  const double* pb = probeActor_->GetBounds();
  for (int i = 0; i < 3; ++i) {
    b[2 * i] = std::min(b[2 * i], pb[2 * i]);
    b[2 * i + 1] = std::max(b[2 * i + 1], pb[2 * i + 1]);
  }
  vtkCamera* cam = ren->GetActiveCamera();
  const double c[3] = {(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2};
  cam->SetFocalPoint(c);
  cam->SetPosition(c[0] + 1.0, c[1] + 0.7, c[2] - 1.2);  // from the eye side, above
  cam->SetViewUp(0, 1, 0);
  ren->ResetCamera(b);
  ren->ResetCameraClippingRange();
  requestRender();
}

}  // namespace fovea::viz
