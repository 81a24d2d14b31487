// fovea-cli format SCENE [--in-place]: rewrite a scene in canonical form (key order,
// indentation, unknown keys kept). Prints to stdout, or replaces the file atomically (through a
// symlink: the link's target is replaced, the link stays).
//
// The canonical form is bounded: the reader refuses nesting deeper than 64 levels, and a
// canonical text more than kMaxGrowth times the input (+ 64 KiB) is refused before anything
// is written (2-space indentation grows with the depth; a normal scene grows by less than 3).
#include <cstddef>
#include <filesystem>
#include <iostream>

#include "app/cli/cli_common.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace cmd_format {  // one per command file: fovea-cli compiles in unity batches
namespace {

constexpr std::size_t kMaxGrowth = 16;

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("format", "Rewrite a scene file in canonical form");
  auto path = std::make_shared<std::string>();
  auto inPlace = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file")->required();
  cmd->add_flag("--in-place,-i", *inPlace, "replace the file (atomically) instead of printing");
  cmd->callback([path, inPlace] {
    const Scene scene = loadSceneOrExit(*path);
    const std::string text = serializeScene(scene);
    std::error_code ec;
    const auto input_bytes = std::filesystem::file_size(*path, ec);
    if (!ec && text.size() > kMaxGrowth * input_bytes + (64u << 10))
      inputError(*path + ": the canonical form would be " + std::to_string(text.size()) + " bytes, more than " +
                 std::to_string(kMaxGrowth) + " times the file's " + std::to_string(input_bytes) +
                 " bytes: refused (deeply nested notes?)");
    if (!*inPlace) {
      printText(text);
      return;
    }
    try {
      writeFileAtomic(*path, text);
    } catch (const SceneIoError& e) {
      inputError(e.what());
    }
  });
}

const Registrar reg{"format", &install};

}  // namespace
}  // namespace cmd_format
}  // namespace fovea::cli
