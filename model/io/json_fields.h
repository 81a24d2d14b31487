#pragma once
// Typed, range-checked reading of the JSON inputs that are not scenes (tolerance specs, shard
// parts, fit targets, capture manifests, colour measurements) with the scene file's machinery:
// the same Range notation and checks (model/scene/scene_fields.h), the same type names and the
// same message form as the scene loader,
//   SOURCE: json.path: problem           e.g. spec.json: optimiser.edge_bisections: must be in [0, 20], got 4294967299
// Integers are integers (9.9 is not 9) within their range, checked on the exact JSON value (no
// wrap through a narrower type: 4294967299 is not 3, 2^64 - 1 is not -1). A reader throws
// JsonFieldError at the first problem; nlohmann's own exception text never reaches a user.

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/scene/scene_fields.h"  // Range

namespace fovea {

class JsonFieldError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// "a number", "a string", "an array", "an object", "true or false", "null" (as the scene loader says).
std::string jsonTypeName(const nlohmann::json& v);

// One JSON object of an input, at `path` ("" for the document) of `source` (a file name).
class JsonFields {
 public:
  JsonFields(const nlohmann::json& object, std::string source, std::string path = {});

  const nlohmann::json& value() const { return obj_; }
  bool has(const std::string& key) const {
    ask(key);
    return obj_.is_object() && obj_.contains(key);
  }
  // "path.key" (or "key" at the top), and "path[i]".
  std::string at(const std::string& key) const;
  std::string at(std::size_t index) const;
  // Throws JsonFieldError "SOURCE: PATH: problem" (PATH empty: "SOURCE: problem").
  [[noreturn]] void fail(const std::string& path, const std::string& problem) const;

  // A finite number in `range`; absent: `fallback`, or "missing required field" without one.
  double number(const std::string& key, const Range& range, std::optional<double> fallback = std::nullopt) const;
  // An integer (no fraction, no exponent form beyond the exact value) in [lo, hi].
  long long integer(const std::string& key, long long lo, long long hi,
                    std::optional<long long> fallback = std::nullopt) const;
  // An integer in [0, hi] on the full unsigned 64-bit range (seeds, counts).
  std::uint64_t unsignedInteger(const std::string& key, std::uint64_t hi = UINT64_MAX,
                                std::optional<std::uint64_t> fallback = std::nullopt) const;
  bool boolean(const std::string& key, std::optional<bool> fallback = std::nullopt) const;
  // A string, one of `choices` when given; a non-empty one when `non_empty`.
  std::string text(const std::string& key, const std::vector<std::string>& choices = {},
                   std::optional<std::string> fallback = std::nullopt, bool non_empty = false) const;
  // Numbers of an array at key, each in `range`; `size` 0: any non-empty length up to max_size.
  std::vector<double> numbers(const std::string& key, const Range& range, std::size_t size = 0,
                              std::size_t max_size = 100000) const;
  // A nested object (nullopt when absent and not required).
  std::optional<JsonFields> object(const std::string& key, bool required = false) const;
  // An array's elements as readers (each must be an object); `max_size` bounds its length.
  std::vector<JsonFields> objects(const std::string& key, bool required = true, std::size_t max_size = 100000) const;
  // The raw value at key (checked to be present when required), or nullptr.
  const nlohmann::json* get(const std::string& key, bool required) const;
  // Keys a reader takes as they are without a typed accessor (free text such as "notes", an
  // object read by its own parser).
  void known(const std::vector<std::string>& keys) const;

  // Refuses a key that no accessor asked for, in this object and in every object reached
  // through object()/objects() from it: "SOURCE: gaze.from: not a field of this entry (it
  // reads axis, from_deg, step_deg, to_deg)"; a key this entry does not use in its mode (a
  // half_width beside a normal distribution) is refused the same way. A misspelt key is otherwise silently replaced by
  // its default, and the study answers another question (issue 28: the scene file names its unknown keys; the other
  // inputs must not be quieter). Call it after reading everything.
  void rejectUnknownKeys() const;

 private:
  // What the readers of one document asked for: per object reached, its path and its keys.
  struct Ledger {
    std::vector<std::pair<const nlohmann::json*, std::string>> objects;
    std::vector<std::set<std::string>> asked;
  };
  JsonFields(const nlohmann::json& object, std::string source, std::string path, std::shared_ptr<Ledger> ledger);
  void ask(const std::string& key) const;

  const nlohmann::json& obj_;
  std::string source_, path_;
  std::shared_ptr<Ledger> ledger_;
  std::size_t entry_ = 0;  // this object's index in the ledger
};

// The same checks on one value (an array element, a whole document) at `path` of `source`.
double jsonNumber(const nlohmann::json& v, const Range& range, const std::string& source, const std::string& path);
long long jsonInteger(const nlohmann::json& v, long long lo, long long hi, const std::string& source,
                      const std::string& path);

}  // namespace fovea
