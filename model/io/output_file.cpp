#include "model/io/output_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "model/io/save_temporaries.h"

namespace fovea {

namespace fs = std::filesystem;

namespace {

// What a non-regular file is, in words.
const char* kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string problemOfExisting(const fs::path& target) {
  struct stat st {};
  if (::stat(target.c_str(), &st) != 0) return {};  // absent (or a dangling link): created
  if (S_ISREG(st.st_mode)) return {};
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  return std::string("is ") + kindOf(st.st_mode) + ", not a regular file (refusing to replace it)";
}

}  // namespace

std::optional<std::string> outputPathProblem(const fs::path& path) {
  if (path.empty()) return "an empty path names no file";
  const std::string p = problemOfExisting(saveTarget(path));
  if (!p.empty()) return p;
  return std::nullopt;
}

void writeOutputFile(const fs::path& path, std::string_view text, const std::function<void()>& beforeRename) {
  if (path.empty()) throw OutputError("an empty path names no file");
  const fs::path target = saveTarget(path);  // through symlinks: replace the link's target, not the link
  if (const std::string p = problemOfExisting(target); !p.empty()) throw OutputError(path.string() + ": " + p);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string name = saveTemporaryTemplate(target);
  const int fd = ::mkstemp(name.data());
  if (fd < 0)
    throw OutputError(path.string() + ": cannot create a temporary file in " + dir.string() + ": " +
                      std::strerror(errno));
  // Held until after the rename (close() drops it): an unlocked temporary file is an
  // interrupted save's leftover to the next reader (removeStaleSaveTemporaries).
  ::flock(fd, LOCK_EX);
  const std::string tmp = name;
  auto fail = [&](const std::string& why) {
    ::unlink(tmp.c_str());
    ::close(fd);
    throw OutputError(path.string() + ": save failed (" + why + "); the existing file is unchanged");
  };
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(std::string("write: ") + std::strerror(errno));
    }
    if (n == 0) fail("write: no progress");
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail(std::string("fsync: ") + std::strerror(errno));
  // Keep the target's permissions when replacing it (mkstemp creates 0600).
  struct stat st {};
  const bool exists = ::stat(target.c_str(), &st) == 0;
  if (::fchmod(fd, exists ? (st.st_mode & 07777) : 0644) != 0) fail(std::string("fchmod: ") + std::strerror(errno));
  try {
    if (beforeRename) beforeRename();
  } catch (...) {
    ::unlink(tmp.c_str());
    ::close(fd);
    throw;
  }
  // The target may have become a device or a FIFO meanwhile: rename(2) would replace it.
  if (const std::string p = problemOfExisting(target); !p.empty()) fail(p);
  if (::rename(tmp.c_str(), target.c_str()) != 0) fail(std::string("rename: ") + std::strerror(errno));
  if (::close(fd) != 0) throw OutputError(path.string() + ": save failed (close: " + std::strerror(errno) + ")");
  // The rename itself is durable once the directory is (best effort: not every file system
  // lets a directory be opened for fsync).
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

std::optional<std::string> sameOutputTwice(const std::vector<std::pair<std::string, std::string>>& outputs) {
  auto key = [](const std::string& p) {
    std::error_code ec;
    const fs::path t = saveTarget(p);
    const fs::path abs = fs::weakly_canonical(fs::absolute(t, ec), ec);
    return abs.empty() ? t.lexically_normal().string() : abs.string();
  };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].second.empty()) continue;
    for (std::size_t j = i + 1; j < outputs.size(); ++j) {
      if (outputs[j].second.empty()) continue;
      bool same = key(outputs[i].second) == key(outputs[j].second);
      struct stat a {
      }, b{};
      if (!same && ::stat(outputs[i].second.c_str(), &a) == 0 && ::stat(outputs[j].second.c_str(), &b) == 0)
        same = a.st_dev == b.st_dev && a.st_ino == b.st_ino;
      if (same)
        return outputs[i].first + " and " + outputs[j].first + " name the same file (" + outputs[j].second +
               "): each output needs its own file";
    }
  }
  return std::nullopt;
}

std::optional<std::string> checkStdout() {
  errno = 0;
  std::cout.flush();
  const bool cpp_failed = !std::cout.good();
  const int cpp_errno = errno;
  errno = 0;
  const bool c_failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  const int c_errno = errno;
  if (!cpp_failed && !c_failed) return std::nullopt;
  const int e = c_errno ? c_errno : cpp_errno;
  return std::string("stdout: write failed: ") + (e ? std::strerror(e) : "output error");
}

}  // namespace fovea
