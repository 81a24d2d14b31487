#pragma once
// Shared plumbing of fovea-cli: command registration, exit codes, JSON output, scenes.
//
// Each command lives in its own cmd_<name>.cpp and registers itself with a static
//   const fovea::cli::Registrar reg{"name", &install};
// where install() adds a CLI11 subcommand and its callback. Exit codes:
//   0 success, 1 bad input data (unreadable or invalid file, degenerate data),
//   2 invalid arguments (the message names the argument), 3 device timeout.

#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
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

// Prints JSON to stdout: pretty (2-space) unless compact; NaN/Inf become null. A failed write
// (a full disk, `> /dev/full`) is an inputError "stdout: write failed: STRERROR" (exit 1).
void printJson(const nlohmann::json& j, bool compact = false);
// The same for text, printed as it is.
void printText(const std::string& text);

// Parses "A" or "A,B" into numbers; throws usageError naming `argName` on failure.
std::vector<double> parseNumberList(const std::string& text, const std::string& argName, std::size_t minCount,
                                    std::size_t maxCount);

// An output option (--out, --write-scene, ...): when it was given, its path must be able to
// hold a regular file (not empty, not an existing directory, device or FIFO, its directory
// writable); usageError "OPTION: PATH: problem" otherwise. Call before any work.
void checkOutputOption(const CLI::Option* option, const std::string& path);
// The outputs of one command line ({option, path}) must be different files; usageError otherwise.
void checkDistinctOutputs(const std::vector<std::pair<std::string, std::string>>& outputs);

// A seed: a decimal integer in [0, 2^64 - 1] ("-1", "18446744073709551616", "1e23", "1.5" are
// refused: usageError naming `argName`).
std::uint64_t parseSeed(const std::string& text, const std::string& argName);

// --seed as a validated unsigned integer of T's width (parseSeed, then the range of T): CLI11's
// own conversion turns "-1" into 2^64 - 1.
template <class T>
CLI::Option* addSeedOption(CLI::App* cmd, T& seed, const std::string& help) {
  static_assert(std::is_unsigned_v<T>);
  return cmd->add_option_function<std::string>(
      "--seed",
      [&seed](const std::string& text) {
        const std::uint64_t v = parseSeed(text, "--seed");
        if (v > std::numeric_limits<T>::max())
          usageError("--seed: expected an integer in [0, " + std::to_string(std::numeric_limits<T>::max()) +
                     "], got '" + text + "'");
        seed = static_cast<T>(v);
      },
      help);
}

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
