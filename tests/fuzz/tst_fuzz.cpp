// Seeded fuzz harness: "bad input never crashes, never hangs and never lies".
//   1. scene mutations (in process): parseScene on mutated prototype texts (edge numbers, deep
//      nesting, invalid UTF-8, deleted/duplicated/inserted bytes, truncation) must not crash;
//      every message must be valid UTF-8 and bounded; an accepted scene must round-trip.
//   2. batch lines (fovea-cli grating --batch -): one output line per input line, each valid
//      JSON, an error naming its line or an answer with finite numbers and 0 <= eta <= 1.
//   3. argument sets (fovea-cli grating/validate/format with edge values and odd paths): exit
//      0, 1 or 2 within the time limit, no sanitizer report, JSON output valid.
//   4. the other input families (issue 28), in process: tolerance specs, tolerance parts (merge),
//      fit targets, colour CSVs and colour measurement files, images (PNG, JPEG bytes mutated):
//      no crash, every refusal a std::invalid_argument (or the image reader's error) naming
//      the file, never nlohmann's raw text; what is accepted is within its documented ranges.
//   5. capture manifests (fit-targets) and APT transcripts (stage --replay) mutated, through the
//      CLI: exit 0, 1 or 2, no sanitizer report.
//   6. one regression case per defect of issue 28, through the CLI: the exit code and the
//      message naming the file and the key.
// The CI run is small (seconds, run under ASan by the asan test preset: label "cli");
// FOVEA_FUZZ_SCALE=N multiplies every count (a long run on demand), FOVEA_FUZZ_SEED=S changes the
// seed (the default is fixed, so a CI failure reproduces).
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include "app/embedded_scene.h"
#include "model/analysis/fit_targets.h"
#include "model/analysis/tolerance_run.h"
#include "model/analysis/tolerance_spec.h"
#include "model/analysis/tolerance_stats.h"
#include "model/color/color_calibration.h"
#include "model/color/measurement_csv.h"
#include "model/image/image_io.h"
#include "model/io/json_input.h"
#include "model/scene/scene_io.h"
#include "tests/cli/cli_process.h"
#include "tests/test_files.h"
#include "tests/tolerance_test_spec.h"

namespace tst_fuzz {

using namespace fovea;
namespace fs = std::filesystem;

namespace {

long envLong(const char* name, long fallback) {
  bool ok = false;
  const long v = qEnvironmentVariable(name).toLong(&ok);
  return ok && v > 0 ? v : fallback;
}
const long kScale = envLong("FOVEA_FUZZ_SCALE", 1);
const unsigned kSeed = unsigned(envLong("FOVEA_FUZZ_SEED", 19));

fs::path tmpDir() {
  return fovea::testing::testTmpDir("fuzz");
}

const std::vector<std::string> kEdgeValues{"0",
                                           "-0",
                                           "1e-300",
                                           "-1e-300",
                                           "1e300",
                                           "-1e300",
                                           "1e999",
                                           "-1e999",
                                           "1.7976931348623157e308",
                                           "4.9e-324",
                                           "89.9999999999",
                                           "90",
                                           "-90",
                                           "180",
                                           "2147483648",
                                           "-2147483649",
                                           "1e18",
                                           "-1",
                                           "\"x\"",
                                           "\"\"",
                                           "null",
                                           "true",
                                           "[]",
                                           "{}",
                                           "[1,2]",
                                           "{\"a\":1}",
                                           "\"\xFF\"",
                                           "NaN"};

bool isValidUtf8Json(const std::string& s) {
  try {
    (void)nlohmann::json(s).dump();
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

class Mutator {
 public:
  explicit Mutator(unsigned seed) : rng_(seed) {}
  std::size_t below(std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }
  const std::string& edge() { return kEdgeValues[below(kEdgeValues.size())]; }

  std::string mutate(std::string t) {
    const int rounds = 1 + int(below(3));
    for (int r = 0; r < rounds && !t.empty(); ++r) {
      const std::size_t at = below(t.size());
      switch (below(8)) {
        case 0: {  // a number literal -> an edge value
          const std::size_t s = t.find_first_of("-0123456789", at);
          if (s == std::string::npos) break;
          const std::size_t e = t.find_first_not_of("-+.eE0123456789", s);
          t.replace(s, (e == std::string::npos ? t.size() : e) - s, edge());
          break;
        }
        case 1:
          t.erase(at, below(64) + 1);
          break;
        case 2: {  // random bytes, often not UTF-8
          std::string bytes;
          for (std::size_t i = below(8) + 1; i > 0; --i) bytes += char(below(256));
          t.insert(at, bytes);
          break;
        }
        case 3: {  // duplicate a line (duplicate keys)
          const std::size_t s = t.rfind('\n', at), e = t.find('\n', at);
          if (s != std::string::npos && e != std::string::npos) t.insert(e, t.substr(s, e - s));
          break;
        }
        case 4: {  // deep nesting as a value
          const std::size_t colon = t.find(':', at);
          if (colon == std::string::npos) break;
          const std::size_t depth = std::size_t(1) << (4 + below(12));  // 16 … 32768
          t.insert(colon + 1, std::string(depth, '[') + std::string(depth, ']') + ",\"z\":");
          break;
        }
        case 5:
          t.resize(at);
          break;
        case 6:
          t.insert(at, std::string(1, "{}[],:\"\\"[below(8)]));
          break;
        default: {  // a whole value -> an edge value
          const std::size_t colon = t.find(':', at);
          if (colon == std::string::npos) break;
          const std::size_t e = t.find_first_of(",\n}", colon + 1);
          if (e == std::string::npos) break;
          t.replace(colon + 1, e - colon - 1, edge());
        }
      }
    }
    return t;
  }

 private:
  std::mt19937_64 rng_;
};

const std::string kRequestKeys[] = {"n0",           "n1",        "thickness_um",  "period_nm",
                                    "slant_deg",    "probe_deg", "wavelength_nm", "absorption_per_mm",
                                    "polarization", "model"};

std::string requestLine(Mutator& m) {
  nlohmann::json j{{"n0", 1.5},      {"n1", 0.02},     {"thickness_um", 16},  {"period_nm", 177.3},
                   {"slant_deg", 0}, {"probe_deg", 0}, {"wavelength_nm", 532}};
  std::string line = j.dump();
  switch (m.below(10)) {
    case 0:
      return "";  // blank
    case 1:
      return m.mutate(line);  // byte-level garbage
    case 2:
      return line.substr(0, m.below(line.size()));  // truncated
    case 3:
      return "{\"n0\":" + std::string(m.below(5000) + 1, '[');  // deep, unterminated
    default: {                                                  // edge values in keys
      for (int k = int(m.below(3)) + 1; k > 0; --k) {
        const std::string& key = kRequestKeys[m.below(std::size(kRequestKeys))];
        const std::string value = key == "model" ? (m.below(2) ? "\"rcwa\"" : "\"nope\"") : m.edge();
        const std::string field = "\"" + key + "\":";
        const auto at = line.find(field);
        if (at == std::string::npos) {
          line.insert(line.size() - 1, "," + field + value);
        } else {
          const auto end = line.find_first_of(",}", at + field.size());
          line.replace(at + field.size(), end - at - field.size(), value);
        }
      }
      // RCWA lines get a small explicit discretisation: the fuzz tests the input path, not
      // the solver's convergence time.
      if (line.find("\"rcwa\"") != std::string::npos) line.insert(line.size() - 1, ",\"orders\":2,\"slices\":16");
      return line;
    }
  }
}

void checkNoSanitizerReport(const QByteArray& err, const QStringList& args) {
  const bool report = err.contains("AddressSanitizer") || err.contains("runtime error:") ||
                      err.contains("LeakSanitizer") || err.contains("UndefinedBehaviorSanitizer");
  QVERIFY2(!report, qPrintable(args.join(' ').left(300) + "\n" + QString::fromUtf8(err.left(2000))));
}

void checkFiniteNumbers(const nlohmann::json& j, const std::string& where) {
  for (const auto& [key, v] : j.items()) {
    if (v.is_structured()) {
      checkFiniteNumbers(v, where + "." + key);
    } else if (v.is_null()) {
      QVERIFY2(key == "diffracted_deg", qPrintable(QString::fromStdString(where + ": null in " + key)));
    } else if (v.is_number_float()) {
      QVERIFY2(std::isfinite(v.get<double>()), qPrintable(QString::fromStdString(where + ": " + key)));
    }
  }
}

// A refusal must be the documented kind and text: named, bounded, valid UTF-8, never the JSON
// library's own message.
void checkRefusal(const std::exception& e, const std::string& prefix, long i) {
  const std::string m = e.what();
  QVERIFY2(dynamic_cast<const std::invalid_argument*>(&e) != nullptr || dynamic_cast<const std::runtime_error*>(&e),
           qPrintable(QString("case %1: not an input error: %2").arg(i).arg(QString::fromStdString(m))));
  QVERIFY2(m.find("json.exception") == std::string::npos,
           qPrintable(QString("case %1: raw library text: %2").arg(i).arg(QString::fromStdString(m))));
  QVERIFY2(m.rfind(prefix, 0) == 0, qPrintable(QString("case %1: '%2' does not start with '%3'")
                                                   .arg(i)
                                                   .arg(QString::fromStdString(m))
                                                   .arg(QString::fromStdString(prefix))));
  QVERIFY2(isValidUtf8Json(m) && m.size() < 4000, qPrintable(QString("case %1: message not UTF-8/bounded").arg(i)));
}

std::string smallSpecText() {
  return fovea::testing::smallToleranceSpec().toStdString();
}

std::string tolerancePartText(int records) {
  nlohmann::json r = nlohmann::json::array();
  for (int i = 0; i < records; ++i)
    r.push_back({{"trial", i}, {"inputs", {0.1 * i, -0.2}}, {"figures", {90 - i, 90, 5, 0.1 * i, 0.5}}});
  nlohmann::json p{{"format", "fovea-tolerance-part"},
                   {"version", 1},
                   {"shard", {0, 1}},
                   {"scene", "s"},
                   {"scene_digest", "0"},
                   {"seed", 1},
                   {"trials", records},
                   {"spec", nlohmann::json::parse(smallSpecText())},
                   {"nominal",
                    {{"fov_min_deg", 90},
                     {"fov_zero_gaze_deg", 90},
                     {"eyebox_mm", 5},
                     {"inset_error_deg", 0},
                     {"mean_efficiency", 0.5}}},
                   {"records", r}};
  return p.dump(1);
}

std::string colourCsvText() {
  std::string t = "display,channel,level,x,y,Y,repeat\n";
  const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  for (const char* d : {"foveal", "peripheral"})
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < 256; l += 1)
        t += std::string(d) + "," + "RGB"[c] + "," + std::to_string(l) + "," + std::to_string(xy[c][0]) + "," +
             std::to_string(xy[c][1]) + "," + std::to_string(0.3 * l) + ",1\n";
  return t;
}

}  // namespace

class TestFuzz : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() { qInfo("fuzz seed %u, scale %ld", kSeed, kScale); }

  void sceneMutations() {
    Mutator m(kSeed);
    const std::string base(embeddedDefaultSceneJson());
    const long n = 300 * kScale;
    long accepted = 0;
    for (long i = 0; i < n; ++i) {
      const std::string text = m.mutate(base);
      const SceneLoadResult r = parseScene(text, "fuzz.json");
      for (const auto& e : r.errors) {
        QVERIFY2(isValidUtf8Json(e), qPrintable(QString("case %1: message is not UTF-8").arg(i)));
        QVERIFY2(e.size() < 2000, qPrintable(QString("case %1: message of %2 bytes").arg(i).arg(e.size())));
      }
      QCOMPARE(r.ok(), r.errors.empty());
      if (!r.ok()) continue;
      ++accepted;
      const std::string canonical = serializeScene(*r.scene);
      const SceneLoadResult again = parseScene(canonical, "canonical.json");
      QVERIFY2(again.ok(), qPrintable(QString("case %1: canonical form does not load").arg(i)));
      QCOMPARE(serializeScene(*again.scene), canonical);
      QVERIFY(validateScene(*r.scene).empty());
    }
    qInfo("%ld mutated scenes, %ld accepted", n, accepted);
  }

  void batchLines() {
    Mutator m(kSeed + 1);
    const long n = 400 * kScale;
    QByteArray in;
    for (long i = 0; i < n; ++i) {
      std::string line = requestLine(m);
      line.erase(std::remove(line.begin(), line.end(), '\n'), line.end());
      in += QByteArray::fromStdString(line) + "\n";
    }
    const QStringList args{"grating", "--batch", "-"};
    const auto r = fovea::testing::runFoveaCli(args, 300000, in);
    checkNoSanitizerReport(r.err, args);
    QVERIFY2(r.code == 0 || r.code == 1, qPrintable(QString("exit %1: %2").arg(r.code).arg(QString(r.err.left(500)))));
    QList<QByteArray> lines = r.out.split('\n');
    if (!lines.isEmpty() && lines.back().isEmpty()) lines.pop_back();
    QCOMPARE(long(lines.size()), n);
    long errors = 0;
    for (long i = 0; i < n; ++i) {
      const std::string where = "output line " + std::to_string(i + 1);
      nlohmann::json j;
      try {
        j = nlohmann::json::parse(lines[int(i)].toStdString());
      } catch (const std::exception& e) {
        QFAIL(qPrintable(QString::fromStdString(where + ": not JSON: " + e.what())));
      }
      if (j.contains("error")) {
        ++errors;
        QVERIFY2(j["error"].get<std::string>().rfind("line " + std::to_string(i + 1) + ": ", 0) == 0,
                 qPrintable(QString::fromStdString(where + ": " + j["error"].get<std::string>())));
        continue;
      }
      checkFiniteNumbers(j, where);
      for (const char* key : {"efficiency", "zero_order"}) {
        const double v = j[key].get<double>();
        QVERIFY2(v >= 0.0 && v <= 1.0, qPrintable(QString::fromStdString(where + ": " + key)));
      }
    }
    QCOMPARE(r.code, errors > 0 ? 1 : 0);
    qInfo("%ld batch lines, %ld errors", n, errors);
  }

  void argumentSets() {
    Mutator m(kSeed + 2);
    const fs::path dir = tmpDir();
    { std::ofstream(dir / "scene.json") << embeddedDefaultSceneJson(); }
    std::error_code ec;
    fs::remove(dir / "loop.json", ec);
    fs::create_symlink("loop.json", dir / "loop.json", ec);
    const QStringList paths{QString::fromStdString((dir / "scene.json").string()),
                            QString::fromStdString(dir.string()),
                            "/proc/x.json",
                            "/dev/null",
                            "/nonexistent/x.json",
                            QString::fromStdString((dir / "loop.json").string()),
                            ""};
    const QStringList flags{"--n0",        "--n1",        "--thickness-um",  "--period-nm",
                            "--slant-deg", "--probe-deg", "--wavelength-nm", "--absorption-per-mm"};
    // Each set is one process start (seconds under ASan on a loaded machine): few by default.
#if defined(__SANITIZE_ADDRESS__)
    const long n = 12 * kScale;
#else
    const long n = 20 * kScale;
#endif
    for (long i = 0; i < n; ++i) {
      QStringList args;
      const std::size_t kind = m.below(4);
      if (kind < 2) {
        args = {"grating", "--n0",        "1.5", "--n1",        "0.02", "--thickness-um",  "16",  "--period-nm",
                "177.3",   "--slant-deg", "0",   "--probe-deg", "0",    "--wavelength-nm", "532", "--json"};
        if (kind == 1)
          args << "--model"
               << "rcwa"
               << "--orders"
               << "2"
               << "--slices"
               << "16";
        for (int k = int(m.below(3)) + 1; k > 0; --k) {
          const QString flag = flags[int(m.below(std::size_t(flags.size())))];
          QString value = QString::fromStdString(m.edge());
          if (value.startsWith('"')) value = value.mid(1, value.size() - 2);
          const int at = int(args.indexOf(flag));
          if (at >= 0)
            args[at + 1] = value;
          else
            args << flag << value;
        }
      } else {
        args = {kind == 2 ? "validate" : "format", paths[int(m.below(std::size_t(paths.size())))]};
        if (kind == 2 && m.below(2)) args << "--json";
        if (kind == 3) args << "-i";
      }
      const auto r = fovea::testing::runFoveaCli(args, 60000);
      checkNoSanitizerReport(r.err, args);
      QVERIFY2(
          r.code >= 0 && r.code <= 2,
          qPrintable(QString("exit %1 for: %2\n%3").arg(r.code).arg(args.join(' ')).arg(QString(r.err.left(500)))));
      if (r.code == 0 && args.contains("--json")) {
        nlohmann::json j;
        try {
          j = nlohmann::json::parse(r.out.toStdString());
        } catch (const std::exception&) {
          QFAIL(qPrintable("not JSON: " + args.join(' ')));
        }
        if (args[0] == "grating") checkFiniteNumbers(j, args.join(' ').toStdString());
      }
      if (args[0] == "validate" && args.contains("--json"))
        QVERIFY2(nlohmann::json::accept(r.out.toStdString()),
                 qPrintable("validate --json printed no JSON: " + args.join(' ')));
    }
  }

  // 4. Tolerance specs: every refusal names the file; an accepted spec is inside its limits.
  void toleranceSpecs() {
    Mutator m(kSeed + 3);
    const std::string base = smallSpecText();
    const long n = 300 * kScale;
    long accepted = 0;
    for (long i = 0; i < n; ++i) {
      auto parsed = parseJsonText(m.mutate(base));
      if (parsed.index() == 1) continue;  // the JSON reader's own refusals: sceneMutations covers them
      try {
        const ToleranceSpec s = parseToleranceSpec(std::get<nlohmann::json>(parsed), "fuzz.json");
        ++accepted;
        QVERIFY(!s.gazes_deg.empty() && s.gazes_deg.size() <= 201);
        for (double g : s.gazes_deg) QVERIFY(std::abs(g) <= 80);
        QVERIFY(s.optimiser.bracket_points >= 3 && s.optimiser.bracket_points <= 65);
        QVERIFY(s.optimiser.edge_bisections >= 0 && s.optimiser.edge_bisections <= 20);
        QVERIFY(!s.parameters.empty() && s.parameters.size() <= kMaxToleranceParameters);
      } catch (const std::exception& e) {
        checkRefusal(e, "fuzz.json: ", i);
      }
    }
    qInfo("%ld mutated tolerance specs, %ld accepted", n, accepted);
  }

  // 4. Tolerance parts through merge: refusals name the part; a merged result's figure counts
  // add up to the records (non-finite ones counted, not binned).
  void toleranceParts() {
    Mutator m(kSeed + 4);
    const std::string base = tolerancePartText(6);
    const long n = 300 * kScale;
    long accepted = 0;
    for (long i = 0; i < n; ++i) {
      auto parsed = parseJsonText(m.mutate(base));
      if (parsed.index() == 1) continue;
      try {
        const nlohmann::json r = mergeToleranceParts({std::get<nlohmann::json>(parsed)}, {"part.json"});
        ++accepted;
        for (const auto& [name, d] : r["figures"].items()) {
          const std::size_t count = d["count"].get<std::size_t>() + d["non_finite"].get<std::size_t>();
          QVERIFY(count <= r["trials"].get<std::size_t>());
          if (d.contains("histogram")) {
            std::size_t binned = 0;
            for (const auto& c : d["histogram"]["counts"]) binned += c.get<std::size_t>();
            QCOMPARE(binned, d["count"].get<std::size_t>());
          }
        }
      } catch (const std::exception& e) {
        checkRefusal(e, "merge: ", i);
      }
    }
    qInfo("%ld mutated tolerance parts, %ld merged", n, accepted);
    // Regression (issue 28): the statistics of figures that overflowed a double.
    ToleranceSpec spec = parseToleranceSpec(nlohmann::json::parse(smallSpecText()));
    std::vector<ToleranceRecord> records;
    for (std::uint64_t t = 0; t < 8; ++t)
      records.push_back(
          {t, {t % 2 ? HUGE_VAL : 1e308, std::nan("")}, {std::nan(""), -HUGE_VAL, 5, 1e308, -1e308}, true, {}});
    const nlohmann::json st = toleranceStatistics(spec, 1, records);
    QCOMPARE(st["figures"]["fov_min_deg"]["non_finite"].get<int>(), 8);
    QCOMPARE(st["inputs"]["HOE x"]["non_finite"].get<int>(), 4);
  }

  // 4. Fit targets: refusals name the target and the key; accepted ones keep chi2 finite.
  void fitTargets() {
    Mutator m(kSeed + 5);
    const std::string base = R"({"format": "fovea-fit-targets", "version": 1, "targets": [
      {"id": "fov", "observable": "fov_deg", "gaze_deg": 0, "direction": "horizontal", "value": 90, "sigma": 0.5},
      {"id": "box", "observable": "eyebox_mm", "gaze_from": -30, "gaze_to": 30, "value": 6, "sigma": 0.2},
      {"id": "eff", "observable": "mean_efficiency", "wavelength_nm": 532, "value": 0.4, "sigma": 0.05}]})";
    const long n = 300 * kScale;
    long accepted = 0;
    for (long i = 0; i < n; ++i) {
      auto parsed = parseJsonText(m.mutate(base));
      if (parsed.index() == 1) continue;
      try {
        for (const FitTarget& t : parseFitTargets(std::get<nlohmann::json>(parsed))) {
          const double r = t.value / t.sigma;
          QVERIFY(std::isfinite(r * r));
          if (t.parameters.contains("wavelength_nm") && t.parameters["wavelength_nm"].is_number()) {
            const double nm = t.parameters["wavelength_nm"].get<double>();
            QVERIFY(nm > 0 && nm <= 2000);
          }
          for (const char* g : {"gaze_from", "gaze_to", "gaze_deg"})
            if (t.parameters.contains(g)) QVERIFY(std::abs(t.parameters[g].get<double>()) <= 80);
        }
        ++accepted;
      } catch (const std::exception& e) {
        checkRefusal(e, "", i);
      }
    }
    qInfo("%ld mutated targets files, %ld accepted", n, accepted);
  }

  // 4. Colour readings: a CSV (mutated bytes, a BOM, an X column) and the JSON measurements.
  void colourInputs() {
    Mutator m(kSeed + 6);
    const std::string csv = colourCsvText();
    const long n = 60 * kScale;
    long accepted = 0;
    for (long i = 0; i < n; ++i) {
      std::string text = m.mutate(csv);
      if (i % 5 == 0) text = "\xEF\xBB\xBF" + text;
      const color::MeasurementImport imp = color::importSpectroradiometerCsv(text);
      QVERIFY(imp.problems.size() <= 1001);
      for (const auto& p : imp.problems) QVERIFY(p.message.size() < 4000);
      if (!imp.ok()) continue;
      ++accepted;
      for (const auto* d : {&imp.measurements.foveal, &imp.measurements.peripheral})
        for (const auto& c : d->channels) QVERIFY(c.Y.back() > c.Y.front());
    }
    qInfo("%ld mutated colour CSVs, %ld accepted", n, accepted);
    // Regression (issue 28): BOM accepted, X not x, no light refused.
    QVERIFY(color::importSpectroradiometerCsv("\xEF\xBB\xBF" + csv).ok());
    std::string tristimulus = csv;
    tristimulus.replace(tristimulus.find(",x,"), 3, ",X,");
    QVERIFY(!color::importSpectroradiometerCsv(tristimulus).ok());
    const color::MeasurementImport imp = color::importSpectroradiometerCsv(csv);
    QVERIFY(imp.ok());
    const std::string json = color::toJson(imp.measurements).dump();
    for (long i = 0; i < 100 * kScale; ++i) {
      auto parsed = parseJsonText(m.mutate(json));
      if (parsed.index() == 1) continue;
      try {
        (void)color::parseColorMeasurements(std::get<nlohmann::json>(parsed));
      } catch (const std::exception& e) {
        checkRefusal(e, "", i);
      }
    }
    color::ColorMeasurements dark = imp.measurements;
    for (auto& c : dark.foveal.channels) std::fill(c.Y.begin(), c.Y.end(), 0.0);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, color::parseColorMeasurements(color::toJson(dark)));
  }

  // 4. Images: mutated PNG and JPEG bytes decode or are refused with the file's name.
  void imageFiles() {
    const fs::path dir = tmpDir();
    cv::Mat img(48, 64, CV_32FC3);
    for (int y = 0; y < img.rows; ++y)
      for (int x = 0; x < img.cols; ++x) img.at<cv::Vec3f>(y, x) = cv::Vec3f(x / 64.0f, y / 48.0f, 0.5f);
    Mutator m(kSeed + 7);
    long refused = 0;
    const long n = 40 * kScale;
    for (const char* ext : {".png", ".jpg"}) {
      const fs::path clean = dir / (std::string("clean") + ext);
      image::writeLinearRgb(clean.string(), img);
      std::ifstream in(clean, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      for (long i = 0; i < n; ++i) {
        std::string b = bytes;
        // Byte flips and cuts: the header's sizes, the chunks, the end marker.
        for (int k = int(m.below(4)) + 1; k > 0; --k) b[m.below(b.size())] = char(m.below(256));
        if (i % 4 == 0) b.resize(m.below(b.size()));
        const fs::path f = dir / (std::string("mutated") + ext);
        std::ofstream(f, std::ios::binary | std::ios::trunc) << b;
        try {
          const cv::Mat out = image::readLinearRgb(f.string());
          QVERIFY(!out.empty() && double(out.total()) <= image::kMaxImagePixels);
        } catch (const image::ImageIoError& e) {
          ++refused;
          QVERIFY(std::string(e.what()).rfind(f.string() + ": ", 0) == 0);
        }
      }
      // Regression (issue 28): a JPEG cut short is refused, not decoded to grey.
      if (std::string(ext) == ".jpg") {
        const fs::path cut = dir / "cut.jpg";
        std::ofstream(cut, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
        QVERIFY_THROWS_EXCEPTION(image::ImageIoError, image::readLinearRgb(cut.string()));
      }
    }
    qInfo("%ld mutated images, %ld refused", 2 * n, refused);
  }

  // 5. Capture manifests and APT transcripts through fovea-cli (few: one process each).
  void manifestsAndTranscripts() {
    Mutator m(kSeed + 8);
    const fs::path dir = tmpDir();
    const std::string manifest = R"({"format": "fovea-capture-session", "kind": "geometric", "steps": [
      {"id": "g10", "kind": "geometric", "display": "peripheral", "gaze_deg": [10, 0], "targets": [],
       "pattern": {"kind": "off"}}],
      "captures": [{"step": "g10", "positions": {"hoe.x": 1.5}}, {"step": "g10", "positions": {"hoe.x": 1.75}}]})";
    const std::string transcript = "# t\n0.000000 TX 05 00 00 00 50 01\n0.001000 RX 06 00 54 00 81 50 01 02 03 04\n";
#if defined(__SANITIZE_ADDRESS__)
    const long n = 3 * kScale;
#else
    const long n = 5 * kScale;
#endif
    for (long i = 0; i < n; ++i) {
      const fs::path mf = dir / "manifest.json", tf = dir / "t.apt";
      std::ofstream(mf, std::ios::trunc) << (i == 0 ? manifest : m.mutate(manifest));
      std::ofstream(tf, std::ios::trunc) << m.mutate(transcript);
      const QList<QStringList> calls{{"fit-targets", QString::fromStdString(mf.string()), "--json"},
                                     {"stage", "--virtual", "MTS25-Z8", "--replay", QString::fromStdString(tf.string()),
                                      "--timeout", "0.2", "position"}};
      for (const auto& args : calls) {
        const auto r = fovea::testing::runFoveaCli(args, 60000);
        checkNoSanitizerReport(r.err, args);
        QVERIFY2(
            r.code >= 0 && r.code <= 3,
            qPrintable(QString("exit %1 for: %2\n%3").arg(r.code).arg(args.join(' ')).arg(QString(r.err.left(500)))));
        QVERIFY2(!r.err.contains("json.exception"), r.err.constData());
        if (i == 0 && args[0] == "fit-targets") {
          QCOMPARE(r.code, 0);  // a step captured twice: one target, ids unique
          QCOMPARE(nlohmann::json::parse(r.out.toStdString())["targets"].size(), std::size_t(1));
        }
      }
    }
  }

  // 6. One case per defect of issue 28 (the rest are in process above): exit code and message.
  void issueRegressions() {
    const fs::path dir = tmpDir();
    const auto file = [&](const char* name, const std::string& text) {
      std::ofstream(dir / name, std::ios::binary | std::ios::trunc) << text;
      return QString::fromStdString((dir / name).string());
    };
    nlohmann::json wrap = nlohmann::json::parse(smallSpecText());
    wrap["optimiser"] = {{"edge_bisections", 4294967299ULL}};
    nlohmann::json far = nlohmann::json::parse(smallSpecText());
    far["gaze"] = {{"from_deg", 1e300}, {"to_deg", 1e300}, {"step_deg", 5e-324}};
    nlohmann::json empty_records = nlohmann::json::parse(tolerancePartText(1));
    empty_records["records"][0]["inputs"] = nlohmann::json::array();
    empty_records["records"][0]["figures"] = nlohmann::json::array();
    const QString fifo = QString::fromStdString((dir / "fifo.csv").string());
    std::error_code ec;
    fs::remove(fifo.toStdString(), ec);
    QCOMPARE(::mkfifo(fifo.toLocal8Bit().constData(), 0600), 0);
    const QString wrap_spec = file("wrap.json", wrap.dump());
    const QString far_spec = file("far.json", far.dump());
    const QString part = file("empty-part.json", empty_records.dump());
    const QString targets = file(
        "wl.json", R"([{"id": "e", "observable": "mean_efficiency", "wavelength_nm": 0, "value": 0.4, "sigma": 0.1}])");
    const QString transcript = file("keep.apt", "# kept\n");
    struct Case {
      QStringList args;
      int code;
      QString message;
    };
    const QList<Case> cases{
        {{"merge", part, "--json"}, 1, "empty-part.json: records[0].inputs: must be an array of 2 numbers"},
        {{"tolerance", "--spec", wrap_spec, "--trials", "1"},
         1,
         "wrap.json: optimiser.edge_bisections: must be an integer in [0, 20], got 4294967299"},
        {{"tolerance", "--spec", far_spec, "--trials", "1"}, 1, "far.json: gaze.from_deg: must be in [-80, 80]"},
        {{"tolerance", "--spec", wrap_spec, "--seed", "-1"}, 2, "--seed: expected an integer"},
        {{"tolerance", "--spec", wrap_spec, "--seed", "18446744073709551616"}, 2, "--seed: expected an integer"},
        {{"tolerance", "--spec", wrap_spec, "--seed", "1e23"}, 2, "--seed: expected an integer"},
        {{"fit-targets", "/nonexistent", "--out", "/dev/null"}, 2, "--out: /dev/null: is a character device"},
        {{"fit-targets", "/nonexistent", "--out", ""}, 2, "--out: an empty path names no file"},
        {{"stage", "--virtual", "MTS25-Z8", "--trace", transcript, "--transcript", transcript, "position"},
         2,
         "name the same file"},
        {{"stage", "--virtual", "MTS25-Z8", "--transcript", transcript, "move-abs", "22"}, 2, "soft limits"},
        {{"track", "/dev/zero"}, 1, "/dev/zero: is a device or a socket, not a regular file"},
        {{"color-calibrate", "--measurements", "/dev/zero", "--out",
          QString::fromStdString((dir / "cal.json").string())},
         1,
         "is a character device"},
        {{"color-calibrate", "--measurements", fifo, "--out", QString::fromStdString((dir / "cal.json").string())},
         1,
         "is a FIFO, not a regular file"},
        {{"fit", "--targets", targets, "--free", "eye.relief_mm"},
         1,
         "wl.json: target \"e\": wavelength_nm: must be > 0"},
    };
    for (const auto& c : cases) {
      const auto r = fovea::testing::runFoveaCli(c.args, 60000);
      checkNoSanitizerReport(r.err, c.args);
      QVERIFY2(r.code == c.code && r.err.contains(c.message.toUtf8()),
               qPrintable(QString("exit %1 (want %2) for: %3\n%4")
                              .arg(r.code)
                              .arg(c.code)
                              .arg(c.args.join(' '))
                              .arg(QString(r.err.left(600)))));
    }
    // The refused move left the transcript as it was.
    std::ifstream kept(transcript.toStdString());
    std::string first;
    std::getline(kept, first);
    QCOMPARE(first, std::string("# kept"));
  }
};

QTEST_GUILESS_MAIN(TestFuzz)

}  // namespace tst_fuzz
#include "tst_fuzz.moc"
