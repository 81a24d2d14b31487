// The seed's definitions beside ours (supplement A.3, A.4, C.2): the centre-FOV eye-box
// criterion, the point source moved along its own axis (z_s) and the FOV measured as the lit
// footprint seen from the pupil. Closed-form checks on a toy FOV model, exact geometry for the
// axial move, and physics checks on traced scenes (limits, symmetry of a symmetric bench).
#include <QtTest>

#include <cmath>
#include <numbers>

#include "app/embedded_scene.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/trace_evaluator.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"

namespace tst_seed_definitions {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;

// The prototype with its projector on the bench axis behind the eye, aimed at the HOE centre
// and recorded from there: mirror-symmetric about the y-z plane.
Scene symmetricBench() {
  Scene s = embeddedDefaultScene();
  s.projector.pose.position_mm = {0.0, 0.0, -70.0};
  s.projector.pose.rotation_deg = {0.0, 0.0, 0.0};
  for (HoeLayer& l : s.hoe_layers) l.recording.reference_point_mm = {0.0, 0.0, -70.0};
  return s;
}

FovEvaluator traced(FovAngle angle = FovAngle::Arrival) {
  TraceEvaluatorOptions o;
  o.fov_method = FovMethod::Edges;
  o.wavelength_nm = 532.0;
  o.fov_angle = angle;
  return traceEvaluator(o);
}

// Toy: the FOV is 90 deg while the Maxwellian focus (at the HOE shift) is within 1 mm of the
// pupil, then falls by 15 deg per mm; the HOE's Bragg edge takes 20 deg per mm beyond 4.5 mm.
FovSample toy(const Scene& scene, const FovQuery& q) {
  const double pupil = placeEye(scene, q.gaze_deg[0], q.gaze_deg[1]).pupil_center.x();
  const double s = q.hoe_shift_mm[0];
  FovSample f;
  f.horizontal_deg = 90.0 - 15.0 * std::max(0.0, std::abs(pupil - s) - 1.0) - 20.0 * std::max(0.0, std::abs(s) - 4.5);
  f.vertical_deg = 78.0;
  return f;
}
}  // namespace

class TestSeedDefinitions : public QObject {
  Q_OBJECT
 private slots:
  void centreFovCriterionIsToleranceZero() {
    // On the toy the optimised FOV stays 90 deg while the plateau middle keeps the focus
    // within 1 mm of the pupil, then falls: the centre-FOV box is where it is still 90
    // (less the 0.01 deg slack), found here by brute force over the gaze.
    const Scene scene = embeddedDefaultScene();
    GazeStudyOptions centre;
    centre.criterion = EyeBoxCriterion::CentreFov;
    const auto c = sweepGaze(scene, toy, -40, 40, 5, GazeAxis::Yaw, ShiftMethod::Hoe, centre);
    const auto t = sweepGaze(scene, toy, -40, 40, 5, GazeAxis::Yaw, ShiftMethod::Hoe);
    QVERIFY(c.ok() && t.ok());
    const EyeBox &bc = c.value->eyebox, &bt = t.value->eyebox;
    QVERIFY(bc.lower_bounded && bc.upper_bounded);
    QCOMPARE(bc.reference_fov_deg, 90.0);
    // Brute force of the same definition: the largest gaze whose optimised FOV >= 90 - 0.01.
    double g = 0;
    while (optimiseShift(scene, toy, g + 0.05, GazeAxis::Yaw, ShiftMethod::Hoe).fov.horizontal_deg >=
           90.0 - kCentreFovSlackDeg)
      g += 0.05;
    const double p_hi = placeEye(scene, g, 0).pupil_center.x();
    QVERIFY2(std::abs(bc.pupil_range_mm[1] - p_hi) < 0.1,
             qPrintable(QString("%1 vs %2").arg(bc.pupil_range_mm[1]).arg(p_hi)));
    // The toy is symmetric: so is the box; and a 3 deg tolerance can only widen it.
    QVERIFY(std::abs(bc.pupil_range_mm[0] + bc.pupil_range_mm[1]) < 0.1);
    QVERIFY2(bt.width_mm > bc.width_mm + 0.2, qPrintable(QString("%1 vs %2").arg(bt.width_mm).arg(bc.width_mm)));
    // Inside the centre-FOV box every sample keeps the centre FOV.
    for (const auto& s : c.value->samples)
      if (s.gaze_deg >= bc.gaze_range_deg[0] && s.gaze_deg <= bc.gaze_range_deg[1])
        QVERIFY(s.fov.horizontal_deg >= 90.0 - kCentreFovSlackDeg);
    QCOMPARE(eyeBoxThresholdDeg(90.0, centre), 90.0 - kCentreFovSlackDeg);
  }

  void axialSourceMoveKeepsTheAimAndTheRecording() {
    const Scene s = embeddedDefaultScene();
    const Scene moved = withSourceAlongAxis(s, 5.0);
    // The prototype's projector is aimed at the HOE centre (the origin): moving 5 mm along its
    // axis brings it 5 mm closer, on the same line; its pose angles and the recorded
    // reference points stay.
    const double d0 = toVec(s.projector.pose.position_mm).norm(), d1 = toVec(moved.projector.pose.position_mm).norm();
    QVERIFY2(std::abs(d0 - d1 - 5.0) < 1e-9, qPrintable(QString("%1 -> %2").arg(d0).arg(d1)));
    QVERIFY(toVec(moved.projector.pose.position_mm)
                .normalized()
                .isApprox(toVec(s.projector.pose.position_mm).normalized(), 1e-12));
    QCOMPARE(moved.projector.pose.rotation_deg, s.projector.pose.rotation_deg);
    for (std::size_t i = 0; i < s.hoe_layers.size(); ++i)
      QCOMPARE(moved.hoe_layers[i].recording.reference_point_mm, s.hoe_layers[i].recording.reference_point_mm);
    // The query carries it: zero shift is the nominal scene, a shift is the moved one.
    const FovEvaluator eval = traced();
    const FovQuery q = gazeQuery(0.0, GazeAxis::Yaw, ShiftMethod::SourceAxial, 3.0);
    QCOMPARE(q.source_axial_shift_mm, 3.0);
    QCOMPARE(q.source_shift_mm, 0.0);
    QCOMPARE(eval(s, q).horizontal_deg, eval(withSourceAlongAxis(s, 3.0), FovQuery{}).horizontal_deg);
  }

  void footprintFovIsBoundByTheHoeSubtense() {
    // At zero gaze with the focus on the pupil centre the lit footprint seen from the pupil
    // and the arrival directions span the same field (every lit ray passes near the focus),
    // and neither can exceed what the 44 mm plate subtends at the pupil (2 atan(22/22) = 90).
    const Scene s = embeddedDefaultScene();
    const FovSample ours = traced(FovAngle::Arrival)(s, FovQuery{});
    const FovSample seed = traced(FovAngle::Footprint)(s, FovQuery{});
    const double subtense = 2.0 * std::atan(0.5 * s.hoe.size_mm[0] / s.eye.relief_mm) * 180.0 / std::numbers::pi;
    QVERIFY2(seed.horizontal_deg <= subtense + 1e-6 && seed.horizontal_deg > 80.0,
             qPrintable(QString::number(seed.horizontal_deg)));
    QVERIFY2(std::abs(seed.horizontal_deg - ours.horizontal_deg) < 1.0,
             qPrintable(QString("seed %1, ours %2").arg(seed.horizontal_deg).arg(ours.horizontal_deg)));
    // Off the focus (HOE moved 1.5 mm) the rays still enter the 5 mm pupil but not through its
    // centre: the two definitions part, but only at second order (the offsets at both plate
    // edges tilt both ends of the span the same way): 89.62 vs 89.87 deg on the prototype.
    FovQuery off;
    off.hoe_shift_mm = {1.5, 0.0};
    const double a = traced(FovAngle::Arrival)(s, off).horizontal_deg;
    const double b = traced(FovAngle::Footprint)(s, off).horizontal_deg;
    // docs/seed-reproduction.md: "by 0.25 deg with the HOE 1.5 mm off", at its printed digits.
    QVERIFY2(std::abs(a - 89.62) <= 0.005 && std::abs(b - 89.87) <= 0.005 && std::abs(std::abs(a - b) - 0.25) <= 0.005,
             qPrintable(QString("arrival %1, footprint %2").arg(a, 0, 'f', 4).arg(b, 0, 'f', 4)));
  }

  void symmetricBenchGivesSymmetricAxialSourceStudy() {
    // Mirror symmetry: FOV(-a) = FOV(a), z_s(-a) = z_s(a) and the eye box symmetric about zero.
    const Scene s = symmetricBench();
    GazeStudyOptions o;
    o.border_bisections = 4;
    const auto r = sweepGaze(s, traced(), -10, 10, 10, GazeAxis::Yaw, ShiftMethod::SourceAxial, o);
    QVERIFY(r.ok());
    const auto& v = r.value->samples;
    QCOMPARE(v.size(), std::size_t{3});
    QVERIFY2(std::abs(v[0].fov.horizontal_deg - v[2].fov.horizontal_deg) < 0.05,
             qPrintable(QString("%1 vs %2").arg(v[0].fov.horizontal_deg).arg(v[2].fov.horizontal_deg)));
    QVERIFY2(std::abs(v[0].shift_mm - v[2].shift_mm) < 0.05,
             qPrintable(QString("%1 vs %2").arg(v[0].shift_mm).arg(v[2].shift_mm)));
    const EyeBox& eb = r.value->eyebox;
    QVERIFY2(std::abs(eb.gaze_range_deg[0] + eb.gaze_range_deg[1]) < 0.7,
             qPrintable(QString("%1 .. %2").arg(eb.gaze_range_deg[0]).arg(eb.gaze_range_deg[1])));
  }

  void footprintNeedsTheEdgesEstimator() {
    TraceEvaluatorOptions o;
    o.fov_method = FovMethod::Dense;
    o.fov_angle = FovAngle::Footprint;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, traceEvaluator(o));
    QCOMPARE(parseFovDefinition("seed").value(), FovAngle::Footprint);
    QCOMPARE(std::string(fovDefinitionName(FovAngle::Arrival)), std::string("ours"));
    QVERIFY(!parseFovDefinition("zemax"));
  }
};

QTEST_APPLESS_MAIN(TestSeedDefinitions)

}  // namespace tst_seed_definitions
#include "tst_seed_definitions.moc"
