// The JSON input layer (model/io/json_input.h): nesting depth, size, UTF-8 and duplicate-key
// limits with their positions, nlohmann's syntax errors, bounded messages, file reading.
#include <QtTest>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "model/io/json_input.h"

namespace tst_json_input {

using namespace fovea;

namespace {
std::string deepArray(std::size_t depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

JsonInputError errorOf(std::string_view text, const JsonLimits& limits = {}) {
  auto r = parseJsonText(text, limits);
  if (!std::holds_alternative<JsonInputError>(r)) qFatal("expected an error for %.60s", std::string(text).c_str());
  return std::get<JsonInputError>(r);
}

std::filesystem::path tmpDir() {
  const auto d = std::filesystem::path(qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp").toStdString()) / "json_input";
  std::filesystem::create_directories(d);
  return d;
}
}  // namespace

class TestJsonInput : public QObject {
  Q_OBJECT
 private slots:
  void depthLimitIsExactAndPositioned() {
    QVERIFY(std::holds_alternative<nlohmann::json>(parseJsonText(deepArray(64))));
    const JsonInputError e = errorOf(deepArray(65));
    QCOMPARE(e.byte, std::size_t(64));
    QCOMPARE(e.line, 1);
    QCOMPARE(e.column, 65);
    QCOMPARE(QString::fromStdString(describe(e, "deep.json")),
             QString("deep.json: line 1, column 65: nesting deeper than 64"));
    // The issue's reproducer: 100 000 levels inside a value, on line 3.
    const std::string text = "{\n \"notes\":\n  " + deepArray(100000) + "}";
    const JsonInputError d = errorOf(text);
    QCOMPARE(d.line, 3);
    QCOMPARE(d.column, 3 + 63);
    QCOMPARE(QString::fromStdString(d.reason), QString("nesting deeper than 64"));
    QCOMPARE(errorOf(deepArray(11), {10, 1000}).reason, std::string("nesting deeper than 10"));
    // Brackets inside strings are text, not nesting.
    QVERIFY(std::holds_alternative<nlohmann::json>(parseJsonText("[\"" + std::string(1000, '[') + "\"]")));
  }

  void sizeLimit() {
    const JsonInputError e = errorOf("[1,2,3]", {64, 6});
    QCOMPARE(QString::fromStdString(e.reason), QString("too large: 7 bytes (limit 6)"));
    QVERIFY(std::holds_alternative<nlohmann::json>(parseJsonText("[1,2,3]", {64, 7})));
  }

  void invalidUtf8ByByteOffset_data() {
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<int>("offset");
    QTest::newRow("lone continuation") << QByteArray("{\"a\":\"x\x80\"}") << 7;
    QTest::newRow("overlong slash") << QByteArray("[\"\xC0\xAF\"]") << 2;
    QTest::newRow("surrogate") << QByteArray("[\"\xED\xA0\x80\"]") << 2;
    QTest::newRow("above U+10FFFF") << QByteArray("[\"\xF4\x90\x80\x80\"]") << 2;
    QTest::newRow("truncated at end") << QByteArray("[\"\xE2\x82") << 2;
    QTest::newRow("outside a string") << QByteArray("[1,\xFF]") << 3;
    QTest::newRow("in a key, line 2") << QByteArray("{\n\"k\xFE\":1}") << 4;
  }
  void invalidUtf8ByByteOffset() {
    QFETCH(QByteArray, text);
    QFETCH(int, offset);
    const JsonInputError e = errorOf(std::string_view(text.constData(), std::size_t(text.size())));
    QCOMPARE(int(e.byte), offset);
    QCOMPARE(QString::fromStdString(e.reason), QString("invalid UTF-8 at byte offset %1").arg(offset));
    QVERIFY(!e.malformed);
  }

  void validUtf8Passes() {
    const auto r = parseJsonText("{\"λ_nm\":\"µm ° € 𝄞\"}");
    QVERIFY(std::holds_alternative<nlohmann::json>(r));
    QCOMPARE(std::get<nlohmann::json>(r)["λ_nm"].get<std::string>(), std::string("µm ° € 𝄞"));
  }

  void duplicateKeysNameBothPositions() {
    const JsonInputError e = errorOf("{\n  \"version\": 2,\n  \"version\": 1\n}");
    QCOMPARE(e.line, 3);
    QCOMPARE(e.column, 3);
    QCOMPARE(QString::fromStdString(describe(e, "s.json")),
             QString("s.json: line 3, column 3: duplicate key \"version\" (first at line 2, column 3)"));
    // An escaped spelling is the same key; the same key in two objects is not a duplicate.
    QCOMPARE(errorOf(R"({"version":2,"\u0076ersion":1})").column, 14);
    QVERIFY(
        std::holds_alternative<nlohmann::json>(parseJsonText(R"({"a":{"x":1},"b":{"x":2},"c":[{"x":1},{"x":2}]})")));
    // Values equal to keys are not keys.
    QVERIFY(std::holds_alternative<nlohmann::json>(parseJsonText(R"({"a":"a","b":["a","a"]})")));
    // An earlier syntax error is reported first.
    const JsonInputError s = errorOf("{\"a\":1,,\"a\":2}");
    QVERIFY(s.malformed);
  }

  void syntaxErrorsKeepTheirFormat() {
    const JsonInputError e = errorOf("{\n  \"a\": tru\n}");
    QVERIFY(e.malformed);
    QCOMPARE(e.line, 2);
    QVERIFY2(describe(e, "f.json").rfind("f.json: malformed JSON at line 2, column ", 0) == 0,
             describe(e, "f.json").c_str());
    const JsonInputError o = errorOf("[1,\n 1e999]");
    QCOMPARE(QString::fromStdString(describe(o, "f.json")),
             QString("f.json: malformed JSON at line 2, column 2: number overflow parsing '1e999'"));
    // A 1 MB token in an error is not quoted whole.
    const JsonInputError big = errorOf("[\"" + std::string(1 << 20, 'x') + "\\q\"]");
    QVERIFY(big.reason.size() < 300);
  }

  void excerptsAreBoundedAndValidUtf8() {
    QCOMPARE(printableExcerpt("abc"), std::string("abc"));
    QCOMPARE(printableExcerpt("a\xFF"
                              "b"),
             std::string("a\\xFFb"));
    QCOMPARE(printableExcerpt(std::string(100, 'x'), 10), std::string(10, 'x') + "…");
    QCOMPARE(printableExcerpt("µµµ", 3), std::string("µµ…"));  // never cut inside a character
    const std::string invalid = "\xC3(\x80";
    QVERIFY(nlohmann::json(printableExcerpt(invalid)).dump().size() > 0);  // dump() throws on invalid UTF-8
  }

  void readInputFileRefusesBeforeReading() {
    const auto dir = tmpDir();
    QCOMPARE(std::get<1>(readInputFile(dir)), std::string("is a directory, not a file"));
    QCOMPARE(std::get<1>(readInputFile(dir / "missing.json")), std::string("no such file"));
    { std::ofstream(dir / "ten.json") << "[1,2,3,45]"; }
    QCOMPARE(std::get<1>(readInputFile(dir / "ten.json", 9)), std::string("too large: 10 bytes (limit 9)"));
    QCOMPARE(std::get<0>(readInputFile(dir / "ten.json", 10)), std::string("[1,2,3,45]"));
    // Devices and FIFOs are refused before a byte is read (/dev/zero never ends; a FIFO with no
    // writer would block the open).
    QCOMPARE(std::get<1>(readInputFile("/dev/zero", 1000)), std::string("is a character device, not a regular file"));
    const auto fifo = dir / "pipe.json";
    std::filesystem::remove(fifo);
    QCOMPARE(::mkfifo(fifo.c_str(), 0600), 0);
    QCOMPARE(std::get<1>(readInputFile(fifo)), std::string("is a FIFO, not a regular file"));
    QCOMPARE(std::get<1>(readInputFile("")), std::string("an empty path names no file"));
  }
};

QTEST_GUILESS_MAIN(TestJsonInput)

}  // namespace tst_json_input
#include "tst_json_input.moc"
