// The binocular closed loop with focus (devices/bench/binocular_loop.h), with the synthetic
// tracker (true gaze + Gaussian noise, no rendering): the left and right eyes are mirror
// images (to 1e-12), a direct-drive focus stage meets 0.25 D within 300 ms over 30-250 cm and
// the prototype's screw stage does not, and the vergence noise matches the closed form.
#include <QtTest>
#include "tests/prototype_scene.h"
#include "tests/test_paths.h"

#include <cmath>

#include "devices/bench/binocular_loop.h"
#include "model/scene/scene_io.h"

namespace tst_binocular_loop {

using namespace fovea;
using namespace fovea::devices;

namespace {
using fovea::testing::prototype;
BinocularOptions synthetic(const char* stage) {
  BinocularOptions o;
  o.track = false;
  o.loop.camera_fps = 120;
  o.loop.stage_model = stage;
  return o;
}
std::vector<BinocularFixation> depthSteps() {
  // 30 <-> 250 cm, in several directions, and a symmetric one.
  return {{300, {10, 5}, 1.0}, {2500, {-8, -4}, 1.0}, {300, {-12, 0}, 1.0}, {2500, {12, 6}, 1.0}, {800, {0, 0}, 1.0}};
}
}  // namespace

class TestBinocularLoop : public QObject {
  Q_OBJECT
  Scene scene_ = prototype();

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
