#pragma once
// Reading, validating and writing scene files (docs/scene-format.md).
//
// Every problem is reported as "<source>: <json path>: <problem>", for example
//   bench.json: hoe_layers[1].thickness_um: must be > 0, got -5
// and a scene is returned only when there is no error at all: nothing is half-loaded.

#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "model/scene/scene.h"

namespace fovea {

struct SceneLoadResult {
  std::optional<Scene> scene;         // set only when errors is empty
  std::vector<std::string> errors;    // every problem found, one message each
  std::vector<std::string> warnings;  // e.g. unknown keys (kept, not dropped)
  bool ok() const { return scene.has_value(); }
};

class SceneIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses scene JSON text; `source` names it in messages (usually the file name).
SceneLoadResult parseScene(std::string_view text, const std::string& source);
// Reads and parses a file; an unreadable file is one error naming the file and the reason.
SceneLoadResult loadSceneFile(const std::filesystem::path& path);

// Semantic checks of an in-memory scene (finite numbers, ranges, consistency): the same
// rules the loader applies, as "<json path>: <problem>" messages. Empty when valid.
std::vector<std::string> validateScene(const Scene& scene);

// Canonical text: fixed key order, 2-space indent, unknown keys last in their object,
// trailing newline. parseScene(serializeScene(s)) == s, and a canonical file survives
// load -> save byte for byte.
std::string serializeScene(const Scene& scene);

// Writes atomically: a temporary file beside the target, flushed and fsync'ed, then
// renamed over it. On any failure the existing file is untouched and SceneIoError says
// why. `beforeRename` is a test hook called after the temporary file is complete.
void saveSceneFileAtomic(const Scene& scene, const std::filesystem::path& path,
                         const std::function<void()>& beforeRename = {});

// Writes `text` atomically to `path` (the mechanism behind saveSceneFileAtomic).
void writeFileAtomic(const std::filesystem::path& path, std::string_view text,
                     const std::function<void()>& beforeRename = {});

// A short human summary: "Optical bench prototype: 3 HOE layers (660/532/460 nm), ...".
std::string sceneSummary(const Scene& scene);

// Shortest text that reads back as the same double ("-5", "0.1", "1e-09").
std::string formatNumber(double value);

}  // namespace fovea
