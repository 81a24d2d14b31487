#include "app/cli/cli_common.h"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>

#include "app/embedded_scene.h"
#include "model/io/output_file.h"
#include "model/io/save_temporaries.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {

std::vector<std::pair<std::string, Installer>>& registry() {
  static std::vector<std::pair<std::string, Installer>> r;
  return r;
}

Registrar::Registrar(const char* name, Installer install) {
  registry().emplace_back(name, install);
}

Scene loadSceneOrExit(const std::string& path) {
  SceneLoadResult r =
      path.empty() ? parseScene(embeddedDefaultSceneJson(), std::string(kEmbeddedSceneName)) : loadSceneFile(path);
  for (const auto& w : r.warnings) std::cerr << "warning: " << w << "\n";
  if (!r.ok()) {
    std::string all;
    for (const auto& e : r.errors) all += (all.empty() ? "" : "\n") + e;
    inputError(all);
  }
  return *r.scene;
}

namespace {
nlohmann::json sanitize(const nlohmann::json& j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return nullptr;
  if (j.is_array() || j.is_object()) {
    nlohmann::json out = j;
    for (auto& v : out) v = sanitize(v);
    return out;
  }
  return j;
}
}  // namespace

void printJson(const nlohmann::json& j, bool compact) {
  printText(sanitize(j).dump(compact ? -1 : 2) + "\n");
}

void printText(const std::string& text) {
  std::cout.flush();  // what was printed before stays before
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0) {
    const int e = errno;
    inputError(std::string("stdout: write failed: ") + (e ? std::strerror(e) : "output error"));
  }
}

void checkOutputOption(const CLI::Option* option, const std::string& path) {
  if (option == nullptr || option->count() == 0) return;
  const std::string name = option->get_name();
  if (path.empty()) usageError(name + ": an empty path names no file");
  if (const auto why = cannotWriteFile(path)) usageError(name + ": " + path + ": " + *why);
}

void checkDistinctOutputs(const std::vector<std::pair<std::string, std::string>>& outputs) {
  if (const auto why = sameOutputTwice(outputs)) usageError(*why);
}

std::uint64_t parseSeed(const std::string& text, const std::string& argName) {
  std::uint64_t v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);  // digits only: no sign, no exponent
  if (text.empty() || ec != std::errc{} || ptr != end)
    usageError(argName + ": expected an integer in [0, 18446744073709551615], got '" + text + "'");
  return v;
}

std::pair<int, int> parseShard(const std::string& s) {
  const auto slash = s.find('/');
  int k = -1, n = -1;
  try {
    if (slash != std::string::npos) {
      std::size_t a = 0, b = 0;
      k = std::stoi(s.substr(0, slash), &a);
      n = std::stoi(s.substr(slash + 1), &b);
      if (a != slash || b != s.size() - slash - 1) k = -1;
    }
  } catch (const std::exception&) {
    k = -1;
  }
  if (k < 0 || n < 1 || k >= n || n > 100000) usageError("--shard: expected K/N with 0 <= K < N, got '" + s + "'");
  return {k, n};
}

std::vector<double> parseNumberList(const std::string& text, const std::string& argName, std::size_t minCount,
                                    std::size_t maxCount) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (...) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(v))
      usageError(argName + ": '" + item + "' is not a finite number");
    out.push_back(v);
  }
  if (out.size() < minCount || out.size() > maxCount)
    usageError(argName + ": expected " + std::to_string(minCount) +
               (maxCount > minCount ? " to " + std::to_string(maxCount) : "") + " comma-separated numbers, got '" +
               text + "'");
  return out;
}

Progress::Progress(std::string label) : label_(std::move(label)), tty_(::isatty(STDERR_FILENO) != 0) {}
Progress::~Progress() {
  if (tty_ && last_ >= 0) std::fprintf(stderr, "\n");
}
void Progress::update(double fraction) {
  if (!tty_) return;
  const int pct = static_cast<int>(std::lround(std::clamp(fraction, 0.0, 1.0) * 100));
  if (pct == last_) return;
  last_ = pct;
  const int bars = pct * 30 / 100;
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), bars, "##############################", 30 - bars, "",
               pct);
  std::fflush(stderr);
}

}  // namespace fovea::cli
