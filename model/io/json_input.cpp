#include "model/io/json_input.h"

#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace fovea {

namespace {

std::pair<int, int> lineColumn(std::string_view text, std::size_t byte) {
  int line = 1, col = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

JsonInputError errorAt(std::string_view text, std::size_t byte, std::string reason, bool malformed = false) {
  JsonInputError e;
  e.byte = byte;
  std::tie(e.line, e.column) = lineColumn(text, byte);
  e.reason = std::move(reason);
  e.malformed = malformed;
  return e;
}

// Length of the well-formed UTF-8 sequence starting at t[i] (RFC 3629 Table 3-7), 0 if none.
std::size_t utf8Length(std::string_view t, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(t[k]); };
  const unsigned c = b(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned lo = 0x80, hi = 0xBF;
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;  // overlong
    if (c == 0xED) hi = 0x9F;  // UTF-16 surrogates
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;  // overlong
    if (c == 0xF4) hi = 0x8F;  // above U+10FFFF
  } else {
    return 0;
  }
  if (i + n > t.size() || b(i + 1) < lo || b(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if ((b(i + k) & 0xC0) != 0x80) return 0;
  return n;
}

void appendUtf8(std::string& out, unsigned cp) {
  if (cp < 0x80) {
    out += char(cp);
  } else if (cp < 0x800) {
    out += char(0xC0 | (cp >> 6));
    out += char(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += char(0xE0 | (cp >> 12));
    out += char(0x80 | ((cp >> 6) & 0x3F));
    out += char(0x80 | (cp & 0x3F));
  } else {
    out += char(0xF0 | (cp >> 18));
    out += char(0x80 | ((cp >> 12) & 0x3F));
    out += char(0x80 | ((cp >> 6) & 0x3F));
    out += char(0x80 | (cp & 0x3F));
  }
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Four hex digits at t[i..i+4), or -1.
long hex4(std::string_view t, std::size_t i) {
  if (i + 4 > t.size()) return -1;
  long v = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    const int h = hexValue(t[i + k]);
    if (h < 0) return -1;
    v = v * 16 + h;
  }
  return v;
}

struct ScanFrame {
  bool object = false;
  bool expect_key = false;
  std::unordered_map<std::string, std::size_t> keys;  // decoded key -> byte of its opening quote
};

// The scan proper. Syntax errors are left to nlohmann (the scan only has to be right on valid
// JSON); a duplicate key is kept in `duplicate` so that an earlier syntax error wins.
std::variant<std::monostate, JsonInputError> scan(std::string_view t, const JsonLimits& limits,
                                                  std::optional<JsonInputError>& duplicate) {
  if (t.size() > limits.max_bytes)
    return errorAt(
        t, 0, "too large: " + std::to_string(t.size()) + " bytes (limit " + std::to_string(limits.max_bytes) + ")");
  std::vector<ScanFrame> stack;
  const auto utf8Error = [&](std::size_t i) {
    return errorAt(t, i, "invalid UTF-8 at byte offset " + std::to_string(i));
  };
  for (std::size_t i = 0; i < t.size(); ++i) {
    const char c = t[i];
    if (static_cast<unsigned char>(c) >= 0x80) {  // outside a string: a syntax error, unless it is not even UTF-8
      const std::size_t n = utf8Length(t, i);
      if (n == 0) return utf8Error(i);
      i += n - 1;
      continue;
    }
    switch (c) {
      case '{':
      case '[':
        if (stack.size() >= limits.max_depth)
          return errorAt(t, i, "nesting deeper than " + std::to_string(limits.max_depth));
        stack.push_back({c == '{', c == '{', {}});
        break;
      case '}':
      case ']':
        if (!stack.empty()) stack.pop_back();
        break;
      case ',':
        if (!stack.empty() && stack.back().object) stack.back().expect_key = true;
        break;
      case ':':
        if (!stack.empty()) stack.back().expect_key = false;
        break;
      case '"': {
        const std::size_t start = i;
        const bool is_key = !stack.empty() && stack.back().object && stack.back().expect_key;
        std::string key;
        bool decodable = true;
        for (++i; i < t.size() && t[i] != '"'; ++i) {
          const unsigned char b = static_cast<unsigned char>(t[i]);
          if (b >= 0x80) {
            const std::size_t n = utf8Length(t, i);
            if (n == 0) return utf8Error(i);
            if (is_key) key.append(t.substr(i, n));
            i += n - 1;
          } else if (b == '\\') {
            if (++i >= t.size()) break;
            if (!is_key) continue;
            switch (t[i]) {
              case 'b':
                key += '\b';
                break;
              case 'f':
                key += '\f';
                break;
              case 'n':
                key += '\n';
                break;
              case 'r':
                key += '\r';
                break;
              case 't':
                key += '\t';
                break;
              case 'u': {
                long cp = hex4(t, i + 1);
                if (cp < 0) {
                  decodable = false;
                  break;
                }
                i += 4;
                if (cp >= 0xD800 && cp < 0xDC00 && i + 2 < t.size() && t[i + 1] == '\\' && t[i + 2] == 'u') {
                  const long lo = hex4(t, i + 3);
                  if (lo >= 0xDC00 && lo < 0xE000) {
                    cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                    i += 6;
                  }
                }
                appendUtf8(key, unsigned(cp));
                break;
              }
              default:
                key += t[i];  // \" \\ \/ (others are nlohmann's syntax errors)
            }
          } else if (is_key) {
            key += char(b);
          }
        }
        if (is_key && decodable && !duplicate) {
          auto [it, inserted] = stack.back().keys.emplace(std::move(key), start);
          if (!inserted) {
            const auto [line, col] = lineColumn(t, it->second);
            const bool one_line = t.find('\n') == std::string_view::npos;  // a JSON-lines line: no line number
            duplicate = errorAt(t, start,
                                "duplicate key \"" + printableExcerpt(it->first) + "\" (first at " +
                                    (one_line ? "" : "line " + std::to_string(line) + ", ") + "column " +
                                    std::to_string(col) + ")");
          }
        }
        if (is_key) stack.back().expect_key = false;
        break;
      }
      default:
        break;
    }
  }
  return std::monostate{};
}

// nlohmann's messages, reduced to the reason and positioned at the offending byte.
JsonInputError fromNlohmann(std::string_view text, const std::exception& ex) {
  std::string reason = ex.what();
  if (const auto* pe = dynamic_cast<const nlohmann::json::parse_error*>(&ex)) {
    // nlohmann reports the byte *after* the offending character; report the character.
    const std::size_t at = pe->byte > 0 ? pe->byte - 1 : 0;
    if (auto p = reason.find(": "); p != std::string::npos) reason = reason.substr(p + 2);
    if (auto p = reason.find(": "); p != std::string::npos && reason.rfind("syntax error", 0) != 0)
      reason = reason.substr(p + 2);
    return errorAt(text, at, printableExcerpt(reason, 200), true);
  }
  if (dynamic_cast<const nlohmann::json::out_of_range*>(&ex)) {
    // Number overflow ("1e999"): nlohmann gives no position, so find the literal it names.
    if (auto p = reason.find("] "); p != std::string::npos) reason = reason.substr(p + 2);
    std::size_t at = 0;
    const auto q1 = reason.find('\''), q2 = reason.rfind('\'');
    if (q1 != std::string::npos && q2 > q1) {
      const auto f = text.find(reason.substr(q1 + 1, q2 - q1 - 1));
      if (f != std::string_view::npos) at = f;
    }
    return errorAt(text, at, printableExcerpt(reason, 200), true);
  }
  return errorAt(text, 0, printableExcerpt(reason, 200), true);
}

template <class Json>
std::variant<Json, JsonInputError> parseWithLimits(std::string_view text, const JsonLimits& limits) {
  std::optional<JsonInputError> duplicate;
  if (auto r = scan(text, limits, duplicate); std::holds_alternative<JsonInputError>(r))
    return std::get<JsonInputError>(std::move(r));
  Json j;
  try {
    j = Json::parse(text.begin(), text.end());
  } catch (const std::exception& e) {
    return fromNlohmann(text, e);
  }
  if (duplicate) return *duplicate;
  return j;
}

}  // namespace

std::string describe(const JsonInputError& e, std::string_view source) {
  const std::string at = "line " + std::to_string(e.line) + ", column " + std::to_string(e.column) + ": ";
  return std::string(source) + (e.malformed ? ": malformed JSON at " : ": ") + at + e.reason;
}

std::string describeInLine(const JsonInputError& e) {
  return std::string(e.malformed ? "malformed JSON at " : "") + "column " + std::to_string(e.column) + ": " + e.reason;
}

std::variant<std::monostate, JsonInputError> checkJsonText(std::string_view text, const JsonLimits& limits) {
  std::optional<JsonInputError> duplicate;
  auto r = scan(text, limits, duplicate);
  if (std::holds_alternative<std::monostate>(r) && duplicate) return *duplicate;
  return r;
}

std::variant<nlohmann::json, JsonInputError> parseJsonText(std::string_view text, const JsonLimits& limits) {
  return parseWithLimits<nlohmann::json>(text, limits);
}

std::variant<nlohmann::ordered_json, JsonInputError> parseOrderedJsonText(std::string_view text,
                                                                          const JsonLimits& limits) {
  return parseWithLimits<nlohmann::ordered_json>(text, limits);
}

std::variant<std::string, std::string> readInputFile(const std::filesystem::path& path, std::size_t max_bytes) {
  using Result = std::variant<std::string, std::string>;
  const auto failure = [](std::string reason) { return Result(std::in_place_index<1>, std::move(reason)); };
  if (path.empty()) return failure("an empty path names no file");
  // O_NONBLOCK: opening a FIFO with no writer returns at once instead of blocking; the type is
  // then checked on the open descriptor (no race with a rename between a stat and the open).
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int e = errno;
    if (e == ENOENT) return failure("no such file");
    if (e == EISDIR) return failure("is a directory, not a file");
    return failure(std::strerror(e));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return failure(std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return failure("is a directory, not a file");
  if (!S_ISREG(st.st_mode)) {
    const char* kind = S_ISFIFO(st.st_mode)   ? "a FIFO"
                       : S_ISCHR(st.st_mode)  ? "a character device"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                                              : "not a regular file";
    return failure(std::string("is ") + kind + ", not a regular file");
  }
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes)
    return failure("too large: " + std::to_string(size) + " bytes (limit " + std::to_string(max_bytes) + ")");
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  // Read at most max_bytes + 1 bytes: a file growing while it is read is bounded too.
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  char buffer[65536];
  while (text.size() <= max_bytes) {
    const ssize_t n = ::read(fd, buffer, std::min<std::size_t>(sizeof buffer, max_bytes + 1 - text.size()));
    if (n < 0) {
      if (errno == EINTR) continue;
      return failure(std::string("read error: ") + std::strerror(errno));
    }
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  if (text.size() > max_bytes) return failure("too large: more than " + std::to_string(max_bytes) + " bytes");
  return Result(std::in_place_index<0>, std::move(text));
}

std::string printableExcerpt(std::string_view text, std::size_t max_bytes) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  std::size_t i = 0;
  while (i < text.size() && out.size() < max_bytes) {
    const std::size_t n = utf8Length(text, i);
    if (n == 0) {
      const unsigned b = static_cast<unsigned char>(text[i]);
      out += "\\x";
      out += hex[b >> 4];
      out += hex[b & 15];
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  if (i < text.size()) out += "…";
  return out;
}

nlohmann::json readJsonText(std::string_view text, std::string_view source, const JsonLimits& limits) {
  auto parsed = parseJsonText(text, limits);
  if (auto* e = std::get_if<JsonInputError>(&parsed)) throw std::runtime_error(describe(*e, source));
  return std::move(std::get<nlohmann::json>(parsed));
}

nlohmann::json readJsonFile(const std::filesystem::path& path, const JsonLimits& limits) {
  auto bytes = readInputFile(path, limits.max_bytes);
  if (bytes.index() == 1) throw std::runtime_error(path.string() + ": " + std::get<1>(bytes));
  return readJsonText(std::get<0>(bytes), path.string(), limits);
}

}  // namespace fovea
