#pragma once
// The temporary files of an atomic save (write beside the target, fsync, rename over it) and
// the ones a killed save leaves behind. A save holds an exclusive flock(2) on its temporary
// file until it is renamed; the kernel drops the lock when the process dies, so a temporary
// file nobody holds locked is a leftover, whatever its age — a save in progress in another
// process is never touched.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fovea {

// mkstemp(3) template of the temporary file for `target`: "<dir>/.<name>.tmp-XXXXXX".
std::string saveTemporaryTemplate(const std::filesystem::path& target);

// The file a save to `path` really writes: `path` with its symlinks followed (a dangling link
// gives the file it points to), so that saving through a link replaces the link's target.
std::filesystem::path saveTarget(const std::filesystem::path& path);

// Removes the unlocked temporary files of `target` (after following its symlinks) and returns
// their names; nothing when the directory cannot be listed.
std::vector<std::filesystem::path> removeStaleSaveTemporaries(const std::filesystem::path& target);

// Why `path` cannot be written (by an atomic save or in place), or nothing: checked before any
// work by creating and removing a temporary file beside it ("is a directory", "No such file or
// directory", "Permission denied", …).
std::optional<std::string> cannotWriteFile(const std::filesystem::path& path);

}  // namespace fovea
