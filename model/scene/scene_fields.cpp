#include "model/scene/scene_fields.h"

#include <cmath>
#include <stdexcept>

#include "model/scene/scene_io.h"

namespace fovea {

namespace {

// "1e+05" -> "1e5": the form people write in a range.
std::string humanNumber(double v) {
  std::string s = formatNumber(v);
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string exponent = s.substr(e + 1);
  const bool negative = !exponent.empty() && exponent[0] == '-';
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.erase(0, 1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return s.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

using Bound = Range::Bound;

// The violated rule in words, with `fmt` formatting the bounds.
template <class Format>
std::string problem(const Range& r, double v, Format fmt) {
  const bool low_ok = r.low == Bound::None || (r.low == Bound::Open ? v > r.lo : v >= r.lo);
  const bool high_ok = r.high == Bound::None || (r.high == Bound::Open ? v < r.hi : v <= r.hi);
  if (low_ok && high_ok) return {};
  const bool interval = r.low != Bound::None && r.high != Bound::None;
  if (interval && r.low == r.high)
    return std::string("must be in ") + (r.low == Bound::Open ? "(" : "[") + fmt(r.lo) + ", " + fmt(r.hi) +
           (r.high == Bound::Open ? ")" : "]");
  if (!low_ok) return std::string("must be ") + (r.low == Bound::Open ? "> " : ">= ") + fmt(r.lo);
  return std::string("must be ") + (r.high == Bound::Open ? "< " : "<= ") + fmt(r.hi);
}

}  // namespace

std::string Range::check(double v) const {
  if (!std::isfinite(v)) return "must be a finite number, got " + formatNumber(v);
  const std::string p = problem(*this, v, formatNumber);
  return p.empty() ? p : p + ", got " + formatNumber(v);
}

std::string Range::checkInteger(long long v) const {
  auto integer = [](double x) { return std::to_string(static_cast<long long>(x)); };
  const std::string p = problem(*this, static_cast<double>(v), integer);
  return p.empty() ? p : p + ", got " + std::to_string(v);
}

std::string Range::text() const {
  if (low == Bound::None && high == Bound::None) return {};
  if (high == Bound::None) return (low == Bound::Open ? "> " : ">= ") + humanNumber(lo);
  if (low == Bound::None) return (high == Bound::Open ? "< " : "<= ") + humanNumber(hi);
  return (low == Bound::Open ? "(" : "[") + humanNumber(lo) + ", " + humanNumber(hi) +
         (high == Bound::Open ? ")" : "]");
}

std::string FieldInfo::rangeText() const {
  std::string r = range.text();
  if (rule_note.empty()) return r;
  return r.empty() ? rule_note : r + ", " + rule_note;
}

namespace {

template <class T, class Get>
void addFields(std::vector<SceneField>& out, const FieldTable<T>& table, const T& obj, const std::string& id, Get get) {
  for (const auto& e : table.entries) {
    if (!e.ref) continue;
    out.push_back({&e.info, id + "." + table.fileKey(e.info, obj), table.unitOf(e.info, obj),
                   [ref = e.ref, get](Scene& s) { return ref(get(s)); }});
  }
}

// "hoe_layers[3]" -> 3 when `id` is an element of the list `list`, else -1.
int indexIn(const std::string& id, const std::string& list) {
  if (id.size() < list.size() + 3 || id.compare(0, list.size() + 1, list + "[") != 0 || id.back() != ']') return -1;
  const std::string digits = id.substr(list.size() + 1, id.size() - list.size() - 2);
  if (digits.empty() || digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stoi(digits);
}

}  // namespace

std::vector<SceneField> elementFields(const Scene& scene, const std::string& id) {
  std::vector<SceneField> out;
  if (id == "projector")
    addFields(
        out, projectorFields(), scene.projector, id, [](Scene & s) -> auto& { return s.projector; });
  if (id == "hoe")
    addFields(
        out, hoeFields(), scene.hoe, id, [](Scene & s) -> auto& { return s.hoe; });
  if (id == "eye")
    addFields(
        out, eyeFields(), scene.eye, id, [](Scene & s) -> auto& { return s.eye; });
  if (id == "foveal_display")
    addFields(
        out, fovealDisplayFields(), scene.foveal_display, id, [](Scene & s) -> auto& { return s.foveal_display; });
  if (id == "beam_shaping_lens")
    addFields(
        out, lensFields(), scene.lens, id, [](Scene & s) -> auto& { return s.lens; });
  if (id == "foveation")
    addFields(
        out, foveationFields(), scene.foveation, id, [](Scene & s) -> auto& { return s.foveation; });
  if (id == "view")
    addFields(
        out, viewFields(), scene.view, id, [](Scene & s) -> auto& { return s.view; });
  if (id == "binocular" && scene.binocular)
    addFields(
        out, binocularFields(), *scene.binocular, id, [](Scene & s) -> auto& { return s.binocular.value(); });
  if (const int i = indexIn(id, "hoe_layers"); i >= 0 && i < static_cast<int>(scene.hoe_layers.size()))
    addFields(
        out, hoeLayerFields(), scene.hoe_layers[i],
        id, [i](Scene & s) -> auto& { return s.hoe_layers.at(static_cast<std::size_t>(i)); });
  if (const int i = indexIn(id, "stages"); i >= 0 && i < static_cast<int>(scene.stages.size()))
    addFields(
        out, stageFields(), scene.stages[i],
        id, [i](Scene & s) -> auto& { return s.stages.at(static_cast<std::size_t>(i)); });
  return out;
}

namespace {

// The field addressed by `path` and the component index (-1: the whole field).
struct Located {
  SceneField field;
  int component = -1;
};

std::optional<Located> locate(const Scene& scene, const std::string& path) {
  const auto dot = path.find('.');
  if (dot == std::string::npos) return std::nullopt;
  for (auto& f : elementFields(scene, path.substr(0, dot))) {
    if (path == f.path) return Located{f, -1};
    if (path.size() > f.path.size() + 2 && path.compare(0, f.path.size() + 1, f.path + "[") == 0 &&
        path.back() == ']') {
      const std::string digits = path.substr(f.path.size() + 1, path.size() - f.path.size() - 2);
      if (digits.empty() || digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
      return Located{f, std::stoi(digits)};
    }
  }
  return std::nullopt;
}

}  // namespace

std::variant<double*, int*> numberAt(Scene& scene, const std::string& path) {
  auto fail = [&path](const std::string& why) -> std::variant<double*, int*> {
    throw std::invalid_argument("parameter " + path + ": " + why);
  };
  if (path.empty()) return fail("empty path");
  const auto at = locate(scene, path);
  if (!at) return fail("no number \"" + path + "\" in the scene file format");
  const ValueRef ref = at->field.ref(scene);
  const std::size_t k = static_cast<std::size_t>(at->component);
  if (at->component < 0) {
    if (auto* d = std::get_if<double*>(&ref)) return *d;
    if (auto* i = std::get_if<int*>(&ref)) return *i;
    return fail("not a single number (give an index, e.g. " + path + "[0])");
  }
  if (auto* a = std::get_if<std::span<double>>(&ref); a && k < a->size()) return &(*a)[k];
  if (auto* a = std::get_if<std::span<int>>(&ref); a && k < a->size()) return &(*a)[k];
  if (auto* v = std::get_if<std::vector<double>*>(&ref); v && k < (*v)->size()) return &(**v)[k];
  return fail("no element [" + std::to_string(k) + "] in " + at->field.path);
}

std::string fieldLabel(const Scene& scene, const std::string& path) {
  const auto at = locate(scene, path);
  if (!at) return {};
  const FieldInfo& f = *at->field.info;
  if (at->component < 0 || f.labels.size() <= 1) return f.label();
  return static_cast<std::size_t>(at->component) < f.labels.size() ? f.label(static_cast<std::size_t>(at->component))
                                                                   : std::string();
}

const FieldInfo* fieldInfoAt(const Scene& scene, const std::string& path, std::string* unit) {
  const auto at = locate(scene, path);
  if (!at) return nullptr;
  if (unit) *unit = at->field.unit;
  return at->field.info;
}

}  // namespace fovea
