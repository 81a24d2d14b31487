#include "model/io/save_temporaries.h"

#include "model/io/output_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace fovea {

namespace fs = std::filesystem;

namespace {
std::string temporaryPrefix(const fs::path& target) {
  return "." + target.filename().string() + ".tmp-";
}
}  // namespace

std::string saveTemporaryTemplate(const fs::path& target) {
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  return (dir / (temporaryPrefix(target) + "XXXXXX")).string();
}

fs::path saveTarget(const fs::path& path) {
  fs::path p = path;
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {  // 40 = Linux MAXSYMLINKS
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) break;
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  return p;
}

std::vector<fs::path> removeStaleSaveTemporaries(const fs::path& target_path) {
  const fs::path target = saveTarget(target_path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = temporaryPrefix(target);
  std::vector<fs::path> removed;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    // mkstemp's suffix: exactly six characters after the prefix.
    if (name.size() != prefix.size() + 6 || name.compare(0, prefix.size(), prefix) != 0) continue;
    std::error_code sec;
    if (!fs::is_regular_file(it->symlink_status(sec))) continue;
    const int fd = ::open(it->path().c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) continue;
    const bool unlocked = ::flock(fd, LOCK_EX | LOCK_NB) == 0;  // a live save holds LOCK_EX
    if (unlocked && ::unlink(it->path().c_str()) == 0) removed.push_back(it->path());
    ::close(fd);
  }
  return removed;
}

std::optional<std::string> cannotWriteFile(const fs::path& path) {
  if (auto p = outputPathProblem(path)) return p;  // empty, a directory, a device, a FIFO...
  const fs::path target = saveTarget(path);
  std::error_code ec;
  std::string tmpl = saveTemporaryTemplate(target);
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0)
    return std::string(std::strerror(errno)) + " (creating a file in '" + fs::path(tmpl).parent_path().string() + "')";
  ::close(fd);
  ::unlink(tmpl.c_str());
  if (fs::exists(target, ec) && ::access(target.c_str(), W_OK) != 0) return std::strerror(errno);
  return std::nullopt;
}

}  // namespace fovea
