#pragma once
#include <string_view>

#include "model/scene/scene.h"

namespace fovea {
// The default prototype scene (resources/scenes/prototype-bench.json), compiled in so
// that the studio and fovea-cli open it with no file on disk.
std::string_view embeddedDefaultSceneJson();
// The name shown for the embedded scene in titles and messages.
inline constexpr std::string_view kEmbeddedSceneName = "prototype-bench.json (embedded)";
// The embedded scene parsed: the one loader of the prototype bench for the tests, the
// benchmarks and the tools. Throws std::runtime_error naming the scene and its first error
// if it does not load (a build whose resource is broken); the studio and fovea-cli parse
// embeddedDefaultSceneJson themselves, to report through their own channels.
Scene embeddedDefaultScene();
}  // namespace fovea
