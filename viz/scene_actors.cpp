#include "viz/scene_actors.h"

#include <algorithm>
#include <cmath>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCubeSource.h>
#include <vtkCylinderSource.h>
#include <vtkMatrix4x4.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRotationalExtrusionFilter.h>
#include <vtkSphereSource.h>

#include "model/analysis/beam_shaping.h"
#include "model/analysis/foveal_optics.h"
#include "model/color/srgb.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"
#include "viz/polyline.h"
#include "viz/scene_elements.h"

namespace fovea::viz {

namespace {

vtkSmartPointer<vtkMatrix4x4> matrixOf(const Frame& f) {
  auto m = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m->SetElement(r, c, f.axes(r, c));
    m->SetElement(r, 3, f.origin(r));
  }
  return m;
}

Frame frameAlong(const Eigen::Vector3d& origin, const Eigen::Matrix3d& axes) {
  Frame f;
  f.origin = origin;
  f.axes = axes;
  return f;
}

vtkSmartPointer<vtkActor> makeActor(vtkPolyData* data, const std::array<double, 3>& rgb, double opacity,
                                    const Frame& frame) {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->SetUserMatrix(matrixOf(frame));
  vtkProperty* p = actor->GetProperty();
  p->SetColor(rgb[0], rgb[1], rgb[2]);
  p->SetOpacity(opacity);
  p->SetAmbient(0.25);
  p->SetDiffuse(0.75);
  p->SetSpecular(0.15);
  return actor;
}

template <class Source>
vtkSmartPointer<vtkPolyData> output(Source* source) {
  source->Update();
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->DeepCopy(source->GetOutput());
  return data;
}

vtkSmartPointer<vtkPolyData> box(double sx, double sy, double sz, const Eigen::Vector3d& centre) {
  vtkNew<vtkCubeSource> cube;
  cube->SetXLength(sx);
  cube->SetYLength(sy);
  cube->SetZLength(sz);
  cube->SetCenter(centre.x(), centre.y(), centre.z());
  return output(cube.GetPointer());
}

// A spherical cap around local +z: polar angle 0..max_deg.
vtkSmartPointer<vtkPolyData> sphereCap(double radius, double max_deg) {
  vtkNew<vtkSphereSource> s;
  s->SetRadius(radius);
  s->SetThetaResolution(64);
  s->SetPhiResolution(max_deg >= 180.0 ? 48 : 12);
  s->SetStartPhi(0.0);
  s->SetEndPhi(max_deg);
  return output(s.GetPointer());
}

void addHoe(const Scene& scene, SceneLayer& layer) {
  const Frame hf = frameOf(scene.hoe.pose);
  const double w = scene.hoe.size_mm[0], h = scene.hoe.size_mm[1];
  double max_thickness_mm = 1e-3;
  for (const auto& l : scene.hoe_layers) max_thickness_mm = std::max(max_thickness_mm, l.thickness_um * 1e-3);
  // Micrometre films are invisible at bench scale: scale thickness and spacing together.
  const double exaggeration = std::max(1.0, kMinDrawnLayer_mm / max_thickness_mm);
  double z_min = 0.0, z_max = 0.0;
  for (std::size_t i = 0; i < scene.hoe_layers.size(); ++i) {
    const auto& l = scene.hoe_layers[i];
    const double t = l.thickness_um * 1e-3 * exaggeration, z = l.offset_um * 1e-3 * exaggeration;
    z_min = std::min(z_min, z - t / 2);
    z_max = std::max(z_max, z + t / 2);
    auto actor = makeActor(box(w, h, t, {0, 0, z}), color::wavelengthColor(l.recording.wavelength_nm), 0.4, hf);
    layer.add(actor, hoeLayerId(static_cast<int>(i)));
  }
  // The carrier's outline around the stack, and the substrate on the world side: local +z,
  // which is bench +z (towards the world) at zero rotation (scene.h).
  const double margin = 0.5;
  auto outline = makeActor(polylineData({{-w / 2 - margin, -h / 2 - margin, z_max},
                                         {w / 2 + margin, -h / 2 - margin, z_max},
                                         {w / 2 + margin, h / 2 + margin, z_max},
                                         {-w / 2 - margin, h / 2 + margin, z_max}},
                                        true),
                           colors::kSubstrate, 1.0, hf);
  outline->GetProperty()->SetLineWidth(2.0);
  outline->GetProperty()->LightingOff();
  layer.add(outline, "hoe");
  if (scene.hoe.substrate_thickness_mm > 0.0) {
    const double s = scene.hoe.substrate_thickness_mm;
    layer.add(makeActor(box(w, h, s, {0, 0, z_max + s / 2}), colors::kSubstrate, 0.35, hf), "hoe");
  }
}

void addProjector(const Scene& scene, SceneLayer& layer, SceneLayer& light) {
  const Projector& p = scene.projector;
  const Frame pf = frameOf(p.pose);
  layer.add(makeActor(box(24.0, 16.0, 36.0, {0, 0, -18.5}), colors::kProjectorBody, 1.0, pf), "projector");
  layer.add(
      makeActor(sphereCap(std::max(p.exit_pupil_diameter_mm, 1.0), 90.0),
                p.wavelengths_nm.empty() ? colors::kProjectorFrustum : color::wavelengthColor(p.wavelengths_nm.front()),
                1.0, pf),
      "projector");
  // Frustum: the four corner rays of the projection up to where they meet the HOE plane
  // (or 100 mm along the axis when a ray misses it or runs away from it).
  const Frame hf = frameOf(scene.hoe.pose);
  const double tx = std::tan(p.fov_deg[0] / 2 * kDeg), ty = std::tan(p.fov_deg[1] / 2 * kDeg);
  std::vector<Eigen::Vector3d> corners;
  const int signs[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (const auto& sign : signs) {
    const Eigen::Vector3d local(sign[0] * tx, sign[1] * ty, 1.0);
    const Eigen::Vector3d dir = pf.axes * local;
    const double denom = hf.z().dot(dir);
    double t = std::abs(denom) > 1e-9 ? hf.z().dot(hf.origin - pf.origin) / denom : -1.0;
    if (!(t > 0.0 && t * local.norm() < 2000.0)) t = 100.0;
    corners.push_back(t * local);
  }
  // The projection is drawn as a faint outline only (edges from the exit pupil and the rim on
  // the HOE plane): it locates the light without covering the ray fans drawn inside it.
  std::vector<Eigen::Vector3d> edge_pts{corners[0], {0, 0, 0},  corners[1], corners[2], {0, 0, 0},
                                        corners[3], corners[0], corners[1], corners[2], corners[3]};
  auto edges = makeActor(polylineData(edge_pts, false), colors::kProjectorFrustum, kFrustumOpacity, pf);
  edges->GetProperty()->LightingOff();
  edges->GetProperty()->SetLineWidth(1.0);
  light.add(edges, "projector", /*pickable=*/false);  // clicks go through the light to what it hits
}

void addEye(const Scene& scene, SceneLayer& layer) {
  const EyePlacement e = placeEye(scene);
  const Frame ef = frameAlong(e.rotation_center, rotationFromDeg({scene.eye.gaze_deg[0], scene.eye.gaze_deg[1], 0.0}));
  const double r = e.eyeball_radius_mm;
  // A muted, half-transparent globe: the pupil in front and the fovea marked on the back
  // (trace overlay) both stay visible, and the ball does not outshine the rays.
  auto globe = makeActor(sphereCap(r, 180.0), colors::kEyeball, kEyeballOpacity, ef);
  globe->GetProperty()->SetSpecular(0.0);
  globe->GetProperty()->SetAmbient(0.35);
  globe->GetProperty()->SetDiffuse(0.55);
  layer.add(globe, "eye");
  // Iris (12 mm across, anatomical average) and pupil (the scene's pupil diameter) as caps
  // just outside the globe; the pupil is the dark disc the rays aim at.
  const double iris_deg = std::asin(std::min(1.0, 6.0 / r)) / kDeg;
  const double pupil_deg = std::asin(std::min(1.0, e.pupil_radius_mm / r)) / kDeg;
  layer.add(makeActor(sphereCap(r + 0.05, iris_deg), colors::kIris, 1.0, ef), "eye");
  auto pupil = makeActor(sphereCap(r + 0.1, pupil_deg), colors::kPupil, 1.0, ef);
  pupil->GetProperty()->LightingOff();
  layer.add(pupil, "eye");
  // Optical axis from the rotation centre along the gaze, 30 mm past the HOE plane.
  const double len = scene.eye.relief_mm + r + 30.0;
  auto axis = makeActor(polylineData({{0, 0, 0}, {0, 0, len}}, false), colors::kOpticalAxis, 0.8, ef);
  axis->GetProperty()->LightingOff();
  axis->GetProperty()->SetLineWidth(1.5);
  layer.add(axis, "eye");
}

void addFovealDisplay(const Scene& scene, SceneLayer& layer) {
  const FovealDisplay& f = scene.foveal_display;
  const Frame ff = frameOf(f.pose);
  // The panel emits along local +z from its face at z = 0; 1 mm of glass behind it.
  layer.add(makeActor(box(f.size_mm[0], f.size_mm[1], 1.0, {0, 0, -0.5}), colors::kMicroOled, 1.0, ff),
            "foveal_display");
  // Image combiner on the eye's zero-gaze axis, eye_distance_mm in front of the pupil. Its
  // aperture passes the foveal field (half the horizontal foveal FOV) plus the pupil.
  const EyePlacement e = placeEye(scene, 0.0, 0.0);
  const ImageCombiner& ic = f.combiner;
  const double half_fov = 0.5 * fovealFovDeg(scene)[0] * kDeg;
  const double radius = ic.eye_distance_mm * std::tan(half_fov) + e.pupil_radius_mm;
  vtkNew<vtkCylinderSource> disc;  // axis along local y: turned to z by the frame below
  disc->SetRadius(radius);
  disc->SetHeight(1.5);
  disc->SetResolution(64);
  Eigen::Matrix3d y_to_z;
  y_to_z << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  const Frame cf = frameAlong(e.pupil_center + ic.eye_distance_mm * e.gaze, y_to_z);
  layer.add(makeActor(output(disc.GetPointer()), colors::kCombiner, 0.35, cf), "foveal_display");
  std::vector<Eigen::Vector3d> rim;  // its edge, in the disc's plane (local x, -z of cf's y axis)
  for (int i = 0; i < 64; ++i) {
    const double phi = 2.0 * kPi * i / 64;
    rim.emplace_back(radius * std::cos(phi), 0.0, radius * std::sin(phi));
  }
  auto edge = makeActor(polylineData(rim, true), colors::kCombiner, 0.9, cf);
  edge->GetProperty()->LightingOff();
  edge->GetProperty()->SetLineWidth(1.5);
  layer.add(edge, "foveal_display");
}

void addLens(const Scene& scene, SceneLayer& layer) {
  const BeamShapingLens& l = scene.lens;
  const double rim = l.diameter_mm / 2.0;
  // Symmetric bi-convex lens with the thick-lens radii of the spot model (beam_shaping.h).
  const double R = biconvexRadiusMm(l.focal_length_mm, l.index, l.center_thickness_mm);
  const double absR = std::max(std::abs(R), rim * 1.0001);
  auto sag = [&](double rr) { return std::copysign(absR - std::sqrt(absR * absR - rr * rr), R); };
  double half_ct = std::max(l.center_thickness_mm, 0.1) / 2.0;
  if (half_ct - sag(rim) < 0.1) half_ct = sag(rim) + 0.1;  // keep a drawable edge
  std::vector<Eigen::Vector3d> profile;
  const int n = 24;
  for (int i = 0; i <= n; ++i) {
    const double rr = rim * i / n;
    profile.emplace_back(rr, 0.0, half_ct - sag(rr));
  }
  for (int i = n; i >= 0; --i) {
    const double rr = rim * i / n;
    profile.emplace_back(rr, 0.0, -(half_ct - sag(rr)));
  }
  vtkNew<vtkRotationalExtrusionFilter> revolve;  // about local z, the lens axis
  revolve->SetInputData(polylineData(profile, false));
  revolve->SetResolution(64);
  revolve->SetAngle(360.0);
  revolve->CappingOff();
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(revolve->GetOutputPort());
  normals->ConsistencyOn();
  normals->AutoOrientNormalsOff();
  const Frame lf = frameOf(l.pose);
  auto actor = makeActor(output(normals.GetPointer()), colors::kLens, l.enabled ? 0.75 : 0.2, lf);
  actor->GetProperty()->SetSpecular(0.5);
  actor->GetProperty()->SetSpecularPower(30.0);
  layer.add(actor, "beam_shaping_lens");
  // Its rim as a solid ring, so the thin lens reads from any side.
  std::vector<Eigen::Vector3d> ring;
  for (int i = 0; i < 64; ++i) {
    const double phi = 2.0 * kPi * i / 64;
    ring.emplace_back(rim * std::cos(phi), rim * std::sin(phi), 0.0);
  }
  auto edge = makeActor(polylineData(ring, true), colors::kLensRim, l.enabled ? 1.0 : 0.35, lf);
  edge->GetProperty()->LightingOff();
  edge->GetProperty()->SetLineWidth(2.0);
  layer.add(edge, "beam_shaping_lens");
}

// Translation stages as their travel: a bar along the driven element's local axis from the
// low to the high soft limit (relative to the element's nominal pose), with end stops.
// Rotation stages and the gaze camera (not part of the bench drawing) get no actor.
void addStages(const Scene& scene, SceneLayer& layer) {
  for (std::size_t i = 0; i < scene.stages.size(); ++i) {
    const StageBinding& st = scene.stages[i];
    const Pose* pose = st.element == "hoe"                 ? &scene.hoe.pose
                       : st.element == "foveal_display"    ? &scene.foveal_display.pose
                       : st.element == "projector"         ? &scene.projector.pose
                       : st.element == "beam_shaping_lens" ? &scene.lens.pose
                                                           : nullptr;
    const int axis = st.axis == "x" ? 0 : st.axis == "y" ? 1 : st.axis == "z" ? 2 : -1;
    if (!pose || axis < 0) continue;
    const Frame f = frameOf(*pose);
    Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
    a[axis] = st.soft_limits[0];
    b[axis] = st.soft_limits[1];
    const QString id = stageId(static_cast<int>(i));
    auto bar = makeActor(polylineData({a, b}, false), colors::kStage, 1.0, f);
    bar->GetProperty()->SetLineWidth(3.0);
    bar->GetProperty()->LightingOff();
    layer.add(bar, id);
    for (const Eigen::Vector3d& end : {a, b}) {
      Frame stop = f;
      stop.origin = f.toBench(end);
      layer.add(makeActor(sphereCap(0.8, 180.0), colors::kStage, 1.0, stop), id);
    }
  }
}

}  // namespace

void buildEyeActors(const Scene& scene, SceneLayer& layer) {
  addEye(scene, layer);
}

void buildSceneActors(const Scene& scene, SceneLayer& layer, SceneLayer& light, SceneLayer& stages) {
  addHoe(scene, layer);
  addProjector(scene, layer, light);
  addEye(scene, layer);
  addFovealDisplay(scene, layer);
  addLens(scene, layer);
  addStages(scene, stages);
}

}  // namespace fovea::viz
