// The studio's analysis forms and fovea-cli's options come from the one analysis registry:
// for every registered analysis the form's defaults equal the values fovea-cli parses from
// a bare command line; "Defaults" restores them; "Copy CLI" gives a command that parses
// back to the form's values, names the saved scene file, and is refused for an unsaved one;
// the studio refuses the same bad numbers with the same messages as the CLI.
#include <QtTest>
#include "tests/test_paths.h"

#include <QLineEdit>
#include <QPushButton>
#include <QToolButton>

#include <algorithm>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "tests/gui/analysis_panel_fixture.h"
#include "widgets/analyses/analyses_panel.h"
#include "widgets/preferences.h"
#include "widgets/scene_document.h"

namespace tst_analysis_defaults {

using namespace fovea;
using namespace fovea::widgets;
using fovea::embeddedDefaultScene;

namespace {

// Parses `args` (after the program name: the subcommand first) with the options fovea-cli
// generates for analysis `id`, and returns the validated values.
nlohmann::json cliValues(const std::string& id, std::vector<std::string> args) {
  CLI::App app;
  auto* cmd = app.add_subcommand(id);
  cmd->add_option("SCENE");
  cmd->add_flag("--json");
  const auto options = cli::addAnalysisOptions(cmd, id);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  return options->values();
}

// The form's values as the registry's (validated, defaults filled in).
nlohmann::json formValues(const AnalysisSpec& spec, const AnalysisParams& form) {
  nlohmann::json v = parameterValues(spec, form);
  const auto problems = analysis::validateValues(*spec.definition, v);
  if (!problems.empty()) qFatal("form values invalid: %s", problems.front().text().c_str());
  return v;
}

std::vector<std::string> words(const QString& command) {
  std::vector<std::string> out;
  for (const QString& w : command.split(' ', Qt::SkipEmptyParts)) out.push_back(w.toStdString());
  return out;
}

}  // namespace

class TestAnalysisDefaults : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() { Preferences::instance().setValues(PreferenceValues{}); }

  void formDefaultsEqualTheCliDefaults() {
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    AnalysesPanel panel(&doc);
    int generated = 0;
    for (const AnalysisSpec& spec : analysisCatalog()) {
      panel.selectAnalysis(spec.id);
      QCOMPARE(panel.currentAnalysis(), spec.id);
      const nlohmann::json studio = formValues(spec, panel.parameters());
      QCOMPARE(studio.size(), spec.definition->parameters.size());
      if (!spec.definition->cli_generated) continue;  // grating (hand-written twin), kogelnik-vs-rcwa
      ++generated;
      const nlohmann::json cli = cliValues(spec.id.toStdString(), {spec.id.toStdString()});
      QVERIFY2(cli == studio, qPrintable(spec.id + ": CLI " + QString::fromStdString(cli.dump()) + " vs studio " +
                                         QString::fromStdString(studio.dump())));
    }
    QCOMPARE(generated, 7);  // trace sweep compare-shift sensitivity resolution optimize-lens selectivity
  }

  // The drift this replaces: the studio's sweep used 1 deg and 1 500 rays, fovea-cli 3 deg
  // and 12 000, and "Defaults" kept 1 deg.
  void defaultsButtonRestoresTheSharedDefaults() {
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    AnalysesPanel panel(&doc);
    panel.selectAnalysis("sweep");
    QVERIFY(panel.setParameter("tolerance-deg", 1.0));
    QVERIFY(panel.setParameter("rays", 1500));
    QCOMPARE(panel.parameters()["tolerance-deg"].toDouble(), 1.0);
    panel.findChild<QPushButton*>("defaults")->click();
    const nlohmann::json cli = cliValues("sweep", {"sweep"});
    QCOMPARE(panel.parameters()["tolerance-deg"].toDouble(), cli["tolerance-deg"].get<double>());
    QCOMPARE(panel.parameters()["rays"].toInt(), cli["rays"].get<int>());
    QVERIFY(panel.parameters()["tolerance-deg"].toDouble() != 1.0);
  }

  void copyCliParsesBackToTheForm() {
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    AnalysesPanel panel(&doc);
    // Unsaved scene: no command with an empty path, a reason instead.
    panel.selectAnalysis("sweep");
    QVERIFY(panel.cliCommand().isEmpty());
    panel.findChild<QPushButton*>("copyCli")->click();
    QVERIFY2(panel.statusText().contains("Save the scene first"), qPrintable(panel.statusText()));
    const QString path = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/copy-cli-scene.json";
    doc.markSaved(path);
    for (const AnalysisSpec& spec : analysisCatalog()) {
      if (!spec.definition->cli_generated) continue;
      panel.selectAnalysis(spec.id);
      // A non-default value in every form, one of them in an option group where there is one.
      for (const AnalysisParameter& p : spec.parameters)
        if (p.kind == AnalysisParameter::Kind::Number && p.minimum > -1e9 && p.maximum < 1e9)
          panel.setParameter(p.key, p.minimum + 0.25 * (p.maximum - p.minimum));
      const QString command = panel.cliCommand();
      QVERIFY2(command.startsWith("fovea-cli " + spec.id + " " + path + " "), qPrintable(command));
      std::vector<std::string> args = words(command);
      args.erase(args.begin());  // "fovea-cli"
      const nlohmann::json parsed = cliValues(spec.id.toStdString(), args);
      const nlohmann::json form = formValues(spec, panel.parameters());
      QVERIFY2(parsed == form, qPrintable(command + "\nCLI " + QString::fromStdString(parsed.dump()) + "\nform " +
                                          QString::fromStdString(form.dump())));
    }
  }

  // A file parameter (the tolerance spec): a path field with a Browse button, empty meaning the
  // shipped default; a missing file refused by the one validator before any work; "Copy CLI"
  // writes --spec FILE and refuses (with the reason) while no file is chosen or a studio-only
  // override is set.
  void fileParameterIsValidatedAndCopied() {
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    AnalysesPanel panel(&doc);
    panel.selectAnalysis("tolerance");
    auto* field = panel.findChild<QLineEdit*>("spec");
    QVERIFY(field);
    QVERIFY(field->placeholderText().contains("prototype-tolerance.json"));
    QVERIFY(panel.findChild<QToolButton*>("spec-browse"));
    const AnalysisSpec& tol = *findAnalysis("tolerance");
    QCOMPARE(tol.parameters[0].kind, AnalysisParameter::Kind::FilePath);
    AnalysisParams p = panel.parameters();
    QVERIFY(validateParameters(tol, p).isEmpty());  // unset: the shipped spec
    p["spec"] = "/no/such/tolerance.json";
    QCOMPARE(validateParameters(tol, p), QStringList{"spec: no such file '/no/such/tolerance.json'"});
    p["spec"] = QString(FOVEA_SOURCE_DIR);
    QVERIFY(validateParameters(tol, p).front().contains("is not a regular file"));

    const QString scene = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/tolerance-scene.json";
    doc.markSaved(scene);
    QVERIFY(panel.cliCommand().isEmpty());
    panel.findChild<QPushButton*>("copyCli")->click();
    QVERIFY2(panel.statusText().contains("--spec"), qPrintable(panel.statusText()));
    const QString spec = QString(FOVEA_SOURCE_DIR) + "/resources/tolerance/prototype-tolerance.json";
    QVERIFY(panel.setParameter("spec", spec));
    QVERIFY(panel.setParameter("trials", 250));
    QCOMPARE(panel.cliCommand(), "fovea-cli tolerance " + scene + " --spec " + spec + " --trials 250 --seed 1 --json");
    QVERIFY(panel.setParameter("compensator", "fixed"));
    QVERIFY(panel.cliCommand().isEmpty());
    panel.findChild<QPushButton*>("copyCli")->click();
    QVERIFY2(panel.statusText().contains("studio only"), qPrintable(panel.statusText()));
    // The same message as a flag of the command line.
    nlohmann::json values = analysis::defaultValues(*tol.definition);
    values["spec"] = "/no/such/tolerance.json";
    QCOMPARE(analysis::validateValues(*tol.definition, values).front().text("--"),
             std::string("--spec: no such file '/no/such/tolerance.json'"));
  }

  void studioRefusesWhatTheCliRefuses() {
    const AnalysisSpec& sweep = *findAnalysis("sweep");
    AnalysisParams p = defaultParameters(sweep);
    p["tolerance-deg"] = std::nan("");
    QCOMPARE(validateParameters(sweep, p), QStringList{"tolerance-deg: must be a finite number, got nan"});
    p = defaultParameters(*findAnalysis("compare-shift"));
    p["gaze-step"] = 1e-9;
    const QStringList problems = validateParameters(*findAnalysis("compare-shift"), p);
    QCOMPARE(problems.size(), 1);
    QVERIFY2(problems.front().startsWith("gaze-step: more than 2000 gaze samples"), qPrintable(problems.front()));
    p = defaultParameters(*findAnalysis("trace"));
    p["gaze-yaw"] = 1000.0;
    QCOMPARE(validateParameters(*findAnalysis("trace"), p),
             QStringList{"gaze-yaw: must lie in [-80, 80] deg, got 1000"});
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, runAnalysis("trace", embeddedDefaultScene(), p));
  }
};

QTEST_MAIN(TestAnalysisDefaults)

}  // namespace tst_analysis_defaults
#include "tst_analysis_defaults.moc"
