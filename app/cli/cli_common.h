#pragma once
// Shared plumbing of fovea-cli: command registration, exit codes, JSON output, scenes.
//
// Each command lives in its own cmd_<name>.cpp and registers itself with a static
//   const fovea::cli::Registrar reg{"name", &install};
// where install() adds a CLI11 subcommand and its callback. Exit codes:
//   0 success, 1 bad input data (unreadable or invalid file, degenerate data),
//   2 invalid arguments (the message names the argument), 3 device timeout.

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "model/scene/scene.h"

namespace fovea::cli {

using Installer = void (*)(CLI::App& app);

struct Registrar {
  Registrar(const char* name, Installer install);
};
std::vector<std::pair<std::string, Installer>>& registry();

// Thrown by commands; main() prints the message to stderr and exits with the code.
class CliError : public std::runtime_error {
 public:
  CliError(int code, const std::string& message) : std::runtime_error(message), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};
[[noreturn]] inline void usageError(const std::string& m) {
  throw CliError(2, m);
}
[[noreturn]] inline void inputError(const std::string& m) {
  throw CliError(1, m);
}

// Loads a scene file (exit 1 with every problem, one per line), or the embedded default
// prototype bench when `path` is empty.
Scene loadSceneOrExit(const std::string& path);

// Prints JSON to stdout: pretty (2-space) unless compact; NaN/Inf become null.
void printJson(const nlohmann::json& j, bool compact = false);

// Parses "A" or "A,B" into numbers; throws usageError naming `argName` on failure.
std::vector<double> parseNumberList(const std::string& text, const std::string& argName, std::size_t minCount,
                                    std::size_t maxCount);

// Parses --shard "K/N" (0 <= K < N <= 100000); throws usageError naming --shard otherwise.
std::pair<int, int> parseShard(const std::string& text);

// A progress bar on stderr when stderr is a terminal; nothing when piped.
class Progress {
 public:
  explicit Progress(std::string label);
  ~Progress();
  void update(double fraction);

 private:
  std::string label_;
  bool tty_;
  int last_ = -1;
};

}  // namespace fovea::cli
