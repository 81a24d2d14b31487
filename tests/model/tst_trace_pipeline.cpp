// The memoised trace pipeline (model/physics/trace_pipeline.h): which stages recompute after
// which edit, that culled and memoised results equal a fresh trace, and the evaluation counts.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>

#include "app/embedded_scene.h"
#include "model/analysis/trace_evaluator.h"
#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"
#include "model/physics/trace_reference.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"

namespace tst_trace_pipeline {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;

std::set<std::string> stageSet(const TraceStats& s) {
  return {s.stages_recomputed.begin(), s.stages_recomputed.end()};
}
std::string joined(const TraceStats& s) {
  std::string out;
  for (const auto& n : s.stages_recomputed) out += (out.empty() ? "" : " ") + n;
  return out;
}
bool anyStartsWith(const TraceStats& s, const std::string& prefix) {
  return std::any_of(s.stages_recomputed.begin(), s.stages_recomputed.end(),
                     [&](const std::string& n) { return n.rfind(prefix, 0) == 0; });
}
bool anyContains(const TraceStats& s, const std::string& part) {
  return std::any_of(s.stages_recomputed.begin(), s.stages_recomputed.end(),
                     [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

// Same numbers (bit for bit) in every field the CLI prints; "" when equal, else what differs.
std::string differences(const TraceResult& a, const TraceResult& b) {
  std::string d;
  const auto cmp = [&](const char* name, double x, double y) {
    if (!(x == y || (std::isnan(x) && std::isnan(y))))
      d += std::string(name) + " " + std::to_string(x) + " vs " + std::to_string(y) + "; ";
  };
  cmp("fov.h", a.fov_deg.horizontal, b.fov_deg.horizontal);
  cmp("fov.v", a.fov_deg.vertical, b.fov_deg.vertical);
  cmp("fov.d", a.fov_deg.diagonal, b.fov_deg.diagonal);
  cmp("rays", a.rays, b.rays);
  cmp("rays_in_pupil", a.rays_in_pupil, b.rays_in_pupil);
  cmp("rays_efficient", a.rays_efficient, b.rays_efficient);
  cmp("mean_efficiency", a.mean_efficiency, b.mean_efficiency);
  cmp("rays_on_hoe", a.rays_on_hoe, b.rays_on_hoe);
  cmp("mean_efficiency_on_hoe", a.mean_efficiency_on_hoe, b.mean_efficiency_on_hoe);
  cmp("uniformity", a.efficiency_uniformity, b.efficiency_uniformity);
  if (a.per_wavelength.size() != b.per_wavelength.size()) return d + "wavelength count";
  for (std::size_t w = 0; w < a.per_wavelength.size(); ++w) {
    const auto &x = a.per_wavelength[w], &y = b.per_wavelength[w];
    cmp("w.nm", x.wavelength_nm, y.wavelength_nm);
    cmp("w.fov.h", x.fov_deg.horizontal, y.fov_deg.horizontal);
    cmp("w.fov.v", x.fov_deg.vertical, y.fov_deg.vertical);
    cmp("w.fov.d", x.fov_deg.diagonal, y.fov_deg.diagonal);
    cmp("w.rays", x.rays, y.rays);
    cmp("w.in_pupil", x.rays_in_pupil, y.rays_in_pupil);
    cmp("w.efficient", x.rays_efficient, y.rays_efficient);
    cmp("w.mean", x.mean_efficiency, y.mean_efficiency);
  }
  return d;
}
#define COMPARE_RESULTS(a, b, what)                                                            \
  do {                                                                                         \
    const std::string diff_ = differences((a), (b));                                           \
    QVERIFY2(diff_.empty(), qPrintable(QString(what) + ": " + QString::fromStdString(diff_))); \
  } while (0)
}  // namespace

class TestTracePipeline : public QObject {
  Q_OBJECT
 private slots:
  void firstRunComputesEveryStage() {
    const Scene s = embeddedDefaultScene();
    TracePipeline p;
    TraceOptions o;
    o.rays = 2000;
    TraceStats st;
    const TraceResult r = p.run(s, o, &st);
    const std::set<std::string> got = stageSet(st);
    for (const char* layer : {"red", "green", "blue"}) {
      QVERIFY2(got.count(std::string("recording:") + layer), qPrintable(QString::fromStdString(joined(st))));
      for (const char* w : {"660nm", "532nm", "460nm"}) {
        QVERIFY(got.count(std::string("diffraction:") + layer + "@" + w));
        QVERIFY(got.count(std::string("coupled_wave:") + layer + "@" + w));
      }
    }
    for (const char* stage : {"geometry", "stack:660nm", "stack:532nm", "stack:460nm", "pupil", "fov", "analyses"})
      QVERIFY(got.count(stage));
    QCOMPARE(st.stages_recomputed.size(), std::size_t{1 + 3 + 9 + 9 + 3 + 3});
    // Rays outside the plate aperture never reach the coupled-wave step: one solve per ray on
    // the plate and layer.
    QCOMPARE(st.evaluations, static_cast<long long>(r.rays_on_hoe) * 3);
    QVERIFY(r.rays_on_hoe < r.rays);
    COMPARE_RESULTS(r, traceScene(s, o), "first run = fresh trace");
    // The same request again recomputes nothing.
    p.run(s, o, &st);
    QVERIFY2(st.stages_recomputed.empty(), qPrintable(QString::fromStdString(joined(st))));
    QCOMPARE(st.evaluations, 0LL);
  }

  void movingTheGazeNeverReRecords() {
    const Scene s = embeddedDefaultScene();
    TracePipeline p;
    TraceOptions o;
    o.rays = 2000;
    p.run(s, o);
    for (double yaw : {5.0, -12.0, 20.0, 0.5}) {
      o.gaze_deg = std::array<double, 2>{yaw, yaw / 4};
      TraceStats st;
      const TraceResult r = p.run(s, o, &st);
      QCOMPARE(stageSet(st), (std::set<std::string>{"pupil", "fov", "analyses"}));
      QCOMPARE(st.evaluations, 0LL);
      COMPARE_RESULTS(r, traceScene(s, o), "gaze update = fresh trace");
    }
    // A new threshold reruns the FOV only.
    o.efficiency_threshold = 0.5;
    TraceStats st;
    COMPARE_RESULTS(p.run(s, o, &st), traceScene(s, o), "threshold");
    QCOMPARE(stageSet(st), (std::set<std::string>{"fov"}));
  }

  void editingTheRedLayerLeavesGreenAndBlue() {
    Scene s = embeddedDefaultScene();
    QCOMPARE(s.hoe_layers[0].name, std::string("red"));
    TracePipeline p;
    TraceOptions o;
    o.rays = 2000;
    const TraceResult first = p.run(s, o);
    // Coupling only (n1): red's coupled wave at every wavelength, the stacks and what follows.
    s.hoe_layers[0].n1 *= 1.3;
    TraceStats st;
    TraceResult r = p.run(s, o, &st);
    QCOMPARE(stageSet(st),
             (std::set<std::string>{"coupled_wave:red@660nm", "coupled_wave:red@532nm", "coupled_wave:red@460nm",
                                    "stack:660nm", "stack:532nm", "stack:460nm", "pupil", "fov", "analyses"}));
    QCOMPARE(st.evaluations, static_cast<long long>(first.rays_on_hoe));  // one layer, every ray on the plate
    COMPARE_RESULTS(r, traceScene(s, o), "red n1 edit");
    // Recording geometry: red is re-recorded and re-diffracted; green and blue untouched.
    s.hoe_layers[0].recording.reference_point_mm[0] += 0.5;
    r = p.run(s, o, &st);
    QVERIFY(anyStartsWith(st, "recording:red"));
    QVERIFY(anyStartsWith(st, "diffraction:red@"));
    QVERIFY2(!anyContains(st, "green") && !anyContains(st, "blue"), qPrintable(QString::fromStdString(joined(st))));
    QVERIFY(!anyStartsWith(st, "geometry"));
    COMPARE_RESULTS(r, traceScene(s, o), "red recording edit");
    // Reverting the edit finds the earlier stages in the memo: nothing is solved again.
    s.hoe_layers[0].recording.reference_point_mm[0] -= 0.5;
    r = p.run(s, o, &st);
    QCOMPARE(st.evaluations, 0LL);
    QVERIFY(!anyStartsWith(st, "recording:"));
  }

  void wavelengthsNotAskedForAreNotEvaluated() {
    const Scene s = embeddedDefaultScene();
    TracePipeline p;
    TraceOptions o;
    o.rays = 2000;
    o.wavelength_nm = 532.0;
    TraceStats st;
    const TraceResult r = p.run(s, o, &st);
    QVERIFY(!anyContains(st, "660nm") && !anyContains(st, "460nm"));
    QCOMPARE(st.evaluations, static_cast<long long>(r.rays_on_hoe) * 3);  // three layers, one wavelength
    QCOMPARE(r.per_wavelength.size(), std::size_t{1});
    COMPARE_RESULTS(r, traceScene(s, o), "one wavelength");
    // Asking for all three later reuses the recordings and the 532 nm stages.
    o.wavelength_nm.reset();
    p.run(s, o, &st);
    QVERIFY(!anyStartsWith(st, "recording:") && !anyStartsWith(st, "geometry"));
    QVERIFY(!anyContains(st, "@532nm") && !anyContains(st, "stack:532nm"));
    QVERIFY(anyContains(st, "@660nm") && anyContains(st, "@460nm"));
  }

  void raysThatCannotReachThePupilAreCulled() {
    const Scene s = embeddedDefaultScene();
    TraceOptions full;
    full.rays = 3000;
    TraceOptions culled = full;
    culled.cull_to_pupil = true;
    // At 20 deg gaze without the HOE shift the Bragg-matched orders all miss the pupil: only the
    // few rays whose cross-talk orders (another layer, off Bragg) cross it are solved.
    TracePipeline p;
    full.gaze_deg = culled.gaze_deg = std::array<double, 2>{20.0, 0.0};
    TraceStats st;
    TraceResult r = p.run(s, culled, &st);
    QCOMPARE(r.rays_in_pupil, 0);
    QVERIFY(std::isnan(r.mean_efficiency_on_hoe));
    const TraceResult r20 = traceScene(s, full);
    QVERIFY2(st.evaluations < r20.rays_on_hoe * 3 / 10, qPrintable(QString::number(st.evaluations)));
    qInfo("cull at 20 deg gaze: %lld of %d ray-layer solves", st.evaluations, r20.rays_on_hoe * 3);
    // At 12 deg the pupil centre sits 2.4 mm from the recorded focus: part of the field enters
    // and only those rays are solved; the FOV, pupil counts and efficiencies equal the full
    // trace's.
    const Scene off = s;
    full.gaze_deg = culled.gaze_deg = std::array<double, 2>{12.0, 0.0};
    TracePipeline q;
    r = q.run(off, culled, &st);
    const TraceResult ref = traceScene(off, full);
    QVERIFY(r.rays_in_pupil > 0 && r.rays_in_pupil < ref.rays_on_hoe);
    QVERIFY(st.evaluations < static_cast<long long>(ref.rays_on_hoe) * 3);
    QVERIFY(st.evaluations >= static_cast<long long>(r.rays_in_pupil) * 3);
    TraceResult ref_no_hoe_mean = ref;
    ref_no_hoe_mean.mean_efficiency_on_hoe = r.mean_efficiency_on_hoe;
    COMPARE_RESULTS(r, ref_no_hoe_mean, "culled = full at the pupil");
    qInfo("cull: %lld of %d ray-layer solves (%d rays in the pupil)", st.evaluations, ref.rays_on_hoe * 3,
          r.rays_in_pupil);
    // Moving the gaze solves only rays that newly reach the pupil; results stay exact.
    long long total = st.evaluations;
    for (double yaw : {11.0, 10.0, 11.0}) {
      full.gaze_deg = culled.gaze_deg = std::array<double, 2>{yaw, 0.0};
      r = q.run(off, culled, &st);
      QVERIFY(!anyStartsWith(st, "recording:") && !anyStartsWith(st, "diffraction:"));
      total += st.evaluations;
      TraceResult f = traceScene(off, full);
      f.mean_efficiency_on_hoe = r.mean_efficiency_on_hoe;
      COMPARE_RESULTS(r, f, "culled gaze update");
    }
    QCOMPARE(st.evaluations, 0LL);  // back to 11 deg: everything it needs is memoised
    QVERIFY(total <= static_cast<long long>(ref.rays_on_hoe) * 3);
  }

  void shiftingThePlateNeverReRecords() {
    // The HOE is recorded once at its nominal pose and then translated rigidly on its stage:
    // the recording (fringes in plate-local coordinates) is reused for every shift, only its
    // sampling at the new hits reruns. Per ray, the cached recording must give what a
    // from-scratch trace gives (the plain loop of trace_reference.h), and the physics must be
    // that of a grating carried by the plate: a plate shifted by s is the nominal plate lit by
    // the projector moved by -s (same plate-local hits and directions; the eye does not enter
    // efficiencies and directions).
    const Scene s = embeddedDefaultScene();
    const Frame plate = frameOf(s.hoe.pose);
    TracePipeline p;
    TraceOptions o;
    o.rays = 1500;
    o.keep_rays = true;
    const TraceResult unshifted = p.run(s, o);
    double worst_reference = 0, worst_moved_projector = 0;
    int compared = 0;
    for (const std::array<double, 2> shift :
         {std::array<double, 2>{1.25, 0.0}, {-2.7, 0.0}, {0.4, -1.9}, {3.3, 2.2}, {0.0, 0.0}}) {
      o.hoe_shift_mm = shift;
      TraceStats st;
      const TraceResult r = p.run(s, o, &st);
      QVERIFY2(!anyStartsWith(st, "recording:"), qPrintable(QString::fromStdString(joined(st))));
      const auto ref = referenceTrace<double>(s, o);
      Scene moved = s;
      const Eigen::Vector3d delta = -(shift[0] * plate.x() + shift[1] * plate.y());
      for (int k = 0; k < 3; ++k) moved.projector.pose.position_mm[k] += delta[k];
      TraceOptions mo = o;
      mo.hoe_shift_mm = {0.0, 0.0};
      const TraceResult m = traceScene(moved, mo);
      QCOMPARE(r.ray_list.size(), ref.rays.size());
      QCOMPARE(r.ray_list.size(), m.ray_list.size());
      double moved_by_shift = 0;  // control: the shift does change the rays
      for (std::size_t i = 0; i < r.ray_list.size(); ++i) {
        const TracedRay &a = r.ray_list[i], &b = m.ray_list[i];
        QCOMPARE(a.hits_hoe, ref.rays[i].hits_hoe);
        QCOMPARE(a.hits_hoe, b.hits_hoe);
        if (!a.hits_hoe) continue;
        ++compared;
        if (unshifted.ray_list[i].hits_hoe)
          moved_by_shift = std::max(moved_by_shift, std::abs(a.efficiency - unshifted.ray_list[i].efficiency));
        worst_reference = std::max(worst_reference, std::abs(a.efficiency - ref.rays[i].efficiency));
        worst_moved_projector = std::max(worst_moved_projector, std::abs(a.efficiency - b.efficiency));
        QCOMPARE(a.exits, b.exits);
        if (a.exits) {
          worst_reference = std::max(worst_reference, (a.out_direction - ref.rays[i].out_direction).norm());
          worst_moved_projector = std::max(worst_moved_projector, (a.out_direction - b.out_direction).norm());
        }
      }
      QVERIFY(shift[0] == 0.0 && shift[1] == 0.0 ? moved_by_shift == 0.0 : moved_by_shift > 1e-3);
    }
    qInfo("%d ray hits: max |d eff|, |d dir| vs fresh reference %.2e, vs moved projector %.2e", compared,
          worst_reference, worst_moved_projector);
    QVERIFY(compared > 5000);
    QVERIFY2(worst_reference <= 1e-12, qPrintable(QString::number(worst_reference)));
    QVERIFY2(worst_moved_projector <= 1e-12, qPrintable(QString::number(worst_moved_projector)));
  }

  void randomEditSequenceMatchesFreshTraces() {
    // Memoisation must never change a result: a random walk of edits, each compared with a
    // fresh trace (and the culled pipeline with the full one at the pupil).
    Scene s = embeddedDefaultScene();
    TracePipeline p, pc;
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(-1, 1);
    TraceOptions o;
    o.rays = 800;
    for (int step = 0; step < 40; ++step) {
      switch (rng() % 8) {
        case 0:
          o.gaze_deg = std::array<double, 2>{15 * u(rng), 10 * u(rng)};
          break;
        case 1:
          o.hoe_shift_mm = {3 * u(rng), 2 * u(rng)};
          break;
        case 2:
          s.hoe_layers[rng() % 3].n1 = 0.02 + 0.01 * u(rng);
          break;
        case 3:
          s.hoe_layers[rng() % 3].recording.signal_point_mm[2] = -22 + 2 * u(rng);
          break;
        case 4:
          o.wavelength_nm = (rng() % 2) ? std::optional<double>(532.0 + 20 * u(rng)) : std::nullopt;
          break;
        case 5:
          o.efficiency_threshold = 0.1 + 0.09 * u(rng);
          break;
        case 6:
          s.eye.relief_mm = 22 + 3 * u(rng);
          break;
        case 7:
          o.source_shift_mm = 2 * u(rng);
          break;
      }
      const TraceResult fresh = traceScene(s, o);
      COMPARE_RESULTS(p.run(s, o), fresh, "memoised walk");
      TraceOptions oc = o;
      oc.cull_to_pupil = true;
      TraceResult fr = fresh;
      const TraceResult c = pc.run(s, oc);
      fr.mean_efficiency_on_hoe = c.mean_efficiency_on_hoe;
      COMPARE_RESULTS(c, fr, "culled walk");
    }
  }

  void coupledWaveMatchesTheScalarPath() {
    // The coupled-wave stage solves lossless films through the SIMD batch (kogelnik_batch.h);
    // per ray the stacked efficiency must equal the scalar closed forms of the plain loop
    // (trace_reference.h: diffractLayerT per layer) to 1e-12, for s, p and unpolarised light,
    // in reflection (the prototype), transmission (signal focus moved behind the plate), thick
    // over-modulated films (nu, xi >> 1: side lobes and the saturated reflection branch) and a
    // stack mixing an absorbing layer (scalar path) with lossless ones.
    const Scene proto = embeddedDefaultScene();
    Scene transmission = proto, thick = proto, absorbing = proto;
    for (HoeLayer& l : transmission.hoe_layers) l.recording.signal_point_mm[2] = 22.0;
    for (HoeLayer& l : thick.hoe_layers) {
      l.thickness_um = 400.0;
      l.n1 = 0.03;
    }
    absorbing.hoe_layers[1].absorption_per_mm = 2.0;
    const Frame plate = frameOf(proto.hoe.pose);
    struct Case {
      const char* name;
      const Scene* scene;
    };
    double worst = 0;
    int compared = 0, world_side = 0, strong = 0;
    for (const Case& c : {Case{"reflection", &proto}, Case{"transmission", &transmission}, Case{"thick", &thick},
                          Case{"absorbing", &absorbing}})
      for (const Polarization pol : {Polarization::S, Polarization::P, Polarization::Unpolarized}) {
        TraceOptions o;
        o.rays = 700;
        o.keep_rays = true;
        o.polarization = pol;
        const TraceResult r = TracePipeline().run(*c.scene, o);
        const auto ref = referenceTrace<double>(*c.scene, o);
        QCOMPARE(r.ray_list.size(), ref.rays.size());
        double case_worst = 0;
        for (std::size_t i = 0; i < r.ray_list.size(); ++i) {
          const TracedRay& a = r.ray_list[i];
          QCOMPARE(a.hits_hoe, ref.rays[i].hits_hoe);
          if (!a.hits_hoe) continue;
          ++compared;
          QCOMPARE(a.exits, ref.rays[i].exits);
          case_worst = std::max(case_worst, std::abs(a.efficiency - ref.rays[i].efficiency));
          if (a.exits && (plate.axes.transpose() * a.out_direction).z() > 0) ++world_side;
          if (a.nu > 3 && a.efficiency > 0.5) ++strong;
        }
        QVERIFY2(case_worst <= 1e-12,
                 qPrintable(QString("%1 pol %2: %3").arg(c.name).arg(static_cast<int>(pol)).arg(case_worst)));
        worst = std::max(worst, case_worst);
      }
    qInfo("%d ray hits: max |d eff| batch vs scalar %.2e; %d exit on the world side, %d with nu > 3", compared, worst,
          world_side, strong);
    QVERIFY(world_side > 1000);  // the transmission case is transmission
    QVERIFY(strong > 100);       // the thick case is over-modulated
  }

  void traceEvaluatorMatchesTheTracer() {
    const Scene s = embeddedDefaultScene();
    TraceEvaluatorOptions eo;
    eo.rays = 1200;
    const FovEvaluator eval = traceEvaluator(eo);
    for (double yaw : {0.0, 10.0, -15.0}) {
      FovQuery q;
      q.gaze_deg = {yaw, 0.0};
      q.hoe_shift_mm = {yaw * 0.17, 0.0};
      const FovSample f = eval(s, q);
      TraceOptions o;
      o.rays = 1200;
      o.gaze_deg = q.gaze_deg;
      o.hoe_shift_mm = q.hoe_shift_mm;
      const TraceResult r = traceScene(s, o);
      QCOMPARE(f.extent_horizontal_deg, r.fov_deg.horizontal);
      QCOMPARE(f.extent_vertical_deg, r.fov_deg.vertical);
      QCOMPARE(f.mean_efficiency, r.mean_efficiency);
      QCOMPARE(f.rays_in_pupil, r.rays_in_pupil);
      QCOMPARE(f.efficiency_uniformity, r.efficiency_uniformity);
    }
  }
};

QTEST_GUILESS_MAIN(TestTracePipeline)

}  // namespace tst_trace_pipeline
#include "tst_trace_pipeline.moc"
