// fovea-cli grating: the JSON contract (docs/physics.md), batch mode and exit codes.
#include <QtTest>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"

namespace tst_cli_grating {

namespace {
using Run = fovea::testing::CliOutput;
Run runCli(const QStringList& args, const QByteArray& stdin_data = {}) {
  return fovea::testing::runFoveaCli(args, 60000, stdin_data);
}
QStringList reflectionArgs() {
  // Unslanted reflection grating at normal incidence, on Bragg: Lambda = lambda / (2 n0).
  return {"grating",           "--n0",        "1.5", "--n1",        "0.02", "--thickness-um",  "16",  "--period-nm",
          "177.3333333333333", "--slant-deg", "0",   "--probe-deg", "0",    "--wavelength-nm", "532", "--json"};
}
}  // namespace

class TestCliGrating : public QObject {
  Q_OBJECT
 private slots:
  void singleShotJsonContract() {
    const Run r = runCli(reflectionArgs());
    QCOMPARE(r.code, 0);
    const auto j = nlohmann::json::parse(r.out.toStdString());
    for (const char* key : {"efficiency", "type", "nu", "xi", "diffracted_deg"}) QVERIFY2(j.contains(key), key);
    QCOMPARE(j["type"].get<std::string>(), std::string("reflection"));
    const double nu = std::numbers::pi * 0.02 * 16 / 0.532;
    QVERIFY(std::abs(j["nu"].get<double>() - nu) < 1e-9);
    QVERIFY(j["xi"].get<double>() < 1e-9);
    QVERIFY(std::abs(j["efficiency"].get<double>() - std::pow(std::tanh(nu), 2)) < 1e-9);
    QVERIFY(std::abs(j["diffracted_deg"].get<double>() - 180.0) < 1e-6);
  }

  void transmissionAndEvanescentOrder() {
    // Unslanted transmission grating on Bragg: diffracted at -theta; p polarisation accepted.
    Run r = runCli({"grating", "--n0", "1.5", "--n1", "0.01", "--thickness-um", "26.17841251990", "--period-nm", "1000",
                    "--slant-deg", "90", "--probe-deg", "10.214472381521484", "--wavelength-nm", "532",
                    "--polarization", "s", "--json"});
    QCOMPARE(r.code, 0);
    auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["type"].get<std::string>(), std::string("transmission"));
    QVERIFY(std::abs(j["efficiency"].get<double>() - 1.0) < 1e-9);
    QVERIFY(std::abs(j["diffracted_deg"].get<double>() + 10.214472381521484) < 1e-6);
    // Period far below lambda / (2 n0) with an unslanted transmission grating: the order is evanescent.
    r = runCli({"grating", "--n0", "1.5", "--n1", "0.01", "--thickness-um", "10", "--period-nm", "100", "--slant-deg",
                "90", "--probe-deg", "0", "--wavelength-nm", "532", "--polarization", "p", "--json"});
    QCOMPARE(r.code, 0);
    j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(j["diffracted_deg"].is_null());
    QCOMPARE(j["efficiency"].get<double>(), 0.0);
  }

  void invalidArgumentsExitTwoNamingTheArgument() {
    const struct {
      const char* flag;
      const char* value;
      const char* named;
    } cases[] = {{"--thickness-um", "-1", "--thickness-um"},
                 {"--n1", "1.5", "--n1"},
                 {"--n1", "2", "--n1"},
                 {"--period-nm", "nan", "--period-nm"},
                 {"--wavelength-nm", "0", "--wavelength-nm"},
                 {"--probe-deg", "95", "--probe-deg"},
                 {"--polarization", "q", "--polarization"},
                 {"--model", "nosuch", "--model"}};
    for (const auto& c : cases) {
      QStringList args = reflectionArgs();
      const int at = static_cast<int>(args.indexOf(c.flag));
      if (at >= 0)
        args[at + 1] = c.value;
      else
        args << c.flag << c.value;
      const Run r = runCli(args);
      QVERIFY2(r.code == 2, qPrintable(QString("%1 %2 -> %3").arg(c.flag, c.value).arg(r.code)));
      QVERIFY2(r.err.contains(c.named), r.err.constData());
    }
    QStringList missing = reflectionArgs();
    missing.removeAt(missing.indexOf("--n0") + 1);
    missing.removeAt(missing.indexOf("--n0"));
    const Run r = runCli(missing);
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("--n0"));
  }

  void batchFromStdinKeepsOrderAndReportsBadLines() {
    const QByteArray in =
        R"({"n0":1.5,"n1":0.02,"thickness_um":16,"period_nm":177.3333333333333,"slant_deg":0,"probe_deg":0,"wavelength_nm":532,"polarization":"s"}
{"n0":1.5,"n1":1.6,"thickness_um":16,"period_nm":177,"slant_deg":0,"probe_deg":0,"wavelength_nm":532}
this is not json

{"n0":1.5,"n1":0.02,"thickness_um":32,"period_nm":177.3333333333333,"slant_deg":0,"probe_deg":0,"wavelength_nm":532,"polarization":"p"}
{"n0":1.5,"n1":0.02,"thickness_um":16,"period_nm":177,"slant_deg":0,"probe_deg":0,"wavelength_nm":532,"polarization":"z"}
)";
    const Run r = runCli({"grating", "--batch", "-"}, in);
    QCOMPARE(r.code, 1);  // some lines failed; every line still has its answer
    QVERIFY2(r.err.contains("--batch: 4 of 6 line(s) failed"), r.err.constData());
    const QList<QByteArray> lines = r.out.trimmed().split('\n');
    QCOMPARE(lines.size(), 6);  // the blank line answers too
    const auto l0 = nlohmann::json::parse(lines[0].toStdString());
    const auto l1 = nlohmann::json::parse(lines[1].toStdString());
    const auto l2 = nlohmann::json::parse(lines[2].toStdString());
    const auto blank = nlohmann::json::parse(lines[3].toStdString());
    QCOMPARE(QString::fromStdString(blank["error"].get<std::string>()),
             QString("line 4: blank line (expected a JSON object)"));
    QCOMPARE(blank["line"].get<int>(), 4);
    const auto l3 = nlohmann::json::parse(lines[4].toStdString());
    const auto l4 = nlohmann::json::parse(lines[5].toStdString());
    const double nu = std::numbers::pi * 0.02 * 16 / 0.532;
    QVERIFY(std::abs(l0["efficiency"].get<double>() - std::pow(std::tanh(nu), 2)) < 1e-9);
    QVERIFY(l1.contains("error") && l1["error"].get<std::string>().find("n1") != std::string::npos);
    QVERIFY(l2.contains("error") &&
            l2["error"].get<std::string>().rfind(
                "line 3: malformed JSON at column 2: syntax error while parsing value - invalid literal", 0) == 0);
    // p at normal incidence: rho_hat . sigma_hat = -1, same as s.
    QVERIFY(std::abs(l3["efficiency"].get<double>() - std::pow(std::tanh(2 * nu), 2)) < 1e-9);
    QVERIFY(l4.contains("error") && l4["error"].get<std::string>().find("polarization") != std::string::npos);
  }

  void batchFromFile() {
    const QString dir = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp");
    const QString path = dir + "/grating_batch.jsonl";
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    for (int i = 0; i < 3; ++i)
      f.write(
          QString(
              R"({"n0":1.5,"n1":0.01,"thickness_um":%1,"period_nm":1000,"slant_deg":90,"probe_deg":10.214472381521484,"wavelength_nm":532})"
              "\n")
              .arg(10 * (i + 1))
              .toUtf8());
    f.close();
    const Run r = runCli({"grating", "--batch", path});
    QCOMPARE(r.code, 0);
    const QList<QByteArray> lines = r.out.trimmed().split('\n');
    QCOMPARE(lines.size(), 3);
    for (int i = 0; i < 3; ++i) {
      const auto j = nlohmann::json::parse(lines[i].toStdString());
      const double nu =
          std::numbers::pi * 0.01 * 10 * (i + 1) / (0.532 * std::cos(10.214472381521484 * std::numbers::pi / 180));
      QVERIFY(std::abs(j["efficiency"].get<double>() - std::pow(std::sin(nu), 2)) < 1e-9);
    }
    QCOMPARE(runCli({"grating", "--batch", dir + "/does-not-exist.jsonl"}).code, 1);
  }
};

QTEST_GUILESS_MAIN(TestCliGrating)

}  // namespace tst_cli_grating
#include "tst_cli_grating.moc"
