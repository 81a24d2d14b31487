#include "viz/efficiency_colors.h"

#include <algorithm>
#include <cmath>

#include <vtkLookupTable.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>

namespace fovea::viz {

namespace {
// Control points of the ramp (t = 0 at kLowEfficiency, 1 at 1).
constexpr std::array<std::array<double, 3>, 5> kRamp{
    {{0.30, 0.12, 0.70}, {0.62, 0.16, 0.66}, {0.88, 0.30, 0.45}, {0.98, 0.58, 0.20}, {0.99, 0.92, 0.20}}};
}  // namespace

std::array<double, 3> efficiencyColor(double efficiency) {
  const double e = std::clamp(efficiency, 0.0, 1.0);
  if (!(e >= kLowEfficiency)) return kLowEfficiencyGray;
  const double t = (e - kLowEfficiency) / (1.0 - kLowEfficiency) * (kRamp.size() - 1);
  const std::size_t i = std::min<std::size_t>(kRamp.size() - 2, static_cast<std::size_t>(std::floor(t)));
  const double f = t - static_cast<double>(i);
  std::array<double, 3> c{};
  for (int k = 0; k < 3; ++k) c[k] = (1.0 - f) * kRamp[i][k] + f * kRamp[i + 1][k];
  return c;
}

vtkSmartPointer<vtkLookupTable> efficiencyLookupTable() {
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  const int n = 256;
  lut->SetNumberOfTableValues(n);
  lut->SetRange(kLowEfficiency, 1.0);
  for (int i = 0; i < n; ++i) {
    const auto c = efficiencyColor(kLowEfficiency + (1.0 - kLowEfficiency) * i / (n - 1));
    lut->SetTableValue(i, c[0], c[1], c[2], 1.0);
  }
  lut->SetBelowRangeColor(kLowEfficiencyGray[0], kLowEfficiencyGray[1], kLowEfficiencyGray[2], 1.0);
  lut->UseBelowRangeColorOn();
  lut->Build();
  return lut;
}

vtkSmartPointer<vtkScalarBarActor> efficiencyColorBar() {
  auto bar = vtkSmartPointer<vtkScalarBarActor>::New();
  bar->SetLookupTable(efficiencyLookupTable());
  bar->SetTitle("efficiency");
  bar->SetNumberOfLabels(4);
  bar->SetLabelFormat("%.1f");
  bar->DrawBelowRangeSwatchOn();
  bar->SetBelowRangeAnnotation("< 0.1");
  bar->SetOrientationToVertical();
  bar->SetPosition(0.90, 0.30);
  bar->SetWidth(0.09);
  bar->SetHeight(0.45);
  bar->SetMaximumWidthInPixels(80);
  bar->SetBarRatio(0.35);
  for (vtkTextProperty* t :
       {bar->GetTitleTextProperty(), bar->GetLabelTextProperty(), bar->GetAnnotationTextProperty()}) {
    t->SetColor(0.92, 0.92, 0.92);
    t->SetFontSize(13);
    t->ShadowOff();
    t->ItalicOff();
    t->BoldOff();
  }
  bar->UnconstrainedFontSizeOn();  // keep the 13 px labels at any viewport size
  bar->SetTextPositionToSucceedScalarBar();
  bar->PickableOff();
  return bar;
}

}  // namespace fovea::viz
