#include "app/cli/preview_json_io.h"

#include <fstream>
#include <sstream>

#include "app/cli/cli_common.h"

namespace fovea::cli {
nlohmann::json readJsonFileOrExit(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path + ": cannot open the file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  try {
    return nlohmann::json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    inputError(path + ": not valid JSON: " + e.what());
  }
}
}  // namespace fovea::cli
