#include "model/io/json_fields.h"

#include <algorithm>
#include <cmath>

#include "model/scene/scene_io.h"  // formatNumber

namespace fovea {

std::string jsonTypeName(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::array:
      return "an array of " + std::to_string(v.size());
    case nlohmann::json::value_t::object:
      return "an object";
    default:
      return "a number (" + v.dump() + ")";
  }
}

namespace {

[[noreturn]] void raise(const std::string& source, const std::string& path, const std::string& problem) {
  // An empty source: the caller names the file ("PATH: problem").
  throw JsonFieldError((source.empty() ? "" : source + ": ") + (path.empty() ? "" : path + ": ") + problem);
}

std::string integerRange(long long lo, long long hi) {
  return "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

}  // namespace

double jsonNumber(const nlohmann::json& v, const Range& range, const std::string& source, const std::string& path) {
  if (!v.is_number()) raise(source, path, "must be a number, got " + jsonTypeName(v));
  const double d = v.get<double>();
  if (const std::string p = range.check(d); !p.empty()) raise(source, path, p);
  return d;
}

long long jsonInteger(const nlohmann::json& v, long long lo, long long hi, const std::string& source,
                      const std::string& path) {
  // The exact JSON value: an unsigned one above LLONG_MAX, a float (9.9, 1e23) are never
  // converted (get<long long>() would wrap or truncate them).
  if (v.is_number_unsigned()) {
    const std::uint64_t u = v.get<std::uint64_t>();
    if (hi < 0 || u > static_cast<std::uint64_t>(hi) || (lo > 0 && u < static_cast<std::uint64_t>(lo)))
      raise(source, path, "must be " + integerRange(lo, hi) + ", got " + std::to_string(u));
    return static_cast<long long>(u);
  }
  if (v.is_number_integer()) {
    const long long i = v.get<long long>();
    if (i < lo || i > hi) raise(source, path, "must be " + integerRange(lo, hi) + ", got " + std::to_string(i));
    return i;
  }
  if (v.is_number()) raise(source, path, "must be " + integerRange(lo, hi) + ", got " + formatNumber(v.get<double>()));
  raise(source, path, "must be " + integerRange(lo, hi) + ", got " + jsonTypeName(v));
}

JsonFields::JsonFields(const nlohmann::json& object, std::string source, std::string path)
    : JsonFields(object, std::move(source), std::move(path), std::make_shared<Ledger>()) {}

JsonFields::JsonFields(const nlohmann::json& object, std::string source, std::string path,
                       std::shared_ptr<Ledger> ledger)
    : obj_(object), source_(std::move(source)), path_(std::move(path)), ledger_(std::move(ledger)) {
  if (!obj_.is_object()) raise(source_, path_, "must be an object, got " + jsonTypeName(obj_));
  entry_ = ledger_->objects.size();
  ledger_->objects.emplace_back(&obj_, path_);
  ledger_->asked.emplace_back();
}

void JsonFields::ask(const std::string& key) const {
  ledger_->asked[entry_].insert(key);
}

void JsonFields::known(const std::vector<std::string>& keys) const {
  for (const auto& k : keys) ask(k);
}

void JsonFields::rejectUnknownKeys() const {
  for (std::size_t e = 0; e < ledger_->objects.size(); ++e) {
    const auto& [object, path] = ledger_->objects[e];
    const std::set<std::string>& asked = ledger_->asked[e];
    for (const auto& item : object->items()) {
      if (asked.count(item.key())) continue;
      std::string list;
      for (const auto& k : asked) list += (list.empty() ? "" : ", ") + k;
      raise(source_, path.empty() ? item.key() : path + "." + item.key(),
            "not a field of this entry" + (list.empty() ? std::string() : " (it reads " + list + ")"));
    }
  }
}

std::string JsonFields::at(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}
std::string JsonFields::at(std::size_t index) const {
  return path_ + "[" + std::to_string(index) + "]";
}
void JsonFields::fail(const std::string& path, const std::string& problem) const {
  raise(source_, path, problem);
}

const nlohmann::json* JsonFields::get(const std::string& key, bool required) const {
  ask(key);
  const auto it = obj_.find(key);
  if (it == obj_.end()) {
    if (required) raise(source_, at(key), "missing required field");
    return nullptr;
  }
  return &*it;
}

double JsonFields::number(const std::string& key, const Range& range, std::optional<double> fallback) const {
  const nlohmann::json* v = get(key, !fallback);
  return v ? jsonNumber(*v, range, source_, at(key)) : *fallback;
}

long long JsonFields::integer(const std::string& key, long long lo, long long hi,
                              std::optional<long long> fallback) const {
  const nlohmann::json* v = get(key, !fallback);
  return v ? jsonInteger(*v, lo, hi, source_, at(key)) : *fallback;
}

std::uint64_t JsonFields::unsignedInteger(const std::string& key, std::uint64_t hi,
                                          std::optional<std::uint64_t> fallback) const {
  const nlohmann::json* v = get(key, !fallback);
  if (!v) return *fallback;
  const std::string range = "an integer in [0, " + std::to_string(hi) + "]";
  if (v->is_number_unsigned() && v->get<std::uint64_t>() <= hi) return v->get<std::uint64_t>();
  if (v->is_number_unsigned()) raise(source_, at(key), "must be " + range + ", got " + v->dump());
  if (v->is_number_integer()) raise(source_, at(key), "must be " + range + ", got " + v->dump());
  if (v->is_number()) raise(source_, at(key), "must be " + range + ", got " + formatNumber(v->get<double>()));
  raise(source_, at(key), "must be " + range + ", got " + jsonTypeName(*v));
}

bool JsonFields::boolean(const std::string& key, std::optional<bool> fallback) const {
  const nlohmann::json* v = get(key, !fallback);
  if (!v) return *fallback;
  if (!v->is_boolean()) raise(source_, at(key), "must be true or false, got " + jsonTypeName(*v));
  return v->get<bool>();
}

std::string JsonFields::text(const std::string& key, const std::vector<std::string>& choices,
                             std::optional<std::string> fallback, bool non_empty) const {
  const nlohmann::json* v = get(key, !fallback);
  if (!v) return *fallback;
  if (!v->is_string()) raise(source_, at(key), "must be a string, got " + jsonTypeName(*v));
  std::string s = v->get<std::string>();
  if (non_empty && s.empty()) raise(source_, at(key), "must not be empty");
  if (!choices.empty() && std::find(choices.begin(), choices.end(), s) == choices.end()) {
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    raise(source_, at(key), "must be one of " + list + ", got \"" + s + "\"");
  }
  return s;
}

std::vector<double> JsonFields::numbers(const std::string& key, const Range& range, std::size_t size,
                                        std::size_t max_size) const {
  const nlohmann::json* v = get(key, true);
  const std::string what = size ? "an array of " + std::to_string(size) + " numbers" : "a non-empty array of numbers";
  if (!v->is_array() || (size ? v->size() != size : (v->empty() || v->size() > max_size)))
    raise(source_, at(key), "must be " + what + ", got " + jsonTypeName(*v));
  std::vector<double> out;
  out.reserve(v->size());
  for (std::size_t i = 0; i < v->size(); ++i)
    out.push_back(jsonNumber((*v)[i], range, source_, at(key) + "[" + std::to_string(i) + "]"));
  return out;
}

std::optional<JsonFields> JsonFields::object(const std::string& key, bool required) const {
  const nlohmann::json* v = get(key, required);
  if (!v) return std::nullopt;
  return JsonFields(*v, source_, at(key), ledger_);
}

std::vector<JsonFields> JsonFields::objects(const std::string& key, bool required, std::size_t max_size) const {
  const nlohmann::json* v = get(key, required);
  std::vector<JsonFields> out;
  if (!v) return out;
  if (!v->is_array()) raise(source_, at(key), "must be an array, got " + jsonTypeName(*v));
  if (v->size() > max_size)
    raise(source_, at(key),
          "must hold at most " + std::to_string(max_size) + " elements, got " + std::to_string(v->size()));
  out.reserve(v->size());
  for (std::size_t i = 0; i < v->size(); ++i)
    out.push_back(JsonFields((*v)[i], source_, at(key) + "[" + std::to_string(i) + "]", ledger_));
  return out;
}

}  // namespace fovea
