#include "viz/trace_overlay.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkLookupTable.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkUnsignedCharArray.h>

#include "model/physics/eye_model.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"
#include "viz/efficiency_colors.h"
#include "viz/polyline.h"
#include "viz/scene_view.h"

namespace fovea::viz {

namespace {

constexpr double kDash_mm = 1.2;         // dash and gap length of rays missing the pupil
constexpr double kAwayLength_mm = 30.0;  // drawn length of rays that do not head into the eye
constexpr double kRayWidth_px = 3.0;
constexpr double kMissOpacity = 0.55;
constexpr std::array<double, 3> kPupilGreen{0.25, 0.95, 0.35};
constexpr std::array<double, 3> kFoveaOrange{1.00, 0.55, 0.10};

// Line segments with one RGB colour each.
class Segments {
 public:
  void add(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const std::array<double, 3>& rgb) {
    const vtkIdType ids[2] = {points_->InsertNextPoint(a.data()), points_->InsertNextPoint(b.data())};
    lines_->InsertNextCell(2, ids);
    const unsigned char c[3] = {static_cast<unsigned char>(std::lround(rgb[0] * 255)),
                                static_cast<unsigned char>(std::lround(rgb[1] * 255)),
                                static_cast<unsigned char>(std::lround(rgb[2] * 255))};
    colors_->InsertNextTypedTuple(c);
  }
  void addDashed(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const std::array<double, 3>& rgb) {
    const double len = (b - a).norm();
    if (!(len > 0.0)) return;
    const Eigen::Vector3d u = (b - a) / len;
    for (double s = 0.0; s < len; s += 2.0 * kDash_mm) add(a + s * u, a + std::min(len, s + kDash_mm) * u, rgb);
  }
  bool empty() const { return lines_->GetNumberOfCells() == 0; }
  vtkSmartPointer<vtkActor> actor(double width) {
    auto data = vtkSmartPointer<vtkPolyData>::New();
    data->SetPoints(points_);
    data->SetLines(lines_);
    colors_->SetName("colors");
    data->GetCellData()->SetScalars(colors_);
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputData(data);
    mapper->SetScalarModeToUseCellData();
    mapper->SetColorModeToDirectScalars();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->LightingOff();
    actor->GetProperty()->SetLineWidth(static_cast<float>(width));
    return actor;
  }

 private:
  vtkNew<vtkPoints> points_;
  vtkNew<vtkCellArray> lines_;
  vtkSmartPointer<vtkUnsignedCharArray> colors_ = [] {
    auto c = vtkSmartPointer<vtkUnsignedCharArray>::New();
    c->SetNumberOfComponents(3);
    return c;
  }();
};

// n indices spread evenly over [lo, hi], both ends included.
std::vector<char> spread(int count, int lo, int hi, int n) {
  std::vector<char> pick(static_cast<std::size_t>(std::max(0, count)), 0);
  if (hi < lo) return pick;
  if (hi - lo + 1 <= n) {
    for (int i = lo; i <= hi; ++i) pick[static_cast<std::size_t>(i)] = 1;
    return pick;
  }
  for (int k = 0; k < n; ++k)
    pick[static_cast<std::size_t>(lo + static_cast<int>(std::lround(static_cast<double>(k) * (hi - lo) / (n - 1))))] =
        1;
  return pick;
}

// Which pixels of the grid a fan draws: rays spread evenly over the part of the projector
// field that lands on the plate (the projection is larger than the HOE, seed A.3), in the
// middle row (horizontal fan), the middle column (vertical) or a grid over both.
class FanSelection {
 public:
  FanSelection(const TraceResult& trace, const std::array<int, 2>& grid, const TraceOverlayOptions& o)
      : nx_(std::max(1, grid[0])), ny_(std::max(1, grid[1])), fan_(o.fan) {
    const std::size_t per = static_cast<std::size_t>(nx_) * ny_;
    std::vector<char> hit(per, 0);
    for (std::size_t i = 0; i < trace.ray_list.size(); ++i)
      if (trace.ray_list[i].hits_hoe) hit[i % per] = 1;
    auto range = [&](bool alongRow, int fixed) {
      int lo = 1 << 30, hi = -1;
      const int count = alongRow ? nx_ : ny_;
      for (int k = 0; k < count; ++k) {
        const int x = alongRow ? k : fixed, y = alongRow ? fixed : k;
        if (!hit[static_cast<std::size_t>(y * nx_ + x)]) continue;
        lo = std::min(lo, k);
        hi = std::max(hi, k);
      }
      return std::pair{lo, hi};
    };
    const int n = std::max(2, o.fan_rays);
    if (fan_ == FanPattern::Horizontal) {
      const auto [lo, hi] = range(true, ny_ / 2);
      cols_ = spread(nx_, lo, hi, n);
      rows_.assign(static_cast<std::size_t>(ny_), 0);
      rows_[static_cast<std::size_t>(ny_ / 2)] = 1;
    } else if (fan_ == FanPattern::Vertical) {
      const auto [lo, hi] = range(false, nx_ / 2);
      rows_ = spread(ny_, lo, hi, n);
      cols_.assign(static_cast<std::size_t>(nx_), 0);
      cols_[static_cast<std::size_t>(nx_ / 2)] = 1;
    } else {
      int x0 = 1 << 30, x1 = -1, y0 = 1 << 30, y1 = -1;
      for (int y = 0; y < ny_; ++y)
        for (int x = 0; x < nx_; ++x)
          if (hit[static_cast<std::size_t>(y * nx_ + x)]) {
            x0 = std::min(x0, x);
            x1 = std::max(x1, x);
            y0 = std::min(y0, y);
            y1 = std::max(y1, y);
          }
      const double aspect = x1 >= x0 && y1 > y0 ? static_cast<double>(x1 - x0) / (y1 - y0) : 1.0;
      const int nxs = std::max(2, static_cast<int>(std::lround(std::sqrt(n * aspect))));
      const int nys = std::max(2, static_cast<int>(std::lround(static_cast<double>(n) / nxs)));
      cols_ = spread(nx_, x0, x1, nxs);
      rows_ = spread(ny_, y0, y1, nys);
    }
  }
  bool contains(const std::array<int, 2>& px) const {
    return px[0] >= 0 && px[0] < nx_ && px[1] >= 0 && px[1] < ny_ && cols_[static_cast<std::size_t>(px[0])] &&
           rows_[static_cast<std::size_t>(px[1])];
  }

 private:
  int nx_, ny_;
  FanPattern fan_;
  std::vector<char> cols_, rows_;
};

// A filled disc (triangle fan) and its rim on a sphere around `centre`, the cap of angular
// radius cap_deg around the unit direction `axis`.
void addSphereCap(SceneLayer& layer, const Eigen::Vector3d& centre, double radius, const Eigen::Vector3d& axis,
                  double cap_deg, const std::array<double, 3>& rgb, const QString& id) {
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  const int n = 48;
  std::vector<Eigen::Vector3d> rim;
  for (int i = 0; i < n; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / n, th = cap_deg * kDeg;
    rim.push_back(centre + radius * (std::cos(th) * axis + std::sin(th) * (std::cos(phi) * u + std::sin(phi) * v)));
  }
  layer.add(flatLineActor(rim, rgb, 3.0, true), id, false);
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  const Eigen::Vector3d apex = centre + radius * axis;
  points->InsertNextPoint(apex.data());
  for (const auto& p : rim) points->InsertNextPoint(p.data());
  vtkNew<vtkCellArray> tris;
  for (vtkIdType i = 0; i < n; ++i) {
    const vtkIdType t[3] = {0, 1 + i, 1 + (i + 1) % n};
    tris->InsertNextCell(3, t);
  }
  data->SetPoints(points);
  data->SetPolys(tris);
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(rgb[0], rgb[1], rgb[2]);
  actor->GetProperty()->LightingOff();
  layer.add(actor, id, false);
}

// A quad mesh over the projector grid: the plate points of the pixels offset by `offset`,
// each coloured by sum/count through the efficiency colours; a quad is drawn where its four
// pixels hit the plate and have a count. Returns the number of quads.
int addPixelMesh(SceneLayer& layer, const std::array<int, 2>& grid, const std::vector<Eigen::Vector3d>& where,
                 const std::vector<char>& hit, const std::vector<double>& sum, const std::vector<int>& count,
                 const Eigen::Vector3d& offset) {
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> eta;
  eta->SetName("efficiency");
  for (std::size_t i = 0; i < where.size(); ++i) {
    const Eigen::Vector3d p = where[i] + offset;
    points->InsertNextPoint(p.data());
    eta->InsertNextValue(count[i] ? sum[i] / count[i] : 0.0);
  }
  vtkNew<vtkCellArray> quads;
  const int nx = grid[0], ny = grid[1];
  int cells = 0;
  for (int y = 0; y + 1 < ny; ++y)
    for (int x = 0; x + 1 < nx; ++x) {
      const vtkIdType q[4] = {y * nx + x, y * nx + x + 1, (y + 1) * nx + x + 1, (y + 1) * nx + x};
      bool ok = true;
      for (vtkIdType id : q) ok = ok && hit[static_cast<std::size_t>(id)] && count[static_cast<std::size_t>(id)];
      if (!ok) continue;
      quads->InsertNextCell(4, q);
      ++cells;
    }
  if (cells == 0) return 0;
  data->SetPoints(points);
  data->SetPolys(quads);
  data->GetPointData()->SetScalars(eta);
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(data);
  mapper->SetLookupTable(efficiencyLookupTable());
  mapper->UseLookupTableScalarRangeOn();
  mapper->InterpolateScalarsBeforeMappingOn();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  layer.add(actor, "hoe");
  return cells;
}

}  // namespace

bool wavelengthShown(const TraceOverlayOptions& o, double nm) {
  return std::none_of(o.hidden_wavelengths_nm.begin(), o.hidden_wavelengths_nm.end(),
                      [nm](double h) { return std::abs(h - nm) < 1e-6; });
}

TraceOverlay::TraceOverlay(SceneView* view, OverlayRole role) : view_(view), role_(role) {
  colorBar_ = efficiencyColorBar();
  colorBar_->VisibilityOff();
  // In the view's right margin (its own renderer), title and labels inside the strip.
  colorBar_->SetPosition(0.30, 0.18);
  colorBar_->SetWidth(0.55);
  colorBar_->SetHeight(0.62);
  colorBar_->SetMaximumWidthInPixels(200);
  colorBar_->SetBarRatio(0.32);
  if (role_ == OverlayRole::Main) view_->legendRenderer()->AddViewProp(colorBar_);
}

TraceOverlay::~TraceOverlay() {
  if (role_ == OverlayRole::Main) view_->legendRenderer()->RemoveViewProp(colorBar_);
}

QString TraceOverlay::layerName(const char* base) const {
  return role_ == OverlayRole::LeftEye ? QStringLiteral("left-") + base : QString(base);
}

void TraceOverlay::setPlateShift(const Eigen::Vector3d& shift_bench) {
  if (role_ == OverlayRole::Main)
    view_->setHoeDisplayShift(shift_bench);
  else
    view_->setLeftHoeDisplayShift(shift_bench);
}

vtkScalarBarActor* TraceOverlay::colorBar() const {
  return colorBar_;
}

void TraceOverlay::clear() {
  for (const char* name : {"rays", "eye_marks", "effmap", "seen"}) view_->layer(layerName(name)).clear();
  colorBar_->VisibilityOff();
  if (role_ == OverlayRole::Main)
    view_->setHoeDisplayShift(Eigen::Vector3d::Zero());
  else
    view_->setLeftHoeDisplayShift(std::nullopt);  // the mirror of the right one's again
  stats_ = {};
  view_->requestRender();
}

void TraceOverlay::show(const Scene& scene, const TraceResult& trace, const std::array<int, 2>& grid,
                        const std::array<double, 2>& shift, const TraceOverlayOptions& o) {
  SceneLayer& rays = view_->layer(layerName("rays"));
  SceneLayer& marks = view_->layer(layerName("eye_marks"));
  SceneLayer& effmap = view_->layer(layerName("effmap"));
  SceneLayer& seen = view_->layer(layerName("seen"));
  rays.clear();
  marks.clear();
  effmap.clear();
  seen.clear();
  stats_ = {};
  const Frame nominal = frameOf(scene.hoe.pose);
  const Eigen::Vector3d shift_bench = shift[0] * nominal.x() + shift[1] * nominal.y();
  setPlateShift(shift_bench);
  const EyePlacement eye = placeEye(scene, trace.gaze_deg[0], trace.gaze_deg[1]);

  // Pupil outline and fovea (Fig. S5: green pupil, orange fovea).
  {
    const Eigen::Vector3d u = eye.gaze.unitOrthogonal(), v = eye.gaze.cross(u);
    std::vector<Eigen::Vector3d> ring;
    for (int i = 0; i < 48; ++i) {
      const double phi = 2.0 * std::numbers::pi * i / 48;
      ring.push_back(eye.pupil_center + 0.15 * eye.gaze +
                     eye.pupil_radius_mm * (std::cos(phi) * u + std::sin(phi) * v));
    }
    marks.add(flatLineActor(ring, kPupilGreen, 3.0, true), "eye", false);
    addSphereCap(marks, eye.rotation_center, eye.eyeball_radius_mm + 0.12, -eye.gaze,
                 std::max(0.5, scene.eye.fovea_radius_deg), kFoveaOrange, "eye");
  }

  const std::size_t per = static_cast<std::size_t>(std::max(1, grid[0] * grid[1]));
  if (o.rays) {
    Segments solid, dashed;
    const FanSelection fan(trace, grid, o);
    for (const TracedRay& r : trace.ray_list) {
      if (!r.hits_hoe || !wavelengthShown(o, r.wavelength_nm) || !fan.contains(r.pixel)) continue;
      ++stats_.rays_drawn;
      const bool low = !(r.efficiency >= kLowEfficiency);
      if (low) ++stats_.rays_low;
      const auto rgb = efficiencyColor(r.efficiency);
      solid.add(r.source, r.hoe_point, rgb);
      if (!r.exits) continue;
      const PupilCrossing c = crossPupil(eye, r.hoe_point, r.out_direction);
      const bool reaches = c.radius_mm > 0.0 || c.in_pupil;
      const Eigen::Vector3d end = reaches ? c.point : Eigen::Vector3d(r.hoe_point + kAwayLength_mm * r.out_direction);
      if (r.in_pupil) {
        ++stats_.rays_in_pupil;
        solid.add(r.hoe_point, end, rgb);
      } else {
        ++stats_.rays_missing;
        dashed.addDashed(r.hoe_point, end, rgb);
      }
    }
    // Solid fans drawn as lit tubes that read at any zoom; misses dashed and faded.
    if (!solid.empty()) {
      auto a = solid.actor(kRayWidth_px);
      a->GetProperty()->SetRenderLinesAsTubes(true);
      rays.add(a, {}, false);
    }
    if (!dashed.empty()) {
      auto a = dashed.actor(kRayWidth_px - 1.0);
      a->GetProperty()->SetOpacity(kMissOpacity);
      rays.add(a, {}, false);
    }
  }

  if (role_ == OverlayRole::Main && grid[0] > 1 && grid[1] > 1 && !trace.ray_list.empty()) {
    // Per pixel: plate point and mean efficiency over the shown wavelengths, of every ray
    // (the efficiency map) and of the rays entering the pupil (what the eye sees).
    const std::size_t blocks = trace.ray_list.size() / per;
    std::vector<double> sum(per, 0.0), sum_seen(per, 0.0);
    std::vector<int> count(per, 0), count_seen(per, 0);
    std::vector<char> hit(per, 0);
    std::vector<Eigen::Vector3d> where(per, Eigen::Vector3d::Zero());
    for (std::size_t b = 0; b < blocks; ++b)
      for (std::size_t i = 0; i < per; ++i) {
        const TracedRay& r = trace.ray_list[b * per + i];
        if (!r.hits_hoe) continue;
        hit[i] = 1;
        where[i] = r.hoe_point;
        if (!wavelengthShown(o, r.wavelength_nm)) continue;
        sum[i] += r.efficiency;
        ++count[i];
        if (r.in_pupil) {
          sum_seen[i] += r.efficiency;
          ++count_seen[i];
        }
      }
    const Frame plate{nominal.origin + shift_bench, nominal.axes};
    if (o.efficiency_map)
      for (double side : {-1.0, 1.0})
        stats_.effmap_cells = addPixelMesh(effmap, grid, where, hit, sum, count, side * 0.95 * plate.z());
    // The eye's side of the plate is the one facing the eye (-z of the HOE, scene.h).
    addPixelMesh(seen, grid, where, hit, sum_seen, count_seen, -1.05 * plate.z());
  }
  colorBar_->SetVisibility(role_ == OverlayRole::Main && (o.rays || o.efficiency_map));
  view_->requestRender();
}

}  // namespace fovea::viz
