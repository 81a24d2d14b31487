#pragma once
#include <string_view>

namespace fovea {
// The default prototype scene (resources/scenes/prototype-bench.json), compiled in so
// that the studio and fovea-cli open it with no file on disk.
std::string_view embeddedDefaultSceneJson();
// The name shown for the embedded scene in titles and messages.
inline constexpr std::string_view kEmbeddedSceneName = "prototype-bench.json (embedded)";
}  // namespace fovea
