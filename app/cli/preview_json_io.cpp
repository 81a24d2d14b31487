#include "app/cli/preview_json_io.h"

#include "app/cli/cli_common.h"
#include "model/io/json_input.h"

namespace fovea::cli {
nlohmann::json readJsonFileOrExit(const std::string& path) {
  auto text = readInputFile(path);
  if (const auto* reason = std::get_if<1>(&text)) inputError(path + ": cannot read the file: " + *reason);
  auto parsed = parseJsonText(std::get<0>(text));
  if (const auto* e = std::get_if<JsonInputError>(&parsed)) inputError(describe(*e, path));
  return std::get<nlohmann::json>(std::move(parsed));
}
}  // namespace fovea::cli
