// fovea-cli grating --model rcwa: the contract (Kogelnik's JSON plus total_efficiency and
// orders[{order, side, efficiency, angle_deg}], --orders N, --slices M, "model":"rcwa" in
// --batch lines), checked against independent closed forms (Kogelnik on Bragg for a thick weak
// grating, energy conservation when lossless, the unmodulated film) and against the error map
// of docs/benchmarks.md, rebuilt with the CLI alone from --error-map-requests.
#include <QtTest>
#include "tests/test_paths.h"

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"

namespace tst_cli_grating_rcwa {

namespace {
using fovea::testing::CliOutput;

CliOutput runCli(const QStringList& args, const QByteArray& stdin_data = {}) {
  return fovea::testing::runFoveaCli(args, 120000, stdin_data);
}

// Unslanted reflection grating, d = 20 µm, n1 = 0.01, on Bragg at normal incidence (the example
// of docs/benchmarks.md: Kogelnik 0.6852, RCWA 0.6850).
QStringList reflection(const QString& model) {
  return {"grating",
          "--model",
          model,
          "--n0",
          "1.5",
          "--n1",
          "0.01",
          "--thickness-um",
          "20",
          "--period-nm",
          "177.33333333333334",
          "--slant-deg",
          "0",
          "--probe-deg",
          "0",
          "--wavelength-nm",
          "532",
          "--json"};
}

std::vector<nlohmann::json> jsonLines(const QByteArray& out) {
  std::vector<nlohmann::json> v;
  for (const QByteArray& l : out.split('\n'))
    if (!l.isEmpty()) v.push_back(nlohmann::json::parse(l.toStdString()));
  return v;
}

// η Kogelnik and η RCWA of every point of docs/benchmarks/kogelnik_vs_rcwa.md's per-point table.
std::vector<std::pair<double, double>> documentedPoints() {
  std::ifstream in(std::string(FOVEA_SOURCE_DIR) + "/docs/benchmarks/kogelnik_vs_rcwa.md");
  std::vector<std::pair<double, double>> rows;
  std::string line;
  bool in_points = false;
  while (std::getline(in, line)) {
    if (line.rfind("| geometry |", 0) == 0) {
      in_points = true;
      continue;
    }
    if (!in_points || line.rfind("|---", 0) == 0 || line.rfind("| ", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(cell);
    // cells[0] is empty (before the first '|'): geometry = 1, η Kogelnik = 10, η RCWA = 11.
    if (cells.size() > 11) rows.emplace_back(std::stod(cells[10]), std::stod(cells[11]));
  }
  return rows;
}
}  // namespace

class TestCliGratingRcwa : public QObject {
  Q_OBJECT
 private slots:
  void contractKeysAndKogelnikOnBragg() {
    const CliOutput k = runCli(reflection("kogelnik"));
    const CliOutput r = runCli(reflection("rcwa"));
    QCOMPARE(k.code, 0);
    QVERIFY2(r.code == 0, r.err.constData());
    const auto kj = nlohmann::json::parse(k.out.toStdString());
    const auto rj = nlohmann::json::parse(r.out.toStdString());
    for (const auto& [key, v] : kj.items()) QVERIFY2(rj.contains(key), key.c_str());  // same JSON as Kogelnik …
    QCOMPARE(rj["model"].get<std::string>(), std::string("rcwa"));
    QCOMPARE(rj["type"].get<std::string>(), std::string("reflection"));
    QVERIFY(rj["total_efficiency"].is_number());  // … plus total_efficiency and orders
    QVERIFY(rj["orders"].is_array() && !rj["orders"].empty());
    for (const auto& o : rj["orders"]) {
      QVERIFY(o["order"].is_number_integer());
      QVERIFY(o["side"] == "reflected" || o["side"] == "transmitted");
      QVERIFY(o["efficiency"].is_number() && o["angle_deg"].is_number());
    }
    // Independent closed form: Kogelnik Eq. 56 on Bragg, eta = tanh^2(nu), nu = pi n1 d / lambda.
    const double nu = std::numbers::pi * 0.01 * 20 / 0.532;
    QVERIFY(std::abs(kj["efficiency"].get<double>() - std::pow(std::tanh(nu), 2)) < 1e-12);
    const double eta = rj["efficiency"].get<double>();
    QVERIFY2(std::abs(eta - std::pow(std::tanh(nu), 2)) < 1.5e-3, qPrintable(QString::number(eta)));  // the map's bound
    QCOMPARE(rj["kogelnik_efficiency"].get<double>(), kj["efficiency"].get<double>());
    // Lossless: the propagating orders carry all the power; zero order = 1 - eta here.
    QVERIFY(std::abs(rj["total_efficiency"].get<double>() - 1.0) < 1e-6);
    QVERIFY(std::abs(rj["zero_order"].get<double>() + eta - 1.0) < 1e-3);
  }

  void unmodulatedFilmDiffractsNothing() {
    QStringList args = reflection("rcwa");
    args[args.indexOf("--n1") + 1] = "0";
    const CliOutput r = runCli(args);
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(std::abs(j["efficiency"].get<double>()) < 1e-12);
    QVERIFY(std::abs(j["zero_order"].get<double>() - 1.0) < 1e-12);
  }

  void ordersAndSlicesFlags() {
    // Slanted transmission (K_x != 0: a 2-D problem; the unslanted reflection grating is a 1-D
    // stack that needs order 0 only).
    QStringList args{"grating", "--model",     "rcwa",  "--n0",        "1.5", "--n1",        "0.01", "--thickness-um",
                     "20",      "--period-nm", "276.1", "--slant-deg", "60",  "--probe-deg", "10",   "--wavelength-nm",
                     "532",     "--json"};
    args << "--orders"
         << "2"
         << "--slices"
         << "64";
    const CliOutput r = runCli(args);
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["rcwa"]["orders"].get<int>(), 2);
    QCOMPARE(j["rcwa"]["slices"].get<int>(), 64);
    QVERIFY(j["rcwa"]["converged"].get<bool>());
    QStringList kog = reflection("kogelnik");
    kog << "--orders"
        << "2";
    const CliOutput k = runCli(kog);
    QCOMPARE(k.code, 2);
    QVERIFY(k.err.contains("--orders: only the rcwa model has orders and slices"));
    QStringList bad = reflection("rcwa");
    bad << "--orders"
        << "401";
    const CliOutput b = runCli(bad);
    QCOMPARE(b.code, 2);
    QVERIFY2(b.err.contains("--orders: must be an integer in [0, 400] (got 401)"), b.err.constData());
  }

  void batchLinesChooseTheModel() {
    const QByteArray req =
        R"("n0":1.5,"n1":0.01,"thickness_um":20,"period_nm":177.33333333333334,"slant_deg":0,"probe_deg":0,"wavelength_nm":532)";
    const QByteArray in = "{" + req + R"(,"model":"rcwa"})" + "\n{" + req + "}\n{" + req +
                          R"(,"model":"rcwa","orders":1,"slices":32})" + "\n{" + req + R"(,"orders":1})" + "\n";
    const CliOutput r = runCli({"grating", "--batch", "-"}, in);
    QCOMPARE(r.code, 1);  // the last line asks Kogelnik for orders
    const auto lines = jsonLines(r.out);
    QCOMPARE(int(lines.size()), 4);
    QCOMPARE(lines[0]["model"].get<std::string>(), std::string("rcwa"));
    QVERIFY(lines[0].contains("orders") && lines[0].contains("total_efficiency"));
    QCOMPARE(lines[1]["model"].get<std::string>(), std::string("kogelnik"));
    QCOMPARE(lines[2]["rcwa"]["slices"].get<int>(), 32);
    QCOMPARE(QString::fromStdString(lines[3]["error"].get<std::string>()),
             QString("line 4: orders: only the rcwa model has orders and slices"));
    // --model rcwa is the default of lines without "model".
    const CliOutput d = runCli({"grating", "--batch", "-", "--model", "rcwa"}, "{" + req + "}\n");
    QCOMPARE(d.code, 0);
    QCOMPARE(jsonLines(d.out).at(0)["model"].get<std::string>(), std::string("rcwa"));
  }

  // docs/benchmarks.md's map from the CLI alone: the requests, then both models in --batch.
  // Every 4th point (60 of 240) keeps the test cheap; the documented commands run all of them.
  void errorMapReproducedFromTheCli() {
    const CliOutput req = runCli({"grating", "--error-map-requests"});
    QCOMPARE(req.code, 0);
    const QList<QByteArray> all = req.out.trimmed().split('\n');
    QCOMPARE(all.size(), 240);
    const auto documented = documentedPoints();
    QCOMPARE(int(documented.size()), 240);
    QByteArray subset;
    std::vector<int> index;
    for (int i = 0; i < all.size(); i += 4) {
      subset += all[i] + "\n";
      index.push_back(i);
    }
    const CliOutput k = runCli({"grating", "--batch", "-", "--model", "kogelnik"}, subset);
    const CliOutput r = runCli({"grating", "--batch", "-", "--model", "rcwa"}, subset);
    QVERIFY2(k.code == 0, k.err.constData());
    QVERIFY2(r.code == 0, r.err.constData());
    const auto kl = jsonLines(k.out), rl = jsonLines(r.out);
    QCOMPARE(kl.size(), index.size());
    QCOMPARE(rl.size(), index.size());
    double worst_k = 0, worst_r = 0;
    for (std::size_t n = 0; n < index.size(); ++n) {
      const auto [eta_k, eta_r] = documented[std::size_t(index[n])];
      // The table prints 4 decimals (rounding 5e-5); RCWA is converged to 1e-4 in both runs.
      worst_k = std::max(worst_k, std::abs(kl[n]["efficiency"].get<double>() - eta_k));
      worst_r = std::max(worst_r, std::abs(rl[n]["efficiency"].get<double>() - eta_r));
    }
    QVERIFY2(worst_k <= 5.1e-5, qPrintable(QString("Kogelnik vs table: %1").arg(worst_k)));
    QVERIFY2(worst_r <= 1.5e-4, qPrintable(QString("RCWA vs table: %1").arg(worst_r)));
    qInfo("CLI vs docs/benchmarks/kogelnik_vs_rcwa.md over %d points: Kogelnik %.2g, RCWA %.2g", int(index.size()),
          worst_k, worst_r);
  }
};

QTEST_GUILESS_MAIN(TestCliGratingRcwa)

}  // namespace tst_cli_grating_rcwa
#include "tst_cli_grating_rcwa.moc"
