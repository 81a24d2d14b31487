// The binocular closed loop with focus (devices/bench/binocular_loop.h), with the synthetic
// tracker (true gaze + Gaussian noise, no rendering): the left and right eyes are mirror
// images (to 1e-12), a direct-drive focus stage meets 0.25 D within 300 ms over 30-250 cm and
// the prototype's screw stage does not, and the vergence noise matches the closed form; a
// binocular scene in mode "explicit" runs its left eye on its own left train.
#include <QtTest>
#include "app/embedded_scene.h"
#include "tests/test_paths.h"

#include <cmath>

#include "devices/bench/binocular_loop.h"
#include "model/scene/eye_scene.h"
#include "model/scene/scene_io.h"

namespace tst_binocular_loop {

using namespace fovea;
using namespace fovea::devices;

namespace {
using fovea::embeddedDefaultScene;
BinocularOptions synthetic(const char* stage) {
  BinocularOptions o;
  o.track = false;
  o.loop.camera_fps = 120;
  o.loop.stage_model = stage;
  return o;
}
Scene binocularPrototype() {
  const SceneLoadResult r = loadSceneFile(std::string(FOVEA_SOURCE_DIR) + "/resources/scenes/binocular-prototype.json");
  if (!r.ok()) qFatal("binocular-prototype.json: %s", r.errors.front().c_str());
  return *r.scene;
}
// Every number of one eye's monocular loop result.
std::vector<double> eyeNumbers(const ClosedLoopResult& e) {
  std::vector<double> v{e.latency_to_command_s, e.time_off_fovea_s,    e.time_beyond_tolerance_s, e.duration_s,
                        e.fov_partly_lost_s,    e.fov_lost_s,          e.mean_light_lost,         double(e.unsettled),
                        double(e.frames),       double(e.frames_found)};
  for (const Stats& s : {e.hoe_move_s, e.oled_move_s, e.inset_error_deg, e.settle_s, e.hoe_error_mm})
    v.insert(v.end(), {s.mean, s.p95, s.max, double(s.count)});
  v.insert(v.end(), e.off_fovea_per_saccade_s.begin(), e.off_fovea_per_saccade_s.end());
  return v;
}
std::vector<double> focusNumbers(const FocusEye& f) {
  return {f.model.mirror_distance_mm,
          f.model.focal_length_mm,
          f.model.nominal_panel_mm,
          f.travel.travel_mm,
          f.travel.range_d,
          f.counts_per_mm,
          f.move_s.mean,
          f.move_s.max};
}
// Every number of a result, eye by eye (e: 0 left, 1 right) and the shared ones (e: 2).
std::vector<double> resultNumbers(const BinocularResult& r, int e) {
  if (e < 2) {
    const auto i = static_cast<std::size_t>(e);
    std::vector<double> v = eyeNumbers(r.eyes[i]);
    const auto f = focusNumbers(r.focus_eyes[i]);
    v.insert(v.end(), f.begin(), f.end());
    v.insert(v.end(), {r.hoe_move_s[i].mean, r.hoe_move_s[i].max, r.oled_move_s[i].mean, r.oled_move_s[i].max});
    for (const auto& x : r.fixations) v.insert(v.end(), {x.final_focus_error_d[i], x.inset_on_fovea_fraction[i]});
    return v;
  }
  std::vector<double> v{r.closed_form_sigma_d_mean, r.measured_sigma_d_raw, r.measured_sigma_d_filtered,
                        r.measured_bias_d_raw,      r.focus_move_s.mean,    double(r.vergence_samples)};
  for (const auto& x : r.fixations)
    v.insert(v.end(), {x.peak_focus_error_d, x.time_to_tolerance_s.value_or(-1), x.focus_motion_s});
  return v;
}
// The Fick line of sight of scene_geometry.h's gazeDirection, Ry(yaw) Rx(-pitch) (0, 0, 1)
// (not included: its fovea::Frame would meet devices::Frame in this test batch).
Eigen::Vector3d lineOfSight(double yaw_deg, double pitch_deg) {
  const double y = yaw_deg * M_PI / 180, p = pitch_deg * M_PI / 180;
  return {std::cos(p) * std::sin(y), std::sin(p), std::cos(p) * std::cos(y)};
}
std::vector<BinocularFixation> depthSteps() {
  // 30 <-> 250 cm, in several directions, and a symmetric one.
  return {{300, {10, 5}, 1.0}, {2500, {-8, -4}, 1.0}, {300, {-12, 0}, 1.0}, {2500, {12, 6}, 1.0}, {800, {0, 0}, 1.0}};
}
}  // namespace

class TestBinocularLoop : public QObject {
  Q_OBJECT
  Scene scene_ = embeddedDefaultScene();

 private slots:
  // Fixations F with seeds (a, b) against the mirrored fixations (-yaw, pitch) with the seeds
  // swapped: the left eye of one run is the right eye of the other.
  void mirrorSymmetry() {
    auto fx = depthSteps();
    auto mirrored = fx;
    for (auto& f : mirrored) f.direction_deg[0] = -f.direction_deg[0];
    BinocularOptions a = synthetic("DDSM50"), b = synthetic("DDSM50");
    a.seed_left = 11, a.seed_right = 12;
    b.seed_left = 12, b.seed_right = 11;
    const BinocularResult ra = runBinocularLoop(scene_, fx, a), rb = runBinocularLoop(scene_, mirrored, b);
    QCOMPARE(ra.fixations.size(), rb.fixations.size());
    double worst = 0;
    for (std::size_t i = 0; i < ra.fixations.size(); ++i) {
      const auto &fa = ra.fixations[i], &fb = rb.fixations[i];
      worst = std::max({worst, std::abs(fa.inset_on_fovea_fraction[0] - fb.inset_on_fovea_fraction[1]),
                        std::abs(fa.inset_on_fovea_fraction[1] - fb.inset_on_fovea_fraction[0]),
                        std::abs(fa.final_focus_error_d[0] - fb.final_focus_error_d[1]),
                        std::abs(fa.final_focus_error_d[1] - fb.final_focus_error_d[0]),
                        std::abs(fa.peak_focus_error_d - fb.peak_focus_error_d)});
      QCOMPARE(fa.time_to_tolerance_s.has_value(), fb.time_to_tolerance_s.has_value());
      if (fa.time_to_tolerance_s) worst = std::max(worst, std::abs(*fa.time_to_tolerance_s - *fb.time_to_tolerance_s));
    }
    for (int e = 0; e < 2; ++e) {
      const auto &ea = ra.eyes[static_cast<std::size_t>(e)], &eb = rb.eyes[static_cast<std::size_t>(1 - e)];
      worst = std::max({worst, std::abs(ea.inset_error_deg.mean - eb.inset_error_deg.mean),
                        std::abs(ea.inset_error_deg.max - eb.inset_error_deg.max),
                        std::abs(ea.hoe_error_mm.mean - eb.hoe_error_mm.mean),
                        std::abs(ea.time_off_fovea_s - eb.time_off_fovea_s)});
    }
    qInfo("mirror symmetry: worst difference %.3g", worst);
    QVERIFY(worst <= 1e-12);
    // The symmetric fixation straight ahead with equal seeds: both eyes alike.
    BinocularOptions c = synthetic("DDSM50");
    c.seed_left = c.seed_right = 5;
    const BinocularResult rc = runBinocularLoop(scene_, {{500, {0, 3}, 1.0}}, c);
    QVERIFY(std::abs(rc.fixations[0].final_focus_error_d[0] - rc.fixations[0].final_focus_error_d[1]) <= 1e-12);
    QVERIFY(std::abs(rc.eyes[0].inset_error_deg.mean - rc.eyes[1].inset_error_deg.mean) <= 1e-12);
  }

  void directDriveMeetsTheTarget() {
    const auto fx = depthSteps();
    const BinocularResult r = runBinocularLoop(scene_, fx, synthetic("DDSM50"));
    for (const auto& f : r.fixations) {
      qInfo(
          "DDSM50: %.0f cm: to 0.25 D %s ms (eye %.0f ms), final %.4f D, peak %.3f D, focus move %.1f ms, "
          "on fovea %.3f / %.3f",
          f.fixation.distance_mm / 10,
          f.time_to_tolerance_s ? QByteArray::number(*f.time_to_tolerance_s * 1000, 'f', 1).constData() : "never",
          f.eye_time_to_tolerance_s.value_or(-1) * 1000, f.final_focus_error_worst_d, f.peak_focus_error_d,
          f.focus_motion_s * 1000, f.inset_on_fovea_fraction[0], f.inset_on_fovea_fraction[1]);
      QVERIFY(f.time_to_tolerance_s.has_value());
      QVERIFY(*f.time_to_tolerance_s <= 0.3);
      QVERIFY(std::abs(f.final_focus_error_worst_d) < 0.1);
      QVERIFY(f.inset_on_fovea_fraction[0] > 0.8 && f.inset_on_fovea_fraction[1] > 0.8);
    }
    QVERIFY(r.travel.travel_mm > 1 && r.travel.travel_mm < 25);
    // Vergence noise late in the fixations against the closed form (0.05 deg per axis).
    qInfo("vergence noise: closed form %.4f D, measured raw %.4f D (bias %.4f), filtered %.4f D",
          r.closed_form_sigma_d_mean, r.measured_sigma_d_raw, r.measured_bias_d_raw, r.measured_sigma_d_filtered);
    QVERIFY(std::abs(r.measured_sigma_d_raw / r.closed_form_sigma_d_mean - 1) < 0.15);
    QVERIFY(r.measured_sigma_d_filtered < r.measured_sigma_d_raw);
  }

  void screwStageMissesTheTarget() {
    const BinocularResult r = runBinocularLoop(scene_, depthSteps(), synthetic("MTS25-Z8"));
    int late = 0;
    for (const auto& f : r.fixations)
      if (!f.time_to_tolerance_s || *f.time_to_tolerance_s > 0.3) ++late;
    qInfo("MTS25-Z8: %d of %zu fixations late; focus move up to %.0f ms", late, r.fixations.size(),
          r.focus_move_s.max * 1000);
    QVERIFY(late >= 3);
  }

  // Mode "explicit" with the left train written out from the mirror (explicitBinocularScene):
  // the very numbers of mode "mirror", both eyes and the shared ones.
  void explicitMirrorTrainGivesMirrorNumbers() {
    const Scene mirror = binocularPrototype();
    const Scene expl = explicitBinocularScene(mirror);
    QVERIFY(expl.binocular->left.has_value());
    BinocularOptions o = synthetic("DDSM50");
    const BinocularResult a = runBinocularLoop(mirror, depthSteps(), o), b = runBinocularLoop(expl, depthSteps(), o);
    for (int e = 0; e < 3; ++e) {
      const auto va = resultNumbers(a, e), vb = resultNumbers(b, e);
      QCOMPARE(va.size(), vb.size());
      for (std::size_t k = 0; k < va.size(); ++k) QCOMPARE(vb[k], va[k]);
    }
  }

  // A left train with a weaker combiner (magnification 21.9 -> 15, the same 800 mm image; its
  // focus axis's soft limits widened to its travel): its
  // focal length f = (d_f - b) / (M - 1) grows from 36.84 to 55.0 mm, so the 30-250 cm focus
  // needs more travel (u(v) = v f / (v + f)) and the micro-OLED more lateral shift
  // (x_f = (d_f + r) tan(alpha) / M); on a DDSM50 (moves triangular, t = 2 sqrt(d / a)) every
  // left focus move takes sqrt(travel ratio) times the right one's. The right eye is untouched.
  void explicitLeftTrainChangesTheLeftEyeOnly() {
    const Scene mirror = binocularPrototype();
    Scene expl = explicitBinocularScene(mirror);
    expl.binocular->left->foveal_display.combiner.magnification = 15.0;
    // Its focus axis covers its own 30-250 cm travel, z = u0 - u = +5.64 ... -2.47 mm.
    for (auto& axis : expl.binocular->left->stages)
      if (axis.element == "foveal_display" && axis.axis == "z") axis.soft_limits = {-3.0, 6.5};
    BinocularOptions o = synthetic("DDSM50");
    const BinocularResult a = runBinocularLoop(mirror, depthSteps(), o), b = runBinocularLoop(expl, depthSteps(), o);
    // The right eye: every number as in mode mirror; the shared focus numbers follow the slower (left) stage.
    const auto ra = resultNumbers(a, 1), rb = resultNumbers(b, 1);
    for (std::size_t k = 0; k < ra.size(); ++k) QCOMPARE(rb[k], ra[k]);
    const FocusEye &L = b.focus_eyes[0], &R = b.focus_eyes[1];
    const double f_left = (800.0 - 30.0) / (15.0 - 1.0);
    qInfo(
        "left combiner M 15: f %.4f mm (right %.4f), travel %.4f mm (right %.4f), focus move mean %.2f ms (right "
        "%.2f), left oled move mean %.2f ms (mirror %.2f), left inset error mean %.4f deg (mirror %.4f)",
        L.model.focal_length_mm, R.model.focal_length_mm, L.travel.travel_mm, R.travel.travel_mm, L.move_s.mean * 1000,
        R.move_s.mean * 1000, b.oled_move_s[0].mean * 1000, a.oled_move_s[0].mean * 1000,
        b.eyes[0].inset_error_deg.mean, a.eyes[0].inset_error_deg.mean);
    QVERIFY(std::abs(L.model.focal_length_mm - f_left) < 1e-9);
    QVERIFY(std::abs(R.model.focal_length_mm - 770.0 / 20.9) < 1e-9);
    const auto panel = [](double f, double d) { return (d - 30.0) * f / (d - 30.0 + f); };
    QVERIFY(std::abs(L.travel.travel_mm - (panel(f_left, 2500) - panel(f_left, 300))) < 1e-9);
    QVERIFY(L.travel.travel_mm > 2 * R.travel.travel_mm);
    // Per fixation change each eye's panel move |du| between the settled depths (z of the
    // fixation point; the start at 800 cm straight ahead) as a triangular DDSM50 profile
    // (a = 5000 mm/s^2, v^2 / a = 50 mm above every move here): t = 2 sqrt(|du| / a).
    const auto fx = depthSteps();
    for (std::size_t e = 0; e < 2; ++e) {
      const FocusEye& fe = b.focus_eyes[e];
      const double radius = mirror.eye.eyeball_diameter_mm / 2;
      double depth_from = o.start_distance_mm, mean = 0;
      for (const auto& f : fx) {
        const double depth_to = f.distance_mm * lineOfSight(f.direction_deg[0], f.direction_deg[1]).z();
        const double du =
            panelForImageDistance(fe.model, depth_to - radius) - panelForImageDistance(fe.model, depth_from - radius);
        mean += 2 * std::sqrt(std::abs(du) / 5000.0) / static_cast<double>(fx.size());
        depth_from = depth_to;
      }
      QVERIFY2(std::abs(fe.move_s.mean - mean) < 1e-9, e ? "right" : "left");
    }
    QVERIFY(L.move_s.mean > 1.3 * R.move_s.mean);
    for (std::size_t i = 0; i < b.fixations.size(); ++i)
      QVERIFY(b.fixations[i].focus_motion_s > a.fixations[i].focus_motion_s);
    // The micro-OLED's lateral moves: 21.9 / 15 times longer shifts, slower moves, a larger inset error.
    QVERIFY(b.oled_move_s[0].mean > a.oled_move_s[0].mean);
    QVERIFY(b.eyes[0].inset_error_deg.mean > a.eyes[0].inset_error_deg.mean);
    // The left focus still follows within 0.25 D at the end of each fixation.
    for (const auto& f : b.fixations) QVERIFY(std::abs(f.final_focus_error_d[0]) < 0.1);
  }

  // A left train whose focus axis (foveal_display z) stops at z = 1 mm instead of 3.5 mm: the
  // left image cannot come nearer than d(z = 1 mm) = 499.2 mm, so at the 30 cm fixations the
  // left eye ends with the error of that plane seen along its line of sight (about -1.3 D),
  // as predicted to 0.02 D (the eyes' vergence still 0.5 % short after 1 s), while the right
  // eye's numbers do not change.
  void explicitLeftFocusLimitsHoldTheLeftImageBack() {
    const Scene mirror = binocularPrototype();
    Scene expl = explicitBinocularScene(mirror);
    int bound = 0;
    for (auto& b : expl.binocular->left->stages)
      if (b.element == "foveal_display" && b.axis == "z") b.soft_limits = {-1.5, 1.0}, ++bound;
    QCOMPARE(bound, 1);
    const BinocularOptions o = synthetic("DDSM50");
    const BinocularResult a = runBinocularLoop(mirror, depthSteps(), o), b = runBinocularLoop(expl, depthSteps(), o);
    const auto ra = resultNumbers(a, 1), rb = resultNumbers(b, 1);
    for (std::size_t k = 0; k < ra.size(); ++k) QCOMPARE(rb[k], ra[k]);
    const FocusStageModel m = focusStageModel(eyeScene(expl, EyeSide::Left));
    const double radius = mirror.eye.eyeball_diameter_mm / 2;
    const double plane_z = radius + imageDistanceForFocusAxis(m, 1.0);
    QVERIFY(std::abs(plane_z - radius - 499.2) < 0.1);
    int near = 0;
    for (std::size_t i = 0; i < b.fixations.size(); ++i) {
      const BinocularFixation& f = b.fixations[i].fixation;
      const double left = b.fixations[i].final_focus_error_d[0];
      if (f.distance_mm > 400) {
        QVERIFY(std::abs(left - a.fixations[i].final_focus_error_d[0]) < 1e-9);  // within the limits: as mirror
        continue;
      }
      const Eigen::Vector3d q = lineOfSight(f.direction_deg[0], f.direction_deg[1]) * f.distance_mm;
      const Eigen::Vector3d c = o.geometry.leftCentre();
      const auto g = gaze::gazeTowardsDeg(c, q);
      const Eigen::Vector3d dir = lineOfSight(g[0], g[1]), pupil = c + radius * dir;
      const double predicted = 1000.0 / ((plane_z - pupil.z()) / dir.z()) - 1000.0 / (q - pupil).norm();
      qInfo("30 cm at (%.0f, %.0f) deg: left final error %.4f D (predicted %.4f, mirror %.4f), right %.4f D",
            f.direction_deg[0], f.direction_deg[1], left, predicted, a.fixations[i].final_focus_error_d[0],
            b.fixations[i].final_focus_error_d[1]);
      QVERIFY(predicted < -1.0);
      QVERIFY(std::abs(left - predicted) < 0.02);
      QVERIFY(std::abs(a.fixations[i].final_focus_error_d[0]) < 0.1);
      QVERIFY(!b.fixations[i].time_to_tolerance_s.has_value());  // the worse eye never gets there
      ++near;
    }
    QCOMPARE(near, 2);
  }

  void emptyFixationsRefused() {
    bool threw = false;
    try {
      runBinocularLoop(scene_, {}, synthetic("DDSM50"));
    } catch (const std::invalid_argument&) {
      threw = true;
    }
    QVERIFY(threw);
  }
};

QTEST_GUILESS_MAIN(TestBinocularLoop)

}  // namespace tst_binocular_loop
#include "tst_binocular_loop.moc"
