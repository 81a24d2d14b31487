#pragma once
// Reading numbers out of result documents (the fovea-cli --json output the studio's summaries,
// plots and reports show) where a value may be absent: NaN stands for "not there", so a
// missing key prints as a dash instead of throwing. And the writing side: the analyses' JSON
// writers put null where a number is absent or not finite, which the readers take back as NaN.
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

namespace fovea {

// The number at the end of a key path through nested objects, e.g. {"fov_deg", "horizontal"};
// NaN when a key is missing, a level is not an object or the value is not a number (null too).
double jsonNumber(const nlohmann::json& j, std::initializer_list<std::string_view> path);
// Element i of the array j[key] as a number; NaN when absent, too short or not a number.
double jsonNumberAt(const nlohmann::json& j, std::string_view key, std::size_t i);

// v, or null when v is NaN or infinite. (Serialised, nlohmann writes a non-finite number as
// null anyway; this makes the value null in the document too, so is_null() agrees with the text.)
nlohmann::json numberOrNull(double v);
// *v as numberOrNull does, or null when there is no value.
nlohmann::json optionalNumber(const std::optional<double>& v);

}  // namespace fovea
