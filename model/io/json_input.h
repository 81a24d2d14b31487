#pragma once
// Every JSON the program reads goes through here: bytes -> JSON value, with the input limits
// in one place. Before nlohmann's parser sees the text, one iterative pass (no recursion, memory
// bounded by the input) checks
//   - the size (JsonLimits::max_bytes),
//   - the nesting depth (JsonLimits::max_depth): the parsed value is later copied, compared,
//     destroyed and dumped by recursive code, so an unbounded depth would overflow the stack,
//   - UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF), reported by
//     byte offset,
//   - duplicate object keys (RFC 8259 §4 leaves them undefined: we refuse them), reported
//     with both positions.
// Messages never quote more than a few dozen bytes of the input and are always valid UTF-8,
// so they can be printed in JSON output whatever the input was.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <variant>

#include <nlohmann/json.hpp>

namespace fovea {

struct JsonLimits {
  std::size_t max_depth = 64;         // nested arrays/objects; real files use fewer than 10
  std::size_t max_bytes = 16u << 20;  // 16 MiB: a scene is ~10 KB
};

struct JsonInputError {
  std::size_t byte = 0;      // 0-based offset of the offending byte
  int line = 1, column = 1;  // 1-based, column in bytes
  std::string reason;        // e.g. "nesting deeper than 64"
  bool malformed = false;    // a JSON syntax error (nlohmann's), else a limit/UTF-8/duplicate
};

// "SOURCE: line L, column C: REASON" (or "SOURCE: malformed JSON at line L, column C: REASON").
std::string describe(const JsonInputError& e, std::string_view source);
// The same for one line of a JSON-lines file: "column C: REASON" / "malformed JSON at column C: REASON".
std::string describeInLine(const JsonInputError& e);

// The pre-scan alone: the first limit, UTF-8 or duplicate-key problem, or nothing.
std::variant<std::monostate, JsonInputError> checkJsonText(std::string_view text, const JsonLimits& limits = {});

// Pre-scan, then nlohmann's parser. Exactly one alternative is set.
std::variant<nlohmann::json, JsonInputError> parseJsonText(std::string_view text, const JsonLimits& limits = {});
std::variant<nlohmann::ordered_json, JsonInputError> parseOrderedJsonText(std::string_view text,
                                                                          const JsonLimits& limits = {});

// Reads a whole file as bytes, refusing a directory, a FIFO, a device or a socket ("is a FIFO,
// not a regular file": a FIFO with no writer never blocks, /dev/zero is never read), a missing or
// unreadable file and one larger than max_bytes before reading it. On failure the reason alone
// ("is a directory, not a file", "no such file", "too large: … bytes (limit …)", strerror); the
// caller names the path. Every input file of the program is read through here.
std::variant<std::string, std::string> readInputFile(const std::filesystem::path& path,
                                                     std::size_t max_bytes = JsonLimits{}.max_bytes);

// Whole-document readers for files and texts that are not scenes (tolerance specs, shard parts,
// capture manifests, the studio's report manifest): the limits above, and on any problem a
// std::runtime_error "SOURCE: …" naming the file (or `source`).
nlohmann::json readJsonFile(const std::filesystem::path& path, const JsonLimits& limits = {});
nlohmann::json readJsonText(std::string_view text, std::string_view source, const JsonLimits& limits = {});

// At most max_bytes of `text`, cut at a UTF-8 character boundary, invalid bytes shown as \xHH,
// "…" appended when cut: safe to embed in a message.
std::string printableExcerpt(std::string_view text, std::size_t max_bytes = 40);

}  // namespace fovea
