// HOE recording, 3-D reconstruction and the trace to the eye: physics checks on the prototype.
#include <QtTest>

#include <cmath>
#include <numbers>

#include "app/embedded_scene.h"
#include "model/physics/eye_model.h"
#include "model/physics/hoe_recording.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"

namespace tst_hoe_trace {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;
// Distance from point q to the ray origin + t dir (t >= 0).
double distanceToRay(const Eigen::Vector3d& q, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  const double t = std::max(0.0, (q - origin).dot(dir));
  return (origin + t * dir - q).norm();
}
}  // namespace

class TestHoeTrace : public QObject {
  Q_OBJECT
 private slots:
  void recordingGeometryIsBraggMatchedAndFocused() {
    // Every point of every recorded layer, probed by its own reference at its own wavelength,
    // is on Bragg (xi = 0) and sends its ray through the signal focus (the pupil centre).
    double worst_miss_mm = 0.0, eta_min = 1.0, eta_max = 0.0;
    for (bool conjugate : {false, true}) {
      Scene s = embeddedDefaultScene();
      for (auto& l : s.hoe_layers) l.recording.phase_conjugate = conjugate;
      const Frame f = frameOf(s.hoe.pose);
      for (const auto& layer : s.hoe_layers) {
        const LayerModel m = makeLayerModel(s.hoe, layer);
        const Eigen::Vector3d p = toVec(layer.recording.reference_point_mm);
        const Eigen::Vector3d focus = toVec(layer.recording.signal_point_mm);
        for (double u = -22.0; u <= 22.0; u += 5.5) {
          for (double v = -18.0; v <= 18.0; v += 4.5) {
            const RecordedGrating g = recordAt(m, u, v);
            QVERIFY(g.valid);
            const Eigen::Vector3d point = f.toBench({u, v, 0.0});
            const Eigen::Vector3d probe = f.axes.transpose() * (point - p).normalized();
            const LayerDiffraction d =
                diffractLayer(m, g.k_recorded, probe, s.hoe.cover_index, s.hoe.cover_index, s.hoe.substrate_index,
                              layer.recording.wavelength_nm, Polarization::S);
            QVERIFY(d.exits);
            QVERIFY(d.grating.reflection());
            QVERIFY2(d.grating.kogelnik.xi < 1e-9, qPrintable(QString::number(d.grating.kogelnik.xi)));
            const double miss_mm = distanceToRay(focus, point, f.axes * d.out_dir);
            worst_miss_mm = std::max(worst_miss_mm, miss_mm);
            eta_min = std::min(eta_min, d.grating.kogelnik.efficiency);
            eta_max = std::max(eta_max, d.grating.kogelnik.efficiency);
            QVERIFY2(miss_mm < 1e-3, qPrintable(QString("(%1, %2): %3 mm").arg(u).arg(v).arg(miss_mm)));
            // On Bragg the efficiency is Kogelnik's tanh^2(nu) with nu = kappa d / sqrt(c_R |c_S|).
            const double nu = std::numbers::pi * layer.n1 * layer.thickness_um /
                              (layer.recording.wavelength_nm * 1e-3 * std::sqrt(d.grating.c_r * -d.grating.c_s));
            QVERIFY(std::abs(d.grating.kogelnik.efficiency - std::pow(std::tanh(nu), 2)) < 1e-9);
          }
        }
      }
    }
    qInfo("recording geometry: worst miss of the focus %.3g mm, s efficiency %.3f .. %.3f", worst_miss_mm, eta_min,
          eta_max);
    // docs/physics.md prints "s: 0.71-0.92 over the plate": held to those digits.
    QVERIFY2(std::abs(eta_min - 0.71) <= 0.005, qPrintable(QString::number(eta_min)));
    QVERIFY2(std::abs(eta_max - 0.92) <= 0.005, qPrintable(QString::number(eta_max)));
  }

  void phaseConjugateRecordingWritesTheSameFringes() {
    Scene s = embeddedDefaultScene();
    HoeLayer l = s.hoe_layers[1];
    l.recording.phase_conjugate = false;
    const LayerModel direct = makeLayerModel(s.hoe, l);
    l.recording.phase_conjugate = true;
    const LayerModel conj = makeLayerModel(s.hoe, l);
    for (double u : {-20.0, 0.0, 13.0})
      for (double v : {-15.0, 0.0, 9.0}) {
        const RecordedGrating a = recordAt(direct, u, v), b = recordAt(conj, u, v);
        QVERIFY((a.k_recorded - b.k_recorded).norm() < 1e-12 * a.k_recorded.norm());
      }
  }

  void shrinkageAndIndexChangeShiftTheBraggWavelength() {
    // On-axis reflection hologram at the plate centre: reference from (0,0,-500), focus at
    // (0,0,-22): K_rec = -2 k0 n_rec z. Shrinkage s scales K_z by 1/(1+s): Bragg moves to
    // lambda (1+s). A mean-index change moves it to lambda n0 / n_rec.
    Scene s = embeddedDefaultScene();
    HoeLayer l = s.hoe_layers[1];
    l.recording.reference_point_mm = {0.0, 0.0, -500.0};
    const Eigen::Vector3d probe(0.0, 0.0, 1.0);
    const auto xiAt = [&](const HoeLayer& layer, double lambda) {
      const LayerModel m = makeLayerModel(s.hoe, layer);
      return diffractLayer(m, recordAt(m, 0.0, 0.0).k_recorded, probe, 1.0, 1.0, 1.0, lambda, Polarization::S)
          .grating.kogelnik.xi;
    };
    QVERIFY(xiAt(l, 532.0) < 1e-9);
    HoeLayer shrunk = l;
    shrunk.shrinkage_percent = -2.0;
    QVERIFY(xiAt(shrunk, 532.0) > 1.0);
    QVERIFY(xiAt(shrunk, 532.0 * 0.98) < 1e-9);
    HoeLayer swelled = l;
    swelled.recording_n0_delta = 0.01;  // recorded at n0 - 0.01
    QVERIFY(xiAt(swelled, 532.0 * l.n0 / (l.n0 - 0.01)) < 1e-9);
    QVERIFY(xiAt(swelled, 532.0) > 0.1);
  }

  void prototypeFovAtZeroGaze() {
    // The HOE is 44 x 36 mm at 22 mm eye relief: 2 atan(22/22) = 90 deg by 2 atan(18/22) =
    // 78.6 deg. Every ray is on Bragg (recorded in place) and converges to the pupil centre, so
    // the FOV is the plate's angular size, less the last ray spacing of the finite grid.
    const Scene s = embeddedDefaultScene();
    TraceOptions o;
    o.rays = 20000;
    o.gaze_deg = std::array<double, 2>{0.0, 0.0};
    const TraceResult r = traceScene(s, o);
    qInfo("prototype at 0 deg gaze: FOV %.2f x %.2f deg (diagonal %.2f), %d/%d rays efficient, mean eff %.3f",
          r.fov_deg.horizontal, r.fov_deg.vertical, r.fov_deg.diagonal, r.rays_efficient, r.rays, r.mean_efficiency);
    QVERIFY(r.fov_deg.horizontal > 87.0 && r.fov_deg.horizontal <= 90.0 + 1e-9);
    QVERIFY(r.fov_deg.vertical > 76.5 && r.fov_deg.vertical <= 78.6);
    QCOMPARE(r.rays_in_pupil, r.rays_on_hoe);  // the Maxwellian focus lies inside the pupil
    QCOMPARE(r.per_wavelength.size(), std::size_t{3});
    for (const auto& w : r.per_wavelength) QVERIFY(w.fov_deg.horizontal > 87.0);
    // Unpolarised Kogelnik efficiency on Bragg: between tanh^2 of the p and s couplings.
    QVERIFY(r.mean_efficiency > 0.5 && r.mean_efficiency < 1.0);
  }

  void gazeNeedsTheHoeShift() {
    // At 20 deg gaze the pupil centre moves 11.5 sin 20 = 3.9 mm > the 2.5 mm pupil radius away
    // from the focus: no ray enters. Shifting the plate along the gaze carries the focus with it.
    const Scene s = embeddedDefaultScene();
    TraceOptions o;
    o.gaze_deg = std::array<double, 2>{20.0, 0.0};
    QCOMPARE(traceScene(s, o).rays_in_pupil, 0);
    o.hoe_shift_mm = {3.4, 0.0};
    const TraceResult shifted = traceScene(s, o);
    QVERIFY(shifted.fov_deg.horizontal > 80.0);
    o.gaze_deg = std::array<double, 2>{-20.0, 0.0};
    o.hoe_shift_mm = {-3.4, 0.0};
    QVERIFY(traceScene(s, o).fov_deg.horizontal > 80.0);
    o.hoe_shift_mm = {3.4, 0.0};  // the wrong way
    QCOMPARE(traceScene(s, o).rays_in_pupil, 0);
  }

  void shiftedPlateCarriesItsFringes() {
    // With the plate shifted, a ray meets the grating recorded at the same plate coordinates.
    const Scene s = embeddedDefaultScene();
    TraceOptions o;
    o.keep_rays = true;
    o.rays = 1000;
    o.wavelength_nm = 532.0;
    o.hoe_shift_mm = {2.0, -1.0};
    const TraceResult r = traceScene(s, o);
    const Frame f = frameOf(s.hoe.pose);
    const LayerModel green = makeLayerModel(s.hoe, s.hoe_layers[1]);
    int checked = 0;
    for (const auto& ray : r.ray_list) {
      if (!ray.hits_hoe || ray.layer != 1) continue;
      const Eigen::Vector3d local = f.toLocal(ray.hoe_point) - Eigen::Vector3d(2.0, -1.0, 0.0);
      const RecordedGrating g = recordAt(green, local.x(), local.y());
      const LayerDiffraction d = diffractLayer(green, g.k_recorded, f.axes.transpose() * ray.projector_direction, 1.0,
                                               1.0, 1.0, 532.0, Polarization::Unpolarized);
      QVERIFY((f.axes * d.out_dir - ray.out_direction).norm() < 1e-12);
      QVERIFY(std::abs(local.x()) <= 22.0 && std::abs(local.y()) <= 18.0);
      ++checked;
    }
    QVERIFY(checked > 150);
  }

  void sourceShiftMovesTheProjectorAlongZ() {
    const Scene s = embeddedDefaultScene();
    TraceOptions o;
    o.keep_rays = true;
    o.rays = 50;
    o.source_shift_mm = -4.0;
    const TraceResult r = traceScene(s, o);
    const Eigen::Vector3d expect = toVec(s.projector.pose.position_mm) + Eigen::Vector3d(0, 0, -4.0);
    for (const auto& ray : r.ray_list) QVERIFY((ray.source - expect).norm() < 1e-12);
  }

  void everyLayerActsOnEveryWavelength() {
    // Without the green layer, 532 nm light only meets the red and blue gratings far off Bragg:
    // a small but computed efficiency, and no efficient ray.
    Scene s = embeddedDefaultScene();
    s.hoe_layers.erase(s.hoe_layers.begin() + 1);
    TraceOptions o;
    o.wavelength_nm = 532.0;
    o.keep_rays = true;
    o.efficiency_threshold = 0.0;
    const TraceResult r = traceScene(s, o);
    double max_eff = 0.0, sum = 0.0;
    for (const auto& ray : r.ray_list) {
      max_eff = std::max(max_eff, ray.efficiency);
      sum += ray.efficiency;
    }
    QVERIFY(sum > 0.0);
    QVERIFY(max_eff < 0.05);
    o.efficiency_threshold = 0.1;
    QCOMPARE(traceScene(s, o).rays_efficient, 0);
  }

  void raysMissingThePupilAreFlagged() {
    Scene s = embeddedDefaultScene();
    s.eye.lateral_offset_mm = {6.0, 0.0};  // the focus lies 6 mm off the pupil centre
    TraceOptions o;
    o.keep_rays = true;
    o.rays = 400;
    const TraceResult r = traceScene(s, o);
    QCOMPARE(r.rays_in_pupil, 0);
    QCOMPARE(r.fov_deg.horizontal, 0.0);
    for (const auto& ray : r.ray_list)
      if (ray.exits && ray.towards_eye) QVERIFY(ray.pupil_radius_mm > 3.0);
  }

  void eyeAnglesFollowTheGaze() {
    const Eigen::Matrix3d axes = rotationFromDeg({10.0, 0.0, 0.0});
    // Light arriving from the gaze direction has field angle (0, 0).
    const auto f0 = fieldAngleDeg(axes, -gazeDirection(10.0, 0.0));
    QVERIFY(std::abs(f0[0]) < 1e-12 && std::abs(f0[1]) < 1e-12);
    const auto f1 = fieldAngleDeg(Eigen::Matrix3d::Identity(), -gazeDirection(25.0, -7.0));
    QVERIFY(std::abs(f1[0] - 25.0) < 1e-12 && std::abs(f1[1] + 7.0) < 1e-12);
    const Scene s = embeddedDefaultScene();
    const EyePlacement e = placeEye(s, 0.0, 0.0);
    QVERIFY(crossPupil(e, Eigen::Vector3d(2.0, 0, 0), Eigen::Vector3d(0, 0, -1)).in_pupil);
    QVERIFY(!crossPupil(e, Eigen::Vector3d(2.6, 0, 0), Eigen::Vector3d(0, 0, -1)).in_pupil);
    QVERIFY(!crossPupil(e, Eigen::Vector3d(0, 0, -40), Eigen::Vector3d(0, 0, 1)).in_pupil);  // leaving the eye
  }

  void projectorGridAndPixelBeam() {
    const Scene s = embeddedDefaultScene();
    const auto grid = projectorGrid(s.projector, 4000);
    QVERIFY(std::abs(grid[0] * grid[1] - 4000) < 120);
    const auto rays = projectorRays(s.projector, 4000);
    double hmax = 0;
    for (const auto& r : rays) hmax = std::max(hmax, std::abs(r.angle_deg[0]));
    QVERIFY(hmax < 20.0 && hmax > 19.5);
    const PixelBeamSize at_waist = pixelBeamFwhm(s.projector.pixel_beam, 150.0);
    QVERIFY(std::abs(at_waist.long_axis_um - 600.0) < 1e-9);
    const PixelBeamSize far = pixelBeamFwhm(s.projector.pixel_beam, 1150.0);
    QVERIFY(std::abs(far.long_axis_um - (600.0 + 1.2 * 1000.0)) < 1e-9);
    QVERIFY(far.long_axis_um / far.short_axis_um < 1.001);
    const PixelBeamSize exit = pixelBeamFwhm(s.projector.pixel_beam, 0.0);
    QVERIFY(std::abs(exit.long_axis_um / exit.short_axis_um - 1.6) < 1e-12);
  }
};

QTEST_GUILESS_MAIN(TestHoeTrace)

}  // namespace tst_hoe_trace
#include "tst_hoe_trace.moc"
