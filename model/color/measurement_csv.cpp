#include "model/color/measurement_csv.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string_view>

namespace fovea::color {

namespace {

constexpr int kLevels = 256;
constexpr std::size_t kMaxProblems = 1000;
const char* const kDisplays[2] = {"foveal", "peripheral"};
const char* const kChannels[3] = {"R", "G", "B"};

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\"");
  if (a == std::string::npos) return {};
  const auto b = s.find_last_not_of(" \t\r\"");
  return s.substr(a, b - a + 1);
}
std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(trim(field));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}
bool number(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}
bool integer(const std::string& s, int lo, int hi, int& out) {
  double d;
  if (!number(s, d) || d != std::floor(d) || d < lo || d > hi) return false;
  out = static_cast<int>(d);
  return true;
}

// "3-5, 9" from a sorted list of levels.
std::string ranges(const std::vector<int>& levels) {
  std::string s;
  for (std::size_t i = 0; i < levels.size();) {
    std::size_t j = i;
    while (j + 1 < levels.size() && levels[j + 1] == levels[j] + 1) ++j;
    if (!s.empty()) s += ", ";
    s += std::to_string(levels[i]);
    if (j > i) s += "-" + std::to_string(levels[j]);
    i = j + 1;
  }
  return s;
}

struct Accumulator {
  double sum_Y = 0, sum_x = 0, sum_y = 0, sum_X = 0, sum_Z = 0;
  int n = 0;
};

}  // namespace

MeasurementImport importSpectroradiometerCsv(const std::string& file_text) {
  MeasurementImport result;
  auto problem = [&](int line, const std::string& m) { result.problems.push_back({line, m}); };
  // A UTF-8 byte order mark (spreadsheet exports write one) is not part of the first column's name.
  const std::string_view bom = "\xEF\xBB\xBF";
  const std::string text =
      std::string_view(file_text).substr(0, bom.size()) == bom ? file_text.substr(bom.size()) : file_text;
  std::array<std::array<std::array<Accumulator, kLevels>, 3>, 2> acc{};
  std::map<std::array<int, 4>, int> seen;  // (display, channel, level, repeat) -> line

  std::istringstream in(text);
  std::string line;
  int number_of_line = 0;
  std::map<std::string, std::size_t> column;
  std::vector<std::string> required = {"display", "channel", "level", "x", "y", "Y", "repeat"};
  bool tristimulus = false;  // X, Y, Z columns instead of x, y, Y
  while (std::getline(in, line)) {
    ++number_of_line;
    if (result.problems.size() >= kMaxProblems) {  // a file of garbage: the first ones say enough
      problem(number_of_line, "more than " + std::to_string(kMaxProblems) + " problems: stopped reading here");
      return result;
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    const auto fields = split(line);
    if (column.empty()) {  // the header
      for (std::size_t i = 0; i < fields.size(); ++i) {
        // x, y and Y differ only in case, and X, Y, Z are tristimulus values, not chromaticity:
        // one-letter names are case-sensitive (an "X" column is not "x").
        const std::string name = fields[i].size() == 1 ? fields[i] : lower(fields[i]);
        column.emplace(name, i);
      }
      // x and y: chromaticity and luminance. Without them, X or Z: tristimulus values (X, Y, Z).
      tristimulus = !(column.count("x") && column.count("y")) && (column.count("X") || column.count("Z"));
      if (tristimulus) required = {"display", "channel", "level", "X", "Y", "Z", "repeat"};
      std::string missing;
      for (const auto& r : required)
        if (!column.count(r)) missing += (missing.empty() ? "" : ", ") + r;
      if (!missing.empty()) {
        std::string given;
        for (const char* t : {"X", "Z"})
          if (column.count(t)) given += (given.empty() ? "" : ", ") + std::string(t);
        std::string m;
        if (tristimulus) {
          m = "the header has the tristimulus column(s) ";
          m += given;
          m += " but lacks ";
          m += missing;
          m += " (expected display,channel,level,X,Y,Z,repeat for tristimulus values or "
               "display,channel,level,x,y,Y,repeat for chromaticity; X is not the chromaticity x)";
        } else {
          m = "the header lacks the column(s) ";
          m += missing;
          m += " (expected display,channel,level,x,y,Y,repeat)";
        }
        problem(number_of_line, m);
        return result;
      }
      result.tristimulus = tristimulus;
      continue;
    }
    std::size_t needed = 0;
    for (const auto& r : required) needed = std::max(needed, column.at(r) + 1);
    if (fields.size() < needed) {
      problem(number_of_line, "expected " + std::to_string(needed) + " columns, got " + std::to_string(fields.size()));
      continue;
    }
    auto field = [&](const char* name) -> const std::string& { return fields[column.at(name)]; };
    std::vector<std::string> bad;
    const std::string display_name = lower(field("display"));
    int display = -1, channel = -1, level = 0, repeat = 0;
    for (int d = 0; d < 2; ++d)
      if (display_name == kDisplays[d]) display = d;
    if (display < 0) bad.push_back("display '" + field("display") + "' is neither foveal nor peripheral");
    const std::string ch = lower(field("channel"));
    if (ch == "r" || ch == "red") channel = 0;
    if (ch == "g" || ch == "green") channel = 1;
    if (ch == "b" || ch == "blue") channel = 2;
    if (channel < 0) bad.push_back("channel '" + field("channel") + "' is not R, G or B");
    if (!integer(field("level"), 0, kLevels - 1, level))
      bad.push_back("level '" + field("level") + "' is not an integer in 0..255");
    if (!integer(field("repeat"), 0, 1000000, repeat))
      bad.push_back("repeat '" + field("repeat") + "' is not a non-negative integer");
    double x = 0, y = 0, X = 0, Y = 0, Z = 0;
    if (tristimulus) {
      if (!number(field("X"), X) || X < 0) bad.push_back("X '" + field("X") + "' is not a number >= 0");
      if (!number(field("Z"), Z) || Z < 0) bad.push_back("Z '" + field("Z") + "' is not a number >= 0");
    } else {
      if (!number(field("x"), x) || x < 0 || x > 1) bad.push_back("x '" + field("x") + "' is not a number in [0, 1]");
      if (!number(field("y"), y) || y < 0 || y > 1) bad.push_back("y '" + field("y") + "' is not a number in [0, 1]");
    }
    if (!number(field("Y"), Y))
      bad.push_back("Y '" + field("Y") + "' is not a number");
    else if (Y < 0)
      bad.push_back("negative luminance Y = " + field("Y"));
    if (!bad.empty()) {
      std::string m;
      for (const auto& b : bad) m += (m.empty() ? "" : "; ") + b;
      problem(number_of_line, m);
      continue;
    }
    const std::array<int, 4> key{display, channel, level, repeat};
    if (auto it = seen.find(key); it != seen.end()) {
      problem(number_of_line,
              "duplicate reading (same display, channel, level and repeat as line " + std::to_string(it->second) + ")");
      continue;
    }
    seen.emplace(key, number_of_line);
    Accumulator& a = acc[display][channel][level];
    a.sum_Y += Y;
    a.sum_x += x;
    a.sum_y += y;
    a.sum_X += X;
    a.sum_Z += Z;
    ++a.n;
    ++result.rows;
  }
  if (column.empty()) {
    problem(0, "no header line (expected display,channel,level,x,y,Y,repeat)");
    return result;
  }

  result.min_repeats = result.rows ? 1 << 30 : 0;
  for (int d = 0; d < 2; ++d) {
    DisplayMeasurement& dm = d == 0 ? result.measurements.foveal : result.measurements.peripheral;
    for (int c = 0; c < 3; ++c) {
      std::vector<int> missing;
      ChannelMeasurement& cm = dm.channels[c];
      cm.Y.assign(kLevels, 0.0);
      for (int l = 0; l < kLevels; ++l) {
        const Accumulator& a = acc[d][c][l];
        if (a.n == 0) {
          missing.push_back(l);
          continue;
        }
        cm.Y[l] = a.sum_Y / a.n;
        result.min_repeats = std::min(result.min_repeats, a.n);
        result.max_repeats = std::max(result.max_repeats, a.n);
      }
      if (!missing.empty()) {
        problem(0, std::string(kDisplays[d]) + " " + kChannels[c] + ": no readings for level" +
                       (missing.size() > 1 ? "s " : " ") + ranges(missing));
        continue;
      }
      // The same rule as the JSON measurements: the curve must rise (all zero: no light measured).
      if (!(cm.Y[kLevels - 1] > cm.Y[0])) {
        problem(0, std::string(kDisplays[d]) + " " + kChannels[c] +
                       ": the luminance does not rise (Y at level 255 <= Y at level 0; all zero: no light measured)");
        continue;
      }
      const Accumulator& top = acc[d][c][kLevels - 1];
      if (tristimulus) {  // the chromaticity of the mean tristimulus values (their sum > 0: Y rises)
        const double sum = top.sum_X + top.sum_Y + top.sum_Z;
        cm.xy = {top.sum_X / sum, top.sum_Y / sum};
      } else {
        cm.xy = {top.sum_x / top.n, top.sum_y / top.n};
      }
      // Laser primaries lie on the spectral locus (x + y = 1 for red): allow the reading noise.
      if (!(cm.xy.y > 0) || cm.xy.x + cm.xy.y > 1.01)
        problem(0, std::string(kDisplays[d]) + " " + kChannels[c] + ": the level-255 chromaticity is not a colour");
    }
  }
  if (result.min_repeats == 1 << 30) result.min_repeats = 0;
  return result;
}

std::string formatProblems(const MeasurementImport& m, const std::string& file, std::size_t limit) {
  std::string s;
  for (std::size_t i = 0; i < m.problems.size() && i < limit; ++i) {
    const auto& p = m.problems[i];
    s += file + (p.line > 0 ? ":" + std::to_string(p.line) : std::string()) + ": " + p.message + "\n";
  }
  if (m.problems.size() > limit) s += "... and " + std::to_string(m.problems.size() - limit) + " more\n";
  return s;
}

}  // namespace fovea::color
