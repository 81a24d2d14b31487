#pragma once
// Reading JSON input files for the preview/calibration commands: exit 1 naming the file
// and what is wrong with it.
#include <string>

#include <nlohmann/json.hpp>

namespace fovea::cli {
nlohmann::json readJsonFileOrExit(const std::string& path);
}
