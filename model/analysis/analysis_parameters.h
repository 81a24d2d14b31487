#pragma once
// Typed, validated parameters of an analysis (analysis_registry.h): the one declaration of
// a parameter's name, unit, default, range and help, and the one validator that fovea-cli
// and the studio both apply to every value before any work starts.
//
// Values travel as a JSON object {name: value}: numbers for Number and Integer, strings
// for Choice, Text and FilePath, null for "unset" (a parameter whose default is null means "not
// given": the scene's gaze, every projector wavelength ...; `unset_meaning` says which).

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fovea::analysis {

// The widest gaze the studies accept (deg, yaw or pitch): beyond any eye rotation (about
// +-50 deg) with a margin, short of 90 deg where the line of sight leaves the front of the eye.
inline constexpr double kGazeLimitDeg = 80.0;
// The most gaze samples one sweep may take (each is a few dozen traces).
inline constexpr int kMaxGazeSamples = 2000;

// FilePath: the path of an input file (a tolerance spec); the validator checks that it names
// a readable regular file, so a wrong path is refused before any work.
enum class ParameterKind { Number, Integer, Choice, Text, FilePath };

// clang-tidy's bugprone-exception-escape flags the implicit destructor through
// nlohmann::json's destructor (its invariant assertion), which does not throw.
struct ParameterSpec {  // NOLINT(bugprone-exception-escape)
  std::string name;     // fovea-cli flag without the dashes and the studio's key: "gaze-step"
  std::string label;
  std::string unit;  // "deg", "mm", "nm", "" for none
  ParameterKind kind = ParameterKind::Number;
  nlohmann::json default_value;  // number, string, or null (unset; see unset_meaning)
  double minimum = -std::numeric_limits<double>::max(), maximum = std::numeric_limits<double>::max();
  bool minimum_exclusive = false;    // "> minimum" instead of ">= minimum"
  int decimals = 3;                  // display precision in the studio form
  std::vector<std::string> choices;  // Choice: the allowed values; Text: suggestions
  std::string help;
  std::string unset_meaning;  // for a null default: what "not given" means ("the scene's gaze")
  bool studio_only = false;   // not an option of the fovea-cli twin (a studio sweep over it)
};

// Declaration helpers (one line per parameter in the definitions).
ParameterSpec number(std::string name, std::string label, std::string unit, nlohmann::json default_value,
                     double minimum, double maximum, int decimals, std::string help);
ParameterSpec positive(std::string name, std::string label, std::string unit, nlohmann::json default_value,
                       double maximum, int decimals, std::string help);  // (0, maximum]
ParameterSpec integer(std::string name, std::string label, int default_value, int minimum, int maximum,
                      std::string help);
ParameterSpec choice(std::string name, std::string label, std::vector<std::string> choices, std::string default_value,
                     std::string help);
ParameterSpec text(std::string name, std::string label, std::vector<std::string> suggestions, std::string default_value,
                   std::string help);
// An input file, unset by default (`unset_meaning`: what is read instead).
ParameterSpec filePath(std::string name, std::string label, std::string unset_meaning, std::string help);
// A gaze angle in [-kGazeLimitDeg, kGazeLimitDeg].
ParameterSpec gazeAngle(std::string name, std::string label, nlohmann::json default_value, std::string help);

// "must lie in [-80, 80] deg" / "must be > 0 mm": the range in words.
std::string rangeText(const ParameterSpec& spec);

// THE validator. Checks one value against its spec (finite, in range, whole for Integer,
// a listed choice, non-empty text) and normalises it in place (Integer -> integer JSON,
// Text trimmed). Returns the problem without the parameter's name ("must be a finite
// number, got nan"), or nothing when the value is valid. Null is valid only when the
// default is null.
std::optional<std::string> validateValue(const ParameterSpec& spec, nlohmann::json& value);

// Parses the text of a command-line value for `spec` (numbers strictly: "1e3", "nan" and
// "inf" are parsed and then refused by validateValue). Returns the problem on failure.
std::optional<std::string> parseValueText(const ParameterSpec& spec, const std::string& text, nlohmann::json& value);

struct ParameterProblem {
  std::string parameter;  // the name ("gaze-step"); empty for a problem of the whole set
  std::string message;    // "must be > 0 deg, got 0"
  std::string text(const std::string& prefix = "") const;  // "--gaze-step: must be > 0 deg, got 0"
};

// Readers for validated values (never called on unvalidated ones).
double numberOf(const nlohmann::json& values, const std::string& name);
std::optional<double> optionalNumberOf(const nlohmann::json& values, const std::string& name);
int integerOf(const nlohmann::json& values, const std::string& name);
std::string textOf(const nlohmann::json& values, const std::string& name);

// A gaze sweep's range from..to by step: to >= from and at most kMaxGazeSamples samples
// (refused above, before any work). Parameter names "gaze-from", "gaze-to", "gaze-step".
std::optional<ParameterProblem> checkGazeRange(const nlohmann::json& values);

}  // namespace fovea::analysis
