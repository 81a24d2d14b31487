// Fitting a scene to target observables (model/analysis/fit_*.h): the targets format and its
// refusals, the free-parameter spelling, the covariance against the closed form of a linear
// model, and the synthetic recovery of the issue's "Done when": perturb the prototype in a few
// parameters, compute the targets with our own forward model, fit from the unperturbed scene,
// every parameter back within its reported uncertainty.
#include <QtTest>

#include <chrono>
#include <cmath>

#include <Eigen/LU>

#include "app/embedded_scene.h"
#include "model/analysis/fit_json.h"
#include "model/analysis/fit_parameters.h"
#include "model/analysis/fit_solver.h"
#include "model/analysis/fit_targets.h"
#include "model/analysis/fit_uncertainty.h"
#include "model/scene/scene_io.h"
#include "model/scene/scene_parameters.h"

namespace tst_fit {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;

template <class F>
QString refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

FitTarget target(const std::string& id, const std::string& observable, nlohmann::json params, double sigma) {
  nlohmann::json j = params;
  j["id"] = id;
  j["observable"] = observable;
  j["value"] = 0.0;
  j["sigma"] = sigma;
  return parseFitTargets(nlohmann::json::array({j})).front();
}
}  // namespace

class TestFit : public QObject {
  Q_OBJECT
 private slots:
  void targetsFormat() {
    const nlohmann::json file = nlohmann::json::parse(R"js({
      "format": "fovea-fit-targets", "version": 1, "notes": "two targets",
      "targets": [
        {"id": "fov", "observable": "fov_deg", "gaze_deg": 10, "direction": "vertical", "value": 78.0,
         "sigma": 0.5, "unit": "deg", "source": "seed A.3 (measured)"},
        {"id": "xp", "observable": "x_p_mm", "gaze_deg": -20, "value": -3.44, "sigma": 0.1, "source": "seed A.4"}
      ]})js");
    const std::vector<FitTarget> t = parseFitTargets(file);
    QCOMPARE(t.size(), std::size_t(2));
    QCOMPARE(t[0].parameters["direction"].get<std::string>(), std::string("vertical"));
    QCOMPARE(t[0].parameters["shift"].get<std::string>(), std::string("optimal"));  // default filled in
    QCOMPARE(t[1].unit, std::string("mm"));                                         // the observable's
    QCOMPARE(t[1].parameters["gaze_deg"].get<double>(), -20.0);
    // The file form reads back to the same targets.
    const std::vector<FitTarget> back = parseFitTargets(fitTargetsJson(t, "again"));
    QCOMPARE(back[1].parameters, t[1].parameters);
    QCOMPARE(back[0].source, t[0].source);
    // A bare list is a targets file too.
    QCOMPARE(parseFitTargets(file["targets"]).size(), std::size_t(2));

    auto refused = [&](const char* key, nlohmann::json v) {
      nlohmann::json f = file;
      if (v.is_null())
        f["targets"][0].erase(key);
      else
        f["targets"][0][key] = v;
      return refusal([&] { parseFitTargets(f); });
    };
    const QString unknown = refused("observable", "fov");
    QVERIFY2(unknown.contains("unknown observable \"fov\"") && unknown.contains("fov_deg, ") &&
                 unknown.contains("x_p_mm") && unknown.contains("cpd"),
             qPrintable(unknown));
    QVERIFY(refused("sigma", 0).contains("targets[0].sigma: must be in [1e-09, 1e+09], got 0"));
    QVERIFY(refused("sigma", 5e-324).contains("targets[0].sigma: must be in [1e-09, 1e+09], got 5e-324"));
    QVERIFY(refused("value", 1e308).contains("targets[0].value: must be in [-1e+09, 1e+09], got 1e+308"));
    QVERIFY(refused("sigma", nullptr).contains("missing \"sigma\""));
    QVERIFY(refused("unit", "mm").contains("\"unit\" of fov_deg is \"deg\""));
    QVERIFY(refused("direction", "sideways").contains("direction: must be one of horizontal, vertical, diagonal"));
    QVERIFY(refused("gaze", 3).contains("gaze: not a parameter of fov_deg"));
    QVERIFY(refused("gaze_deg", 95).contains("gaze_deg: must lie in [-80, 80] deg"));
    QVERIFY(refused("value", "90").contains("targets[0].value: must be a finite number"));
    nlohmann::json twice = file;
    twice["targets"][1]["id"] = "fov";
    QVERIFY(refusal([&] { parseFitTargets(twice); }).contains("duplicate id \"fov\""));
    QVERIFY(refusal([&] { parseFitTargets(nlohmann::json::array()); }).contains("empty"));
  }

  void observablesReadTheAnalyses() {
    const Scene s = embeddedDefaultScene();
    const std::vector<FitTarget> t{
        target("xp5", "x_p_mm", {{"gaze_deg", 10}, {"wavelength_nm", 532}}, 1),
        target("xp2", "x_p_mm", {{"gaze_deg", 10}, {"wavelength_nm", 532}, {"plateau_tolerance_deg", 2}}, 1),
        target("fov0", "fov_deg", {{"shift", "none"}, {"wavelength_nm", 532}, {"gaze_deg", 10}}, 1),
        target("fov1", "fov_deg", {{"shift", "fixed"}, {"shift_mm", 1.6}, {"wavelength_nm", 532}, {"gaze_deg", 10}}, 1),
        target("box", "eyebox_mm", {{"wavelength_nm", 532}, {"gaze_step", 20}}, 1),
        target("top", "gaze_coverage_deg", {{"wavelength_nm", 532}, {"gaze_step", 20}}, 1),
        target("bottom", "gaze_coverage_deg", {{"wavelength_nm", 532}, {"gaze_step", 20}, {"end", "lower"}}, 1),
        target("cpd", "cpd", {{"eccentricity_deg", 20}, {"kind", "peripheral"}}, 1),
        target("zs", "x_p_mm", {{"gaze_deg", 5}, {"method", "source"}, {"wavelength_nm", 532}}, 1),
        target("zs-axial", "x_p_mm", {{"gaze_deg", 5}, {"method", "source_axial"}, {"wavelength_nm", 532}}, 1)};
    ObservableSettings coarse;  // the study's tolerances as the analyses use them: cheaper than the fit's
    coarse.fov_tolerance_deg = 0.005;
    coarse.shift_bisections = 6;
    coarse.border_bisections = 6;
    const std::vector<double> v = evaluateTargets(s, t, coarse);
    QVERIFY(v[0] > 1.3 && v[0] < 2.0);     // x_p(10 deg) ~ 1.6 mm (docs/analyses.md)
    QVERIFY(v[0] != v[1]);                 // the plateau tolerance reaches the x_p search
    QVERIFY(std::abs(v[3] - v[2]) > 0.1);  // the fixed shift reaches the trace (90 vs 89.6 deg)
    QVERIFY2(v[4] > 8 && v[4] < 20, qPrintable(QString::number(v[4])));  // the HOE eye box, 8-20 mm
    QVERIFY(v[5] > 20 && v[6] < -20);                                    // its gaze borders (one sweep)
    QVERIFY(v[7] > 0);
    // The seed's axial source shift (along the projector's axis) is not the bench-z one.
    QVERIFY(std::isfinite(v[9]) && std::abs(v[9] - v[8]) > 1e-3);
    const FitTarget seed = target("box", "eyebox_mm", {{"criterion", "centre-fov"}, {"method", "source_axial"}}, 1);
    QCOMPARE(seed.parameters["criterion"].get<std::string>(), std::string("centre-fov"));
  }

  void freeParameterSpelling() {
    const Scene s = embeddedDefaultScene();
    const FreeParameter d = parseFreeParameter(s, "eye.relief_mm");
    QCOMPARE(d.initial, 22.0);
    QCOMPARE(d.lower, 17.0);  // +-5 mm default window
    QCOMPARE(d.upper, 27.0);
    QCOMPARE(d.unit, std::string("mm"));
    const FreeParameter a = parseFreeParameter(s, "projector.position_mm[0]=85:95");
    QCOMPARE(a.lower, 85.0);
    QCOMPARE(a.upper, 95.0);
    const FreeParameter w = parseFreeParameter(s, "hoe.rotation_deg[0]=+-2");
    QCOMPARE(w.lower, -2.0);
    QCOMPARE(w.upper, 2.0);
    const FreeParameter n1 = parseFreeParameter(s, "hoe_layers[1].n1");  // +-25 % of 0.015
    QVERIFY(std::abs(n1.lower - 0.01125) < 1e-12 && std::abs(n1.upper - 0.01875) < 1e-12);
    const FreeParameter shrink = parseFreeParameter(s, "hoe_layers[0].shrinkage_percent");  // 0: +-1
    QCOMPARE(shrink.upper, 1.0);
    QVERIFY(refusal([&] { parseFreeParameter(s, "projector.pixels[0]"); }).contains("integer field cannot be fitted"));
    QVERIFY(refusal([&] { parseFreeParameter(s, "eye.colour"); }).contains("eye.colour"));
    QVERIFY(refusal([&] { parseFreeParameter(s, "eye.relief_mm=30:40"); }).contains("outside the bounds"));
    QVERIFY(refusal([&] { parseFreeParameter(s, "eye.relief_mm=5:1"); }).contains("LO < HI"));
    QVERIFY(refusal([&] { parseFreeParameter(s, "eye.relief_mm=a:b"); }).contains("not a finite number"));
    QVERIFY(refusal([&] { parseFreeParameter(s, "hoe_layers[1].n1=-1:1"); }).contains("field's range"));
    QVERIFY(refusal([&] { parseFreeParameters(s, {"eye.relief_mm", "eye.relief_mm=20:24"}); }).contains("twice"));
  }

  void covarianceOfALinearModel() {
    // r = J p: (J^T J)^-1 exactly, whatever the windows the SVD scales by.
    UncertaintyInput in;
    in.jacobian.resize(3, 2);
    in.jacobian << 1, 0, 1, 1, 0, 2;
    in.at_bound = {false, false};
    const Eigen::MatrixXd jtj = in.jacobian.transpose() * in.jacobian;
    const Eigen::MatrixXd expected = jtj.inverse();
    for (const auto& w : {std::vector<double>{1, 1}, std::vector<double>{10, 0.1}}) {
      in.windows = w;
      const UncertaintyResult u = analyseUncertainty(in);
      QVERIFY((u.covariance - expected).cwiseAbs().maxCoeff() < 1e-12);
      QVERIFY(std::abs(*u.sigma[1] - std::sqrt(expected(1, 1))) < 1e-12);
      QVERIFY(std::abs(u.correlation(0, 1) - expected(0, 1) / std::sqrt(expected(0, 0) * expected(1, 1))) < 1e-12);
      QVERIFY(u.determined[0] && u.determined[1]);
    }
    // A parameter no target depends on: undetermined, no uncertainty, the other one unaffected.
    in.jacobian.col(1).setZero();
    in.windows = {1, 1};
    const UncertaintyResult z = analyseUncertainty(in);
    QVERIFY(!z.determined[1] && !z.sigma[1]);
    QVERIFY(z.warnings[1].find("undetermined") != std::string::npos);
    QVERIFY(z.determined[0] && std::abs(*z.sigma[0] - 1 / std::sqrt(2.0)) < 1e-12);
    QVERIFY(z.relative_singular_values[1] == 0.0);
  }

  void recoversPerturbedParameters() {
    // Perturb 4 parameters, compute 5 targets with our forward model (edge FOV, one laser per
    // target: cheap), fit from the prototype: each parameter back within its reported uncertainty.
    const Scene nominal = embeddedDefaultScene();
    const std::vector<std::pair<std::string, double>> truth{{"hoe.size_mm[1]", 35.2},
                                                            {"hoe_layers[1].n1", 0.0165},
                                                            {"hoe_layers[0].n1", 0.0138},
                                                            {"projector.pixel_beam.waist_fwhm_um", 690.0}};
    Scene built = nominal;
    for (const auto& [path, v] : truth) built = withParameter(built, path, v);
    std::vector<FitTarget> t{
        target("fov-h", "fov_deg", {{"shift", "none"}, {"wavelength_nm", 532}}, 0.05),
        target("fov-v", "fov_deg", {{"shift", "none"}, {"direction", "vertical"}, {"wavelength_nm", 532}}, 0.05),
        target("eff-green", "mean_efficiency", {{"shift", "none"}, {"wavelength_nm", 532}}, 0.002),
        target("eff-red", "mean_efficiency", {{"shift", "none"}, {"wavelength_nm", 660}}, 0.002),
        target("spot", "rms_spot_um", nlohmann::json::object(), 2.0)};
    const std::vector<double> measured = evaluateTargets(built, t);
    for (std::size_t i = 0; i < t.size(); ++i) t[i].value = measured[i];
    std::vector<std::string> specs;
    for (const auto& [path, v] : truth) specs.push_back(path);
    const std::vector<FreeParameter> free = parseFreeParameters(nominal, specs);
    FitOptions o;
    o.starts = 2;
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = fitScene(nominal, t, free, o);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    QVERIFY(r.ok());
    const FitResult& f = *r.value;
    qInfo("fit: %d evaluations in %.1f s, chi2 %.3g -> %.3g", f.evaluations, s, f.chi2_initial, f.chi2);
    QVERIFY(f.chi2_initial > 100);  // the perturbation is seen
    QVERIFY2(f.chi2 < 0.1, qPrintable(QString::number(f.chi2)));
    QCOMPARE(f.dof, 1);
    for (std::size_t j = 0; j < truth.size(); ++j) {
      const FitParameterResult& p = f.parameters[j];
      qInfo("%s: %.6g +- %.3g (true %.6g, start %.6g)", p.parameter.path.c_str(), p.fitted, *p.uncertainty,
            truth[j].second, p.parameter.initial);
      QVERIFY(p.determined && p.uncertainty && *p.uncertainty > 0);
      // The uncertainty is small against the perturbation (the targets do determine it) ...
      QVERIFY(*p.uncertainty < 0.2 * std::abs(truth[j].second - p.parameter.initial));
      // ... and the fit is back within it.
      QVERIFY2(std::abs(p.fitted - truth[j].second) < *p.uncertainty, p.parameter.path.c_str());
    }
    QVERIFY(f.warnings.empty());
    // docs/fitting.md prints chi2 3120 in 91 evaluations and the uncertainties +-0.031 mm, +-7e-5,
    // +-5e-5, +-2.5 um: held to those digits (the final chi2, ~3e-9, is rounding noise: not held).
    QCOMPARE(f.evaluations, 91);
    QVERIFY2(std::abs(f.chi2_initial - 3120) < 5, qPrintable(QString::number(f.chi2_initial)));
    const double printed[] = {0.031, 7e-5, 5e-5, 2.5}, half_digit[] = {5e-4, 5e-6, 5e-6, 0.05};
    for (std::size_t j = 0; j < truth.size(); ++j)
      QVERIFY2(std::abs(*f.parameters[j].uncertainty - printed[j]) < half_digit[j],
               qPrintable(QString::number(*f.parameters[j].uncertainty, 'g', 6)));
    QCOMPARE(parameterValue(f.fitted_scene, "hoe.size_mm[1]"), f.parameters[0].fitted);
    const nlohmann::json j = fitResultJson(f, o);
    QCOMPARE(j["parameters"].size(), std::size_t(4));
    QCOMPARE(j["targets"][4]["id"].get<std::string>(), std::string("spot"));
    QVERIFY(std::abs(j["correlation"][1][1].get<double>() - 1.0) < 1e-12);
  }

  void recoversTheEyeReliefFromXp() {
    // docs/fitting.md: the eye relief recovered from x_p(+-10 deg) beside the height, green n1
    // and waist (relief 22 -> 21.5 mm: chi2 2960 in 211 evaluations, relief back to
    // 21.500 +- 0.028 mm), and at 23 mm the same targets only to +-0.39 mm (past the kink of
    // x_p(relief) near 22.2 mm). Held at the printed digits.
    const Scene nominal = embeddedDefaultScene();
    const std::vector<FitTarget> shape{
        target("fov-h", "fov_deg", {{"shift", "none"}, {"wavelength_nm", 532}}, 0.05),
        target("fov-v", "fov_deg", {{"shift", "none"}, {"direction", "vertical"}, {"wavelength_nm", 532}}, 0.05),
        target("eff", "mean_efficiency", {{"shift", "none"}, {"wavelength_nm", 532}}, 0.002),
        target("spot", "rms_spot_um", nlohmann::json::object(), 2.0),
        target("xp+10", "x_p_mm", {{"gaze_deg", 10}, {"wavelength_nm", 532}}, 0.02),
        target("xp-10", "x_p_mm", {{"gaze_deg", -10}, {"wavelength_nm", 532}}, 0.02)};
    const auto fitRelief = [&](double relief) {
      const std::vector<std::pair<std::string, double>> truth{{"eye.relief_mm", relief},
                                                              {"hoe.size_mm[1]", 35.2},
                                                              {"hoe_layers[1].n1", 0.0165},
                                                              {"projector.pixel_beam.waist_fwhm_um", 690.0}};
      Scene built = nominal;
      for (const auto& [path, v] : truth) built = withParameter(built, path, v);
      std::vector<FitTarget> t = shape;
      const std::vector<double> measured = evaluateTargets(built, t);
      for (std::size_t i = 0; i < t.size(); ++i) t[i].value = measured[i];
      std::vector<std::string> specs;
      for (const auto& [path, v] : truth) specs.push_back(path);
      FitOptions o;
      o.starts = 2;
      const auto r = fitScene(nominal, t, parseFreeParameters(nominal, specs), o);
      if (!r.ok()) qFatal("the relief fit was cancelled");
      return *r.value;
    };
    const FitResult near = fitRelief(21.5);
    const FitParameterResult& relief = near.parameters[0];
    qInfo("21.5 mm: %d evaluations, chi2 %.6g -> %.3g, relief %.6f +- %.6f", near.evaluations, near.chi2_initial,
          near.chi2, relief.fitted, relief.uncertainty.value_or(-1));
    QCOMPARE(near.evaluations, 211);
    QVERIFY2(std::abs(near.chi2_initial - 2960) < 5, qPrintable(QString::number(near.chi2_initial)));
    QVERIFY2(near.chi2 < 1e-6, qPrintable(QString::number(near.chi2)));
    QVERIFY2(std::abs(relief.fitted - 21.5) < 5e-4, qPrintable(QString::number(relief.fitted, 'f', 6)));
    QVERIFY(relief.uncertainty && std::abs(*relief.uncertainty - 0.028) < 5e-4);
    const FitResult far = fitRelief(23.0);
    qInfo("23 mm: relief %.6f +- %.6f", far.parameters[0].fitted, far.parameters[0].uncertainty.value_or(-1));
    QVERIFY(far.parameters[0].uncertainty && std::abs(*far.parameters[0].uncertainty - 0.39) < 5e-3);
  }

  void warnsOfUndeterminedParameters() {
    // Efficiency on Bragg depends on n1 d only (tanh^2(pi n1 d / lambda), Kogelnik 1969): one
    // efficiency target cannot separate n1 from the thickness.
    const Scene nominal = embeddedDefaultScene();
    std::vector<FitTarget> t{target("eff", "mean_efficiency", {{"shift", "none"}, {"wavelength_nm", 532}}, 0.002)};
    t[0].value = evaluateTargets(withParameter(nominal, "hoe_layers[1].n1", 0.016), t)[0];
    FitOptions o;
    o.starts = 1;
    const auto r =
        fitScene(nominal, t, parseFreeParameters(nominal, {"hoe_layers[1].n1", "hoe_layers[1].thickness_um"}), o);
    QVERIFY(r.ok());
    QVERIFY(r.value->chi2 < 0.01);
    QVERIFY(!r.value->parameters[0].determined && !r.value->parameters[1].determined);
    QVERIFY(!r.value->parameters[0].uncertainty);
    int undetermined = 0;
    for (const auto& w : r.value->warnings) undetermined += w.message.find("undetermined") != std::string::npos;
    QCOMPARE(undetermined, 2);
  }

  void cancelled() {
    const Scene nominal = embeddedDefaultScene();
    std::vector<FitTarget> t{target("eff", "mean_efficiency", {{"shift", "none"}, {"wavelength_nm", 532}}, 0.002)};
    std::atomic<bool> stop{true};
    StudyControl c;
    c.cancel = &stop;
    QVERIFY(!fitScene(nominal, t, parseFreeParameters(nominal, {"hoe_layers[1].n1"}), {}, c).ok());
  }

  void refusesATargetWithoutValue() {
    const Scene nominal = embeddedDefaultScene();
    std::vector<FitTarget> t{target("cpd", "cpd", {{"eccentricity_deg", 79}, {"kind", "foveal"}}, 1.0)};
    try {
      fitScene(nominal, t, parseFreeParameters(nominal, {"eye.relief_mm"}));
      QFAIL("no error");
    } catch (const std::runtime_error& e) {
      QVERIFY2(QString(e.what()).contains("target \"cpd\" (cpd): no foveal resolution"), e.what());
    }
  }
};

QTEST_GUILESS_MAIN(TestFit)

}  // namespace tst_fit
#include "tst_fit.moc"
