#pragma once
// The one writer of every output file (scenes, fit results, calibrations, Slurm scripts, stage
// traces and transcripts): docs/inputs-outputs.md.
//   - the path must not be empty, and an existing target (after following symlinks) must be a
//     regular file: a device node, a FIFO, a socket or a directory is refused, never replaced;
//   - the text goes to a temporary file beside the target (save_temporaries.h), written with
//     every write(2) checked, fsync'ed, given the target's permissions, then renamed over the
//     target; the temporary file stays locked (flock) until the rename is done, so a
//     concurrent reader that clears interrupted saves' leftovers never deletes it;
//   - on any failure the existing file is unchanged and OutputError says
//     "PATH: save failed (STEP: strerror); the existing file is unchanged".
// Standard output is checked by checkStdout() (fovea-cli calls it before exiting).

#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fovea {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Why `path` cannot be an output file, or nothing: "an empty path names no file", "is a
// directory, not a file", "is a FIFO, not a regular file (refusing to replace it)", ... Checks
// the path only (no file is created); writeOutputFile() applies the same checks.
std::optional<std::string> outputPathProblem(const std::filesystem::path& path);

// Writes `text` atomically to `path` as described above. `beforeRename` is a test hook called
// once the temporary file is complete and still locked. Throws OutputError.
void writeOutputFile(const std::filesystem::path& path, std::string_view text,
                     const std::function<void()>& beforeRename = {});

// The same file named twice among the outputs of one command line ({option, path} pairs; empty
// paths are skipped): "--trace and --transcript name the same file (PATH)", else nothing.
// Paths are compared after following symlinks and by device and inode when the file exists.
std::optional<std::string> sameOutputTwice(const std::vector<std::pair<std::string, std::string>>& outputs);

// Flushes stdout (C and C++ streams) and reports a failed write: "stdout: write failed: No space
// left on device" (e.g. `> /dev/full`), else nothing.
std::optional<std::string> checkStdout();

}  // namespace fovea
