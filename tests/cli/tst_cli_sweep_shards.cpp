// fovea-cli sweep --shard K/N and merge: the parts of three shards, merged in any order, give
// byte for byte the document of one unsharded sweep; the part's contract; a missing shard,
// parts of another sweep and parts of another kind are named.
#include <QtTest>

#include <QFile>
#include <QTemporaryDir>

#include <functional>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace tst_cli_sweep_shards {

using fovea::testing::CliCall;
using fovea::testing::runFoveaCli;

namespace {

using fovea::testing::writeTestFile;

// Five gazes (-10 .. 10 by 5) at a low ray count: a cheap sweep whose eye-box borders lie inside
// the range, so the merge bisects them.
const QStringList kSweep{"sweep", "--gaze-from", "-10", "--gaze-to", "10", "--gaze-step", "5", "--rays", "400"};

}  // namespace

class TestCliSweepShards : public QObject {
  Q_OBJECT
 private slots:
  void threeShardsMergeToTheUnshardedBytes() {
    QTemporaryDir dir;
    CliCall call;
    call.env.insert("FOVEA_CACHE_DIR", dir.filePath("cache"));
    const auto whole = runFoveaCli(kSweep + QStringList{"--no-cache", "--json"}, call);
    QCOMPARE(whole.code, 0);
    const auto w = nlohmann::json::parse(whole.out.toStdString());
    QCOMPARE(w["samples"].size(), std::size_t{5});

    QStringList parts;
    for (const int k : {1, 2, 0}) {
      const auto p = runFoveaCli(kSweep + QStringList{"--shard", QString("%1/3").arg(k), "--json"}, call);
      QCOMPARE(p.code, 0);
      const auto j = nlohmann::json::parse(p.out.toStdString());
      QCOMPARE(j["format"].get<std::string>(), std::string("fovea-sweep-part"));
      QCOMPARE(j["shard"], nlohmann::json({k, 3}));
      QCOMPARE(j["gaze_count"].get<int>(), 5);
      QCOMPARE(j["samples"].size(), std::size_t{k == 0 ? 1u : 2u});  // gazes [0,1) [1,3) [3,5)
      QCOMPARE(j.contains("reference"), k == 0);                     // the zero-gaze reference
      parts << writeTestFile(dir, QString("part-%1.json").arg(k), p.out);
    }
    const auto merged = runFoveaCli(QStringList{"merge"} + parts + QStringList{"--json"}, call);
    QCOMPARE(merged.code, 0);
    QCOMPARE(merged.out, whole.out);

    // Parts whose header contradicts their samples (issue 28): a gaze_count the values do not
    // give, a sample's gaze forged; both named with the file and the key.
    auto forged = [&](const QString& name, const std::function<void(nlohmann::json&, int)>& change) {
      QStringList out;
      for (const QString& path : parts) {
        QFile f(path);
        if (!f.open(QIODevice::ReadOnly)) return QStringList{};
        nlohmann::json j = nlohmann::json::parse(f.readAll().toStdString());
        change(j, j["shard"][0].get<int>());
        out << writeTestFile(dir, name + QString("-%1.json").arg(j["shard"][0].get<int>()),
                             QByteArray::fromStdString(j.dump()));
      }
      return out;
    };
    const auto count =
        runFoveaCli(QStringList{"merge"} + forged("count", [](nlohmann::json& j, int) { j["gaze_count"] = 4; }) +
                        QStringList{"--json"},
                    call);
    QCOMPARE(count.code, 1);
    QVERIFY2(count.err.contains("count-") && count.err.contains(": gaze_count: must be 5"), count.err.constData());
    const auto gaze = runFoveaCli(QStringList{"merge"} +
                                      forged("gaze",
                                             [](nlohmann::json& j, int k) {
                                               if (k == 2) j["samples"][1]["gaze_deg"] = 7.5;
                                             }) +
                                      QStringList{"--json"},
                                  call);
    QCOMPARE(gaze.code, 1);
    QVERIFY2(gaze.err.contains("gaze-2.json: samples[1].gaze_deg: must be 10"), gaze.err.constData());

    // A shard missing.
    const auto missing = runFoveaCli({"merge", parts[0], parts[2], "--json"}, call);
    QCOMPARE(missing.code, 1);
    QVERIFY2(missing.err.contains("missing shard(s) 2 of 3"), missing.err.constData());
    // A part of another sweep (another step: other gazes).
    QStringList other = kSweep;
    other[6] = "10";
    const auto o = runFoveaCli(other + QStringList{"--shard", "2/3", "--json"}, call);
    QCOMPARE(o.code, 0);
    const QString otherPart = writeTestFile(dir, "other.json", o.out);
    const auto mixed = runFoveaCli({"merge", parts[2], parts[0], otherPart, "--json"}, call);
    QCOMPARE(mixed.code, 1);
    QVERIFY2(mixed.err.contains("differs from part 1"), mixed.err.constData());
    // A tolerance part among sweep parts.
    const QString notSweep = writeTestFile(dir, "tol-part.json", R"({"format": "fovea-tolerance-part"})");
    const auto kinds = runFoveaCli({"merge", parts[0], notSweep, "--json"}, call);
    QCOMPARE(kinds.code, 1);
    QVERIFY2(kinds.err.contains("part 2 is not a fovea-sweep-part"), kinds.err.constData());
    // A bad shard is a usage error.
    const auto bad = runFoveaCli(kSweep + QStringList{"--shard", "3/3", "--json"}, call);
    QCOMPARE(bad.code, 2);
    QVERIFY2(bad.err.contains("--shard"), bad.err.constData());
  }
};

QTEST_MAIN(TestCliSweepShards)

}  // namespace tst_cli_sweep_shards
#include "tst_cli_sweep_shards.moc"
