#pragma once
// Reading numbers out of result documents (the fovea-cli --json output the studio's summaries,
// plots and reports show) where a value may be absent: NaN stands for "not there", so a
// missing key prints as a dash instead of throwing.
#include <cstddef>
#include <initializer_list>
#include <string_view>

#include <nlohmann/json.hpp>

namespace fovea {

// The number at the end of a key path through nested objects, e.g. {"fov_deg", "horizontal"};
// NaN when a key is missing, a level is not an object or the value is not a number (null too).
double jsonNumber(const nlohmann::json& j, std::initializer_list<std::string_view> path);
// Element i of the array j[key] as a number; NaN when absent, too short or not a number.
double jsonNumberAt(const nlohmann::json& j, std::string_view key, std::size_t i);

}  // namespace fovea
