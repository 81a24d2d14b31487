#pragma once
// The scene field table: one declaration per field of the scene file (JSON key, member,
// unit, range, presence, label, group, help text). The loader, the canonical writer, the
// validation, the studio's property editor and the JSON paths of parameter sweeps all read
// this table (scene_field_table.cpp), so a field is added with one line there.
//
// Keys are relative to their element object and may be dotted for a nested object
// ("pixel_beam.waist_fwhm_um" in the projector); the nested object itself is declared by an
// Object entry just before its fields. Entries are kept in file order: the canonical
// writer emits them in that order and the loader reports problems in that order.

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "model/scene/scene.h"

namespace fovea {

// One notation for every numeric rule: "> 0", ">= 0", "(0, 180)", "[1, 4]", "(0, 10000]".
struct Range {
  enum class Bound { None, Open, Closed };
  Bound low = Bound::None, high = Bound::None;
  double lo = 0, hi = 0;

  static Range any() { return {}; }
  static Range positive() { return {Bound::Open, Bound::None, 0, 0}; }
  static Range nonNegative() { return {Bound::Closed, Bound::None, 0, 0}; }
  static Range closed(double a, double b) { return {Bound::Closed, Bound::Closed, a, b}; }
  static Range open(double a, double b) { return {Bound::Open, Bound::Open, a, b}; }
  static Range openClosed(double a, double b) { return {Bound::Open, Bound::Closed, a, b}; }

  // Empty when `v` fits, otherwise the problem ("must be > 0, got -5"). A closed or open
  // interval names the whole interval; a half-open one the bound that was crossed.
  std::string check(double v) const;
  // Integers: the same rule with integer bounds in the message ("must be in [1, 4], got 7").
  std::string checkInteger(long long v) const;
  // The notation above, for people ("[-1e5, 1e5]"); empty for any().
  std::string text() const;
};

enum class FieldType { Number, Integer, Bool, Text, Numbers, Integers, NumberList, Object };
enum class Presence { Required, Optional };

// What the table says about one field, independent of the struct it lives in.
struct FieldInfo {
  std::string key;  // relative to the element; dotted inside a nested object
  FieldType type = FieldType::Number;
  std::size_t size = 1;    // components of Numbers / Integers
  std::string unit;        // as printed: "mm", "deg", "µm", "nm", "1/mm", ""
  bool axis_unit = false;  // key and unit take the stage axis' unit: soft_limits_mm / _deg
  Range range;
  Presence presence = Presence::Required;
  bool omit_default = false;         // written only when it differs from the default (newer fields)
  std::vector<std::string> choices;  // Text: the allowed values (empty: any)
  std::string group;                 // heading in the property editor
  std::vector<std::string> labels;   // one per component (one for a scalar)
  std::string help;                  // tooltip / docs
  std::string rule_note;             // cross-field rule shown with the range ("< n0", "!= 0")

  bool required() const { return presence == Presence::Required; }
  // Range and cross-field rules in the one notation ("> 0, < n0").
  std::string rangeText() const;
  // Label of component `i` (the only label of a scalar).
  const std::string& label(std::size_t i = 0) const { return labels.at(labels.size() == 1 ? 0 : i); }
};

// Where a field's value lives in a struct.
using ValueRef =
    std::variant<double*, int*, bool*, std::string*, std::span<double>, std::span<int>, std::vector<double>*>;

namespace field_detail {
inline ValueRef refOf(double& v) {
  return &v;
}
inline ValueRef refOf(int& v) {
  return &v;
}
inline ValueRef refOf(bool& v) {
  return &v;
}
inline ValueRef refOf(std::string& v) {
  return &v;
}
inline ValueRef refOf(std::vector<double>& v) {
  return &v;
}
template <std::size_t N>
ValueRef refOf(std::array<double, N>& v) {
  return std::span<double>(v);
}
template <std::size_t N>
ValueRef refOf(std::array<int, N>& v) {
  return std::span<int>(v);
}

template <class M>
constexpr FieldType typeOf() {
  if constexpr (std::is_same_v<M, double>) return FieldType::Number;
  if constexpr (std::is_same_v<M, int>) return FieldType::Integer;
  if constexpr (std::is_same_v<M, bool>) return FieldType::Bool;
  if constexpr (std::is_same_v<M, std::string>) return FieldType::Text;
  if constexpr (std::is_same_v<M, std::vector<double>>) return FieldType::NumberList;
  if constexpr (std::is_same_v<M, std::array<double, 2>> || std::is_same_v<M, std::array<double, 3>>)
    return FieldType::Numbers;
  if constexpr (std::is_same_v<M, std::array<int, 2>>) return FieldType::Integers;
}
template <class M>
constexpr std::size_t sizeOf() {
  if constexpr (requires { std::tuple_size<M>::value; })
    return std::tuple_size<M>::value;
  else
    return 1;
}

template <class T>
struct ClassOf;
template <class C, class M>
struct ClassOf<M C::*> {
  using type = C;
};

// obj.*m0.*m1...: a member chain (Projector::pose then Pose::position_mm).
template <class T, auto... Members>
ValueRef chain(T& obj) {
  return refOf((obj.*....*Members));
}
template <class T, auto... Members>
using MemberType = std::remove_reference_t<decltype((std::declval<T&>().*....*Members))>;
}  // namespace field_detail

// One entry of an element's table: a field, a nested object, or a cross-field rule.
template <class T>
struct FieldEntry {
  FieldInfo info;
  ValueRef (*ref)(T&) = nullptr;  // fields only
  // Rules only: checked right after the entry before them; empty when fine, otherwise the
  // problem, reported at `info.key` (empty: the element itself).
  std::function<std::string(const T&)> rule;
  bool isRule() const { return static_cast<bool>(rule); }
};

// The table of one element type, built line by line (see scene_field_table.cpp).
template <class T>
class FieldTable {
 public:
  std::vector<FieldEntry<T>> entries;
  std::string (*axis_unit)(const T&) = nullptr;  // unit of axis_unit fields ("mm" / "deg")

  FieldTable& group(std::string name) {
    group_ = std::move(name);
    return *this;
  }
  // A value field: key, unit, range, presence, labels (one per component), help.
  template <auto... Members>
  FieldTable& add(std::string key, std::string unit, Range range, Presence presence, std::vector<std::string> labels,
                  std::string help) {
    using M = field_detail::MemberType<T, Members...>;
    FieldInfo i;
    i.key = std::move(key);
    i.type = field_detail::typeOf<M>();
    i.size = field_detail::sizeOf<M>();
    i.unit = std::move(unit);
    i.range = range;
    i.presence = presence;
    i.group = group_;
    i.labels = std::move(labels);
    i.help = std::move(help);
    entries.push_back({std::move(i), &field_detail::chain<T, Members...>, {}});
    return *this;
  }
  // A text field, optionally restricted to `choices`.
  template <auto... Members>
  FieldTable& text(std::string key, Presence presence, std::string label, std::string help,
                   const std::vector<std::string>& choices = {}) {
    add<Members...>(std::move(key), "", Range::any(), presence, {std::move(label)}, std::move(help));
    entries.back().info.choices = choices;
    return *this;
  }
  // A nested object; its fields follow with keys "key.<field>".
  FieldTable& object(std::string key, Presence presence) {
    FieldInfo i;
    i.key = std::move(key);
    i.type = FieldType::Object;
    i.presence = presence;
    entries.push_back({std::move(i), nullptr, {}});
    return *this;
  }
  // A rule checked after the previous entry, reported at `at`; `note` is shown with the range.
  FieldTable& rule(std::string at, const std::string& note, std::function<std::string(const T&)> check) {
    FieldInfo i;
    i.key = std::move(at);
    i.rule_note = note;
    for (auto& e : entries)
      if (e.ref && e.info.key == i.key) {
        e.info.rule_note = note;
        i.axis_unit = e.info.axis_unit;
      }
    entries.push_back({std::move(i), nullptr, std::move(check)});
    return *this;
  }
  // Modifiers of the last field.
  FieldTable& axisUnit() {
    entries.back().info.axis_unit = true;
    return *this;
  }
  FieldTable& omitDefault() {
    entries.back().info.omit_default = true;
    return *this;
  }

  // The field declared with `key` (full relative key), or nullptr.
  const FieldEntry<T>* find(const std::string& key) const {
    for (const auto& e : entries)
      if (e.ref && e.info.key == key) return &e;
    return nullptr;
  }
  // The key as written in the file for `obj` (soft_limits -> soft_limits_deg on a yaw axis).
  std::string fileKey(const FieldInfo& info, const T& obj) const {
    return info.axis_unit && axis_unit ? info.key + "_" + axis_unit(obj) : info.key;
  }
  std::string unitOf(const FieldInfo& info, const T& obj) const {
    return info.axis_unit && axis_unit ? axis_unit(obj) : info.unit;
  }

 private:
  std::string group_;
};

// The tables (scene_field_table.cpp).
const FieldTable<Projector>& projectorFields();
const FieldTable<Hoe>& hoeFields();
const FieldTable<HoeLayer>& hoeLayerFields();
const FieldTable<Eye>& eyeFields();
const FieldTable<FovealDisplay>& fovealDisplayFields();
const FieldTable<BeamShapingLens>& lensFields();
const FieldTable<Foveation>& foveationFields();
const FieldTable<StageBinding>& stageFields();
const FieldTable<ViewState>& viewFields();
const FieldTable<Binocular>& binocularFields();

bool isRotationAxis(const std::string& axis);

// ---------------------------------------------------------------------------------------
// The table seen from a whole scene: what the property editor and parameter sweeps use.
// ---------------------------------------------------------------------------------------

// One field of one element of a scene, with its full path ("hoe_layers[1].thickness_um").
struct SceneField {
  const FieldInfo* info = nullptr;
  std::string path;  // element id + "." + file key
  std::string unit;  // resolved (axis unit for stage limits)
  std::function<ValueRef(Scene&)> ref;
};

// The fields of element `id` ("projector", "hoe", "hoe_layers[1]", "eye", "foveal_display",
// "beam_shaping_lens", "foveation", "view", "stages[0]", "binocular" when the scene has that
// block), in file order; empty when unknown.
std::vector<SceneField> elementFields(const Scene& scene, const std::string& id);

// A number addressed by a JSON path of the file ("eye.relief_mm", "hoe.rotation_deg[0]",
// "projector.pixels[1]"): a double or an int in the scene. Throws std::invalid_argument
// naming the path when it is no number of the format.
std::variant<double*, int*> numberAt(Scene& scene, const std::string& path);

// The label of the field (component) at `path` ("hoe_layers[1].thickness_um" -> "Thickness",
// "eye.gaze_deg[0]" -> "Gaze yaw"); empty when the path names no field.
std::string fieldLabel(const Scene& scene, const std::string& path);

// The table entry of the field whose value (or component) `path` addresses and its resolved
// unit; nullptr when the path names no field.
const FieldInfo* fieldInfoAt(const Scene& scene, const std::string& path, std::string* unit = nullptr);

}  // namespace fovea
