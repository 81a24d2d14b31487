#include "model/json_numbers.h"

#include <cmath>
#include <limits>

namespace fovea {

namespace {
constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
const nlohmann::json* member(const nlohmann::json& j, std::string_view key) {
  if (!j.is_object()) return nullptr;
  const auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}
}  // namespace

double jsonNumber(const nlohmann::json& j, std::initializer_list<std::string_view> path) {
  const nlohmann::json* p = &j;
  for (std::string_view k : path)
    if (!(p = member(*p, k))) return kMissing;
  return p->is_number() ? p->get<double>() : kMissing;
}

double jsonNumberAt(const nlohmann::json& j, std::string_view key, std::size_t i) {
  const nlohmann::json* a = member(j, key);
  if (!a || !a->is_array() || a->size() <= i) return kMissing;
  const auto& v = (*a)[i];
  return v.is_number() ? v.get<double>() : kMissing;
}

nlohmann::json numberOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json optionalNumber(const std::optional<double>& v) {
  return v ? numberOrNull(*v) : nlohmann::json(nullptr);
}

}  // namespace fovea
