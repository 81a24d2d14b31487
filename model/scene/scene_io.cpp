#include "model/scene/scene_io.h"

#include "model/io/json_input.h"
#include "model/io/output_file.h"
#include "model/io/save_temporaries.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <span>
#include <sstream>
#include <type_traits>
#include <variant>

#include "model/scene/scene_fields.h"

namespace fovea {

using ojson = nlohmann::ordered_json;

std::string formatNumber(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
  return ec == std::errc{} ? std::string(buf, end) : std::to_string(value);
}

namespace {

// ---------------------------------------------------------------------------------------
// Reader: walks the JSON keeping the path, collects every problem, records unknown keys.
// ---------------------------------------------------------------------------------------
class Reader {
 public:
  Reader(std::string source, SceneLoadResult& out, ojson& unknown)
      : source_(std::move(source)), out_(out), unknown_(unknown) {}

  void error(const std::string& path, const std::string& what) {
    out_.errors.push_back(source_ + ": " + (path.empty() ? "" : path + ": ") + what);
  }
  void warning(const std::string& path, const std::string& what) {
    out_.warnings.push_back(source_ + ": " + path + ": " + what);
  }

  // An object scope: reads keys of `obj`, then reports keys it never asked for.
  class Obj {
   public:
    Obj(Reader& r, const ojson& obj, std::string path, std::string pointer)
        : r_(r), obj_(obj), path_(std::move(path)), pointer_(std::move(pointer)) {}
    ~Obj() { finish(); }  // NOLINT(bugprone-exception-escape): finish() only appends warnings
    Obj(const Obj&) = delete;
    Obj& operator=(const Obj&) = delete;

    std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
    const std::string& pointer() const { return pointer_; }

    // Returns the value for `key` or nullptr (reporting "missing" when required).
    const ojson* get(const std::string& key, bool required) {
      seen_.insert(key);
      auto it = obj_.find(key);
      if (it == obj_.end()) {
        if (required) r_.error(at(key), "missing required field");
        return nullptr;
      }
      return &*it;
    }

    void number(const std::string& key, double& out, const Range& range, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_number()) {
        r_.error(at(key), "must be a number, got " + typeName(*v));
        return;
      }
      const double d = v->get<double>();
      if (auto p = range.check(d); !p.empty()) {
        r_.error(at(key), p);
        return;
      }
      out = d;
    }
    void integer(const std::string& key, int& out, const Range& range, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_number_integer()) {
        r_.error(at(key), "must be an integer, got " + typeName(*v));
        return;
      }
      const auto i = v->get<long long>();
      if (auto p = range.checkInteger(i); !p.empty()) {
        r_.error(at(key), p);
        return;
      }
      out = static_cast<int>(i);
    }
    void boolean(const std::string& key, bool& out, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_boolean()) {
        r_.error(at(key), "must be true or false, got " + typeName(*v));
        return;
      }
      out = v->get<bool>();
    }
    void string(const std::string& key, std::string& out, bool required = true,
                const std::vector<std::string>& allowed = {}) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_string()) {
        r_.error(at(key), "must be a string, got " + typeName(*v));
        return;
      }
      std::string s = v->get<std::string>();
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        r_.error(at(key), "must be one of " + list + ", got \"" + s + "\"");
        return;
      }
      out = std::move(s);
    }
    // A fixed-length array of numbers (V = double) or integers (V = int), each in `range`.
    template <class V>
    void array(const std::string& key, std::span<V> out, const Range& range, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_array() || v->size() != out.size()) {
        r_.error(at(key),
                 "must be an array of " + std::to_string(out.size()) + " " + kindOf<V>() + "s, got " + typeName(*v));
        return;
      }
      std::vector<V> tmp;
      if (elements(*v, at(key), range, tmp)) std::copy(tmp.begin(), tmp.end(), out.begin());
    }
    void numberList(const std::string& key, std::vector<double>& out, const Range& range, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_array() || v->empty()) {
        r_.error(at(key), "must be a non-empty array of numbers, got " + typeName(*v));
        return;
      }
      std::vector<double> tmp;
      if (elements(*v, at(key), range, tmp)) out = std::move(tmp);
    }

    // Nested object; nullptr when absent (error if required) or of the wrong type.
    const ojson* object(const std::string& key, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return nullptr;
      if (!v->is_object()) {
        r_.error(at(key), "must be an object, got " + typeName(*v));
        return nullptr;
      }
      return v;
    }
    const ojson* array(const std::string& key, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return nullptr;
      if (!v->is_array()) {
        r_.error(at(key), "must be an array, got " + typeName(*v));
        return nullptr;
      }
      return v;
    }
    void markSeen(const std::string& key) { seen_.insert(key); }

   private:
    template <class V>
    static const char* kindOf() {
      return std::is_same_v<V, int> ? "integer" : "number";
    }
    // Every element of `list` as a V in `range`, reporting each problem; true when all fit.
    template <class V>
    bool elements(const ojson& list, const std::string& path, const Range& range, std::vector<V>& out) {
      bool ok = true;
      for (std::size_t i = 0; i < list.size(); ++i) {
        const auto& e = list[i];
        const std::string p = path + "[" + std::to_string(i) + "]";
        if (std::is_same_v<V, int> ? !e.is_number_integer() : !e.is_number()) {
          r_.error(p, std::string("must be ") + (std::is_same_v<V, int> ? "an " : "a ") + kindOf<V>() + ", got " +
                          typeName(e));
          ok = false;
          continue;
        }
        const std::string problem =
            std::is_same_v<V, int> ? range.checkInteger(e.get<long long>()) : range.check(e.get<double>());
        if (!problem.empty()) {
          r_.error(p, problem);
          ok = false;
          continue;
        }
        out.push_back(e.get<V>());
      }
      return ok;
    }
    void finish() {
      for (auto it = obj_.begin(); it != obj_.end(); ++it) {
        if (seen_.count(it.key())) continue;
        r_.unknown_[pointer_.empty() ? "/" : pointer_][it.key()] = it.value();
        r_.warning(at(it.key()), "unknown key kept as is (not used by this version)");
      }
    }
    Reader& r_;
    const ojson& obj_;
    std::string path_;
    std::string pointer_;
    std::set<std::string> seen_;
  };

  static std::string typeName(const ojson& v) {
    switch (v.type()) {
      case ojson::value_t::null:
        return "null";
      case ojson::value_t::boolean:
        return v.get<bool>() ? "true" : "false";
      case ojson::value_t::string:
        return "a string";
      case ojson::value_t::array:
        return "an array of " + std::to_string(v.size());
      case ojson::value_t::object:
        return "an object";
      default:
        return "a number (" + v.dump() + ")";
    }
  }

 private:
  std::string source_;
  SceneLoadResult& out_;
  ojson& unknown_;
};

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

void readValue(Reader::Obj& o, const std::string& key, const FieldInfo& f, const ValueRef& ref) {
  const bool req = f.required();
  std::visit(
      Overloaded{[&](double* d) { o.number(key, *d, f.range, req); }, [&](int* i) { o.integer(key, *i, f.range, req); },
                 [&](bool* b) { o.boolean(key, *b, req); }, [&](std::string* s) { o.string(key, *s, req, f.choices); },
                 [&](std::span<double> a) { o.array(key, a, f.range, req); },
                 [&](std::span<int> a) { o.array(key, a, f.range, req); },
                 [&](std::vector<double>* v) { o.numberList(key, *v, f.range, req); }},
      ref);
}

// Reads the entries of `table` under `prefix` (a nested object's "key.") from `o`, in table
// order; returns the index after them. Rules run right after the entry before them.
template <class T>
std::size_t readEntries(Reader& r, Reader::Obj& o, const std::string& element_path, const FieldTable<T>& table, T& obj,
                        std::size_t i, const std::string& prefix) {
  const auto& entries = table.entries;
  while (i < entries.size() && startsWith(entries[i].info.key, prefix)) {
    const FieldEntry<T>& e = entries[i];
    const std::string key = table.fileKey(e.info, obj).substr(prefix.size());
    if (e.isRule()) {
      if (const std::string problem = e.rule(obj); !problem.empty())
        r.error(e.info.key.empty() ? element_path : element_path + "." + table.fileKey(e.info, obj), problem);
      ++i;
    } else if (e.info.type == FieldType::Object) {
      const std::string inner = e.info.key + ".";
      std::size_t end = i + 1;
      while (end < entries.size() && startsWith(entries[end].info.key, inner)) ++end;
      if (const ojson* j = o.object(key, e.info.required())) {
        Reader::Obj nested(r, *j, o.at(key), o.pointer() + "/" + key);
        readEntries(r, nested, element_path, table, obj, i + 1, inner);
      }
      i = end;
    } else {
      readValue(o, key, e.info, e.ref(obj));
      ++i;
    }
  }
  return i;
}

template <class T>
void readElement(Reader& r, const ojson& j, const std::string& path, const std::string& pointer,
                 const FieldTable<T>& table, T& obj) {
  Reader::Obj o(r, j, path, pointer);
  readEntries(r, o, path, table, obj, 0, "");
}

// An array of elements ("hoe_layers", "stages"): each must be an object.
// (Paths and pointers under `root`'s: the scene's top level, or the left train of a binocular block.)
template <class T>
void readElements(Reader& r, Reader::Obj& root, const std::string& key, Presence presence, const FieldTable<T>& table,
                  std::vector<T>& out) {
  const ojson* list = root.array(key, presence == Presence::Required);
  if (!list) return;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string path = root.at(key) + "[" + std::to_string(i) + "]";
    if (!(*list)[i].is_object()) {
      r.error(path, "must be an object, got " + Reader::typeName((*list)[i]));
      continue;
    }
    T element;
    readElement(r, (*list)[i], path, root.pointer() + "/" + key + "/" + std::to_string(i), table, element);
    out.push_back(element);
  }
}

template <class T>
void readObjectElement(Reader& r, Reader::Obj& root, const std::string& key, Presence presence,
                       const FieldTable<T>& table, T& obj) {
  if (const ojson* j = root.object(key, presence == Presence::Required))
    readElement(r, *j, root.at(key), root.pointer() + "/" + key, table, obj);
}

// The elements of one eye's optical train from `o` (the scene's top level or a left train):
// the same keys, presence and rules for both.
void readTrain(Reader& r, Reader::Obj& o, Projector& projector, Hoe& hoe, std::vector<HoeLayer>& hoe_layers, Eye& eye,
               FovealDisplay& foveal_display, BeamShapingLens& lens, Foveation& foveation,
               std::vector<StageBinding>& stages) {
  readObjectElement(r, o, "projector", Presence::Required, projectorFields(), projector);
  readObjectElement(r, o, "hoe", Presence::Required, hoeFields(), hoe);
  if (const ojson* layers = o.get("hoe_layers", false); layers && layers->is_array() && layers->empty())
    r.error(o.at("hoe_layers"), "must contain at least one layer");
  readElements(r, o, "hoe_layers", Presence::Required, hoeLayerFields(), hoe_layers);
  readObjectElement(r, o, "eye", Presence::Required, eyeFields(), eye);
  readObjectElement(r, o, "foveal_display", Presence::Required, fovealDisplayFields(), foveal_display);
  readObjectElement(r, o, "beam_shaping_lens", Presence::Optional, lensFields(), lens);
  readObjectElement(r, o, "foveation", Presence::Optional, foveationFields(), foveation);
  readElements(r, o, "stages", Presence::Optional, stageFields(), stages);
}

// The "binocular" block (issue 30): its fields, and in mode "explicit" the left train, which
// must have the scene's elements (as many HOE layers, the same stage axes in the same order).
void readBinocular(Reader& r, const ojson& j, const Scene& scene, Binocular& out) {
  Reader::Obj o(r, j, "binocular", "/binocular");
  readEntries(r, o, "binocular", binocularFields(), out, 0, "");
  const ojson* left = o.object("left", false);
  if (out.mode != "explicit") {
    if (left)
      r.error("binocular.left",
              "a left train needs mode \"explicit\" (mode \"" + out.mode + "\" derives the left eye's train)");
    return;
  }
  if (!o.get("left", false)) {
    r.error("binocular.left", "missing required field (mode \"explicit\": the left eye's optical train)");
    return;
  }
  if (!left) return;  // not an object: reported
  OpticalTrain t;
  {
    Reader::Obj lo(r, *left, "binocular.left", "/binocular/left");
    readTrain(r, lo, t.projector, t.hoe, t.hoe_layers, t.eye, t.foveal_display, t.lens, t.foveation, t.stages);
    // Only a complete train is compared (a missing list was reported above).
    if (lo.get("hoe_layers", false) && !t.hoe_layers.empty() && t.hoe_layers.size() != scene.hoe_layers.size())
      r.error("binocular.left.hoe_layers", "the left train has " + std::to_string(t.hoe_layers.size()) +
                                               " HOE layer(s), the scene's (right) train " +
                                               std::to_string(scene.hoe_layers.size()) +
                                               ": both eyes' trains have the same elements");
    if (t.stages.size() != scene.stages.size()) {
      r.error("binocular.left.stages",
              "the left train has " + std::to_string(t.stages.size()) + " stage axes, the scene's (right) train " +
                  std::to_string(scene.stages.size()) + ": both eyes' trains have the same elements");
    } else {
      for (std::size_t i = 0; i < t.stages.size(); ++i)
        if (t.stages[i].element != scene.stages[i].element || t.stages[i].axis != scene.stages[i].axis)
          r.error("binocular.left.stages[" + std::to_string(i) + "]",
                  "drives " + t.stages[i].element + " " + t.stages[i].axis + ", the scene's stages[" +
                      std::to_string(i) + "] " + scene.stages[i].element + " " + scene.stages[i].axis +
                      ": both eyes' trains have the same stage axes in the same order");
    }
  }
  out.left = std::move(t);
}

}  // namespace

SceneLoadResult parseScene(std::string_view text, const std::string& source) {
  SceneLoadResult result;
  auto parsed = parseOrderedJsonText(text);  // size, depth, UTF-8, duplicate keys, syntax
  if (const auto* e = std::get_if<JsonInputError>(&parsed)) {
    result.errors.push_back(describe(*e, source));
    return result;
  }
  const ojson root = std::get<ojson>(std::move(parsed));

  Scene scene;
  scene.hoe_layers.clear();
  Reader r(source, result, scene.unknown);
  if (!root.is_object()) {
    r.error("", "the top level must be a JSON object, got " + Reader::typeName(root));
    return result;
  }
  {
    Reader::Obj o(r, root, "", "");
    std::string format;
    o.string("format", format);
    if (!format.empty() && format != "fovea-scene")
      r.error("format", "must be \"fovea-scene\", got \"" + format + "\"");
    int version = 0;
    o.integer("version", version, Range::closed(1, 1000000));
    if (version > Scene::kFormatVersion) {
      r.error("version", "file is version " + std::to_string(version) + ", this studio reads up to version " +
                             std::to_string(Scene::kFormatVersion) + " (update the studio)");
      return result;
    }
    o.string("name", scene.name, false);
    if (const ojson* n = o.get("notes", false)) scene.notes = *n;
    readTrain(r, o, scene.projector, scene.hoe, scene.hoe_layers, scene.eye, scene.foveal_display, scene.lens,
              scene.foveation, scene.stages);
    readObjectElement(r, o, "view", Presence::Optional, viewFields(), scene.view);
    if (const ojson* b = o.object("binocular", false)) {  // issue 30: present = a binocular scene
      Binocular binocular;
      readBinocular(r, *b, scene, binocular);
      scene.binocular = std::move(binocular);
    }
  }
  if (result.errors.empty()) result.scene = std::move(scene);
  return result;
}

SceneLoadResult loadSceneFile(const std::filesystem::path& path) {
  SceneLoadResult result;
  auto text = readInputFile(path);
  if (const auto* reason = std::get_if<1>(&text)) {
    result.errors.push_back(path.string() + ": cannot read scene file: " + *reason);
    return result;
  }
  SceneLoadResult parsed = parseScene(std::get<0>(text), path.filename().string());
  for (const auto& stale : removeStaleSaveTemporaries(path))
    parsed.warnings.push_back(path.filename().string() + ": removed " + stale.filename().string() +
                              ", the temporary file of an interrupted save");
  return parsed;
}

std::vector<std::string> validateScene(const Scene& scene) {
  // One set of rules: serialise and run the loader's checks on the text.
  SceneLoadResult r = parseScene(serializeScene(scene), "scene");
  std::vector<std::string> out;
  for (auto& e : r.errors) out.push_back(e.substr(std::string("scene: ").size()));
  return out;
}

namespace {

// Doubles are written as JSON numbers; NaN/Inf (which JSON cannot hold) become null so the
// loader reports them rather than the writer producing invalid JSON.
ojson num(double v) {
  return std::isfinite(v) ? ojson(v) : ojson(nullptr);
}
// Numbers in an array: doubles as num(), integers as they are.
template <class Range>
ojson numberArray(const Range& values) {
  ojson j = ojson::array();
  for (auto v : values) {
    if constexpr (std::is_same_v<decltype(v), double>)
      j.push_back(num(v));
    else
      j.push_back(v);
  }
  return j;
}

void appendUnknown(ojson& obj, const ojson& unknown, const std::string& pointer) {
  auto it = unknown.find(pointer.empty() ? "/" : pointer);
  if (it == unknown.end()) return;
  for (auto kv = it->begin(); kv != it->end(); ++kv) obj[kv.key()] = kv.value();
}

ojson toJson(const ValueRef& ref) {
  return std::visit(
      Overloaded{[](double* d) { return num(*d); }, [](int* i) { return ojson(*i); }, [](bool* b) { return ojson(*b); },
                 [](std::string* s) { return ojson(*s); }, [](std::span<double> a) { return numberArray(a); },
                 [](std::span<int> a) { return numberArray(a); },
                 [](std::vector<double>* v) { return numberArray(*v); }},
      ref);
}

bool sameValue(const ValueRef& a, const ValueRef& b) {
  return std::visit(
      [&b](auto pa) {
        using P = decltype(pa);
        const P pb = std::get<P>(b);
        if constexpr (std::is_pointer_v<P>)
          return *pa == *pb;
        else
          return std::equal(pa.begin(), pa.end(), pb.begin(), pb.end());
      },
      a);
}

// Writes the entries of `table` under `prefix` into `out` (canonical order = table order);
// returns the index after them.
template <class T>
std::size_t writeEntries(ojson& out, const ojson& unknown, const std::string& pointer, const FieldTable<T>& table,
                         const T& obj, std::size_t i, const std::string& prefix) {
  static T defaults{};
  T& value = const_cast<T&>(obj);  // the references are only read
  const auto& entries = table.entries;
  while (i < entries.size() && startsWith(entries[i].info.key, prefix)) {
    const FieldEntry<T>& e = entries[i];
    const std::string key = table.fileKey(e.info, obj).substr(prefix.size());
    if (e.isRule()) {
      ++i;
    } else if (e.info.type == FieldType::Object) {
      ojson nested = ojson::object();
      std::string nested_pointer = pointer;
      nested_pointer.append("/").append(key);
      i = writeEntries(nested, unknown, nested_pointer, table, obj, i + 1, e.info.key + ".");
      appendUnknown(nested, unknown, nested_pointer);
      // An optional object with nothing to say (every field at an omitted default) is left
      // out, so files written before its fields existed keep their bytes.
      if (!nested.empty() || e.info.required()) out[key] = nested;
    } else {
      if (!(e.info.omit_default && sameValue(e.ref(value), e.ref(defaults)))) out[key] = toJson(e.ref(value));
      ++i;
    }
  }
  return i;
}

template <class T>
ojson writeElement(const ojson& unknown, const std::string& pointer, const FieldTable<T>& table, const T& obj) {
  ojson out = ojson::object();
  writeEntries(out, unknown, pointer, table, obj, 0, "");
  appendUnknown(out, unknown, pointer);
  return out;
}

template <class T>
ojson writeElements(const ojson& unknown, const std::string& key, const FieldTable<T>& table,
                    const std::vector<T>& list, const std::string& parent_pointer = "") {
  ojson out = ojson::array();
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::string pointer = parent_pointer;
    pointer.append("/").append(key).append("/").append(std::to_string(i));
    out.push_back(writeElement(unknown, pointer, table, list[i]));
  }
  return out;
}

// One eye's train into `out` (the scene's root or a left train's object), in the scene's order.
void writeTrain(ojson& out, const ojson& u, const std::string& p, const Projector& projector, const Hoe& hoe,
                const std::vector<HoeLayer>& hoe_layers, const Eye& eye, const FovealDisplay& foveal_display,
                const BeamShapingLens& lens, const Foveation& foveation, const std::vector<StageBinding>& stages) {
  out["projector"] = writeElement(u, p + "/projector", projectorFields(), projector);
  out["hoe"] = writeElement(u, p + "/hoe", hoeFields(), hoe);
  out["hoe_layers"] = writeElements(u, "hoe_layers", hoeLayerFields(), hoe_layers, p);
  out["eye"] = writeElement(u, p + "/eye", eyeFields(), eye);
  out["foveal_display"] = writeElement(u, p + "/foveal_display", fovealDisplayFields(), foveal_display);
  out["beam_shaping_lens"] = writeElement(u, p + "/beam_shaping_lens", lensFields(), lens);
  out["foveation"] = writeElement(u, p + "/foveation", foveationFields(), foveation);
  out["stages"] = writeElements(u, "stages", stageFields(), stages, p);
}

}  // namespace

std::string serializeScene(const Scene& s) {
  const ojson& u = s.unknown;
  ojson root = ojson::object();
  root["format"] = "fovea-scene";
  // Version 2 only for what needs it: a monocular scene keeps the bytes it had before.
  root["version"] = s.binocular ? Scene::kFormatVersion : Scene::kMonocularFormatVersion;
  root["name"] = s.name;
  if (!s.notes.is_null()) root["notes"] = s.notes;
  writeTrain(root, u, "", s.projector, s.hoe, s.hoe_layers, s.eye, s.foveal_display, s.lens, s.foveation, s.stages);
  // Newer, optional state: left out while it holds only defaults (older files stay as they are).
  if (ojson view = writeElement(u, "/view", viewFields(), s.view); !view.empty()) root["view"] = view;
  if (s.binocular) {
    ojson b = writeElement(u, "/binocular", binocularFields(), *s.binocular);
    if (const auto& t = s.binocular->left) {
      ojson left = ojson::object();
      writeTrain(left, u, "/binocular/left", t->projector, t->hoe, t->hoe_layers, t->eye, t->foveal_display, t->lens,
                 t->foveation, t->stages);
      appendUnknown(left, u, "/binocular/left");
      b["left"] = std::move(left);
    }
    root["binocular"] = std::move(b);
  }
  appendUnknown(root, u, "/");
  return root.dump(2) + "\n";
}

void writeFileAtomic(const std::filesystem::path& path, std::string_view text,
                     const std::function<void()>& beforeRename) {
  try {
    writeOutputFile(path, text, beforeRename);  // the one output writer (model/io/output_file.h)
  } catch (const OutputError& e) {
    throw SceneIoError(e.what());
  }
}

void saveSceneFileAtomic(const Scene& scene, const std::filesystem::path& path,
                         const std::function<void()>& beforeRename) {
  writeFileAtomic(path, serializeScene(scene), beforeRename);
}

std::string sceneSummary(const Scene& s) {
  std::ostringstream o;
  o << s.name << ": " << s.hoe_layers.size() << " HOE layer" << (s.hoe_layers.size() == 1 ? "" : "s") << " (";
  for (std::size_t i = 0; i < s.hoe_layers.size(); ++i)
    o << (i ? "/" : "") << formatNumber(s.hoe_layers[i].recording.wavelength_nm);
  o << " nm), HOE " << formatNumber(s.hoe.size_mm[0]) << "x" << formatNumber(s.hoe.size_mm[1]) << " mm, projector "
    << s.projector.pixels[0] << "x" << s.projector.pixels[1] << " px over " << formatNumber(s.projector.fov_deg[0])
    << "x" << formatNumber(s.projector.fov_deg[1]) << " deg, eye relief " << formatNumber(s.eye.relief_mm)
    << " mm, pupil " << formatNumber(s.eye.pupil_diameter_mm) << " mm, " << s.stages.size() << " stage axes";
  if (s.binocular) o << ", binocular (" << s.binocular->mode << ", IPD " << formatNumber(s.binocular->ipd_mm) << " mm)";
  return o.str();
}

}  // namespace fovea
