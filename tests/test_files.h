#pragma once
// Files for the test suites: a scratch folder under $FOVEA_TEST_TMP (set by CTest per
// configuration, /tmp otherwise), a whole file as text, the shipped prototype scene, and a
// file written into a temporary folder.
#include <QByteArray>
#include <QFile>
#include <QString>
#include <QTemporaryDir>
#include <QtGlobal>
#include "tests/test_paths.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fovea::testing {

// $FOVEA_TEST_TMP/<name>, created; emptied first when `fresh`.
inline std::filesystem::path testTmpDir(const std::string& name, bool fresh = false) {
  const auto dir = std::filesystem::path(qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp").toStdString()) / name;
  if (fresh) std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Whether a shared object whose file name contains `name` is mapped into this process.
inline bool mappedInProcess(const std::string& name) {
  std::ifstream maps("/proc/self/maps");
  for (std::string line; std::getline(maps, line);)
    if (line.find(name) != std::string::npos) return true;
  return false;
}

// The file's bytes ("" when it cannot be read: the caller's comparison then fails).
inline std::string readFileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::string prototypeSceneText() {
  return readFileText(std::filesystem::path(FOVEA_SOURCE_DIR) / "resources/scenes/prototype-bench.json");
}

// Writes `text` to `name` inside `dir`; the path, or "" when it cannot be written.
inline QString writeTestFile(const QTemporaryDir& dir, const QString& name, const QByteArray& text) {
  const QString path = dir.filePath(name);
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly)) return {};
  file.write(text);
  return path;
}

}  // namespace fovea::testing
