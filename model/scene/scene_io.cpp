#include "model/scene/scene_io.h"

#include "model/io/json_input.h"
#include "model/io/save_temporaries.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

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
struct Range {
  enum Kind { Any, Positive, NonNegative, Closed, OpenClosed, Open } kind = Any;
  double lo = 0, hi = 0;
  static Range any() { return {}; }
  static Range positive() { return {Positive}; }
  static Range nonNegative() { return {NonNegative}; }
  static Range closed(double a, double b) { return {Closed, a, b}; }
  static Range open(double a, double b) { return {Open, a, b}; }
  // Empty when `v` fits, otherwise the problem ("must be > 0, got -5").
  std::string check(double v) const {
    if (!std::isfinite(v)) return "must be a finite number, got " + formatNumber(v);
    const std::string got = ", got " + formatNumber(v);
    switch (kind) {
      case Any: return {};
      case Positive: return v > 0 ? "" : "must be > 0" + got;
      case NonNegative: return v >= 0 ? "" : "must be >= 0" + got;
      case Closed:
        return (v >= lo && v <= hi) ? ""
                                    : "must be in [" + formatNumber(lo) + ", " + formatNumber(hi) + "]" + got;
      case OpenClosed:
      case Open:
        return (v > lo && v < hi) ? ""
                                  : "must be in (" + formatNumber(lo) + ", " + formatNumber(hi) + ")" + got;
    }
    return {};
  }
};

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
    ~Obj() { finish(); }
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

    void number(const std::string& key, double& out, Range range, bool required = true) {
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
    void integer(const std::string& key, int& out, int lo, int hi, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_number_integer()) {
        r_.error(at(key), "must be an integer, got " + typeName(*v));
        return;
      }
      const auto i = v->get<long long>();
      if (i < lo || i > hi) {
        r_.error(at(key), "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                              std::to_string(i));
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
    template <std::size_t N>
    void numbers(const std::string& key, std::array<double, N>& out, Range range, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_array() || v->size() != N) {
        r_.error(at(key), "must be an array of " + std::to_string(N) + " numbers, got " + typeName(*v));
        return;
      }
      std::array<double, N> tmp{};
      bool ok = true;
      for (std::size_t i = 0; i < N; ++i) {
        const auto& e = (*v)[i];
        const std::string p = at(key) + "[" + std::to_string(i) + "]";
        if (!e.is_number()) {
          r_.error(p, "must be a number, got " + typeName(e));
          ok = false;
          continue;
        }
        tmp[i] = e.get<double>();
        if (auto problem = range.check(tmp[i]); !problem.empty()) {
          r_.error(p, problem);
          ok = false;
        }
      }
      if (ok) out = tmp;
    }
    template <std::size_t N>
    void integers(const std::string& key, std::array<int, N>& out, int lo, int hi, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_array() || v->size() != N) {
        r_.error(at(key), "must be an array of " + std::to_string(N) + " integers, got " + typeName(*v));
        return;
      }
      std::array<int, N> tmp{};
      bool ok = true;
      for (std::size_t i = 0; i < N; ++i) {
        const auto& e = (*v)[i];
        const std::string p = at(key) + "[" + std::to_string(i) + "]";
        if (!e.is_number_integer()) {
          r_.error(p, "must be an integer, got " + typeName(e));
          ok = false;
          continue;
        }
        const auto x = e.get<long long>();
        if (x < lo || x > hi) {
          r_.error(p, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(x));
          ok = false;
          continue;
        }
        tmp[i] = static_cast<int>(x);
      }
      if (ok) out = tmp;
    }
    void numberList(const std::string& key, std::vector<double>& out, Range range, bool required = true) {
      const ojson* v = get(key, required);
      if (!v) return;
      if (!v->is_array() || v->empty()) {
        r_.error(at(key), "must be a non-empty array of numbers, got " + typeName(*v));
        return;
      }
      std::vector<double> tmp;
      bool ok = true;
      for (std::size_t i = 0; i < v->size(); ++i) {
        const auto& e = (*v)[i];
        const std::string p = at(key) + "[" + std::to_string(i) + "]";
        if (!e.is_number()) {
          r_.error(p, "must be a number, got " + typeName(e));
          ok = false;
          continue;
        }
        tmp.push_back(e.get<double>());
        if (auto problem = range.check(tmp.back()); !problem.empty()) {
          r_.error(p, problem);
          ok = false;
        }
      }
      if (ok) out = std::move(tmp);
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
      case ojson::value_t::null: return "null";
      case ojson::value_t::boolean: return v.get<bool>() ? "true" : "false";
      case ojson::value_t::string: return "a string";
      case ojson::value_t::array: return "an array of " + std::to_string(v.size());
      case ojson::value_t::object: return "an object";
      default: return "a number (" + v.dump() + ")";
    }
  }

 private:
  std::string source_;
  SceneLoadResult& out_;
  ojson& unknown_;
};

const Range kCoord = Range::closed(-1e5, 1e5);        // mm
const Range kAngle = Range::closed(-360.0, 360.0);    // deg
const Range kWavelength = Range::open(200.0, 2000.0);  // nm
const Range kIndex = Range::closed(1.0, 4.0);

void readPose(Reader::Obj& o, Pose& pose) {
  o.numbers("position_mm", pose.position_mm, kCoord);
  o.numbers("rotation_deg", pose.rotation_deg, kAngle, false);
}

void readProjector(Reader& r, const ojson& j, Projector& p) {
  Reader::Obj o(r, j, "projector", "/projector");
  o.string("name", p.name, false);
  readPose(o, p.pose);
  o.integers("pixels", p.pixels, 1, 100000);
  o.numbers("fov_deg", p.fov_deg, Range::open(0.0, 180.0));
  o.numberList("wavelengths_nm", p.wavelengths_nm, kWavelength);
  o.number("exit_pupil_diameter_mm", p.exit_pupil_diameter_mm, Range::positive(), false);
  if (const ojson* b = o.object("pixel_beam", false)) {
    Reader::Obj ob(r, *b, o.at("pixel_beam"), "/projector/pixel_beam");
    auto& m = p.pixel_beam;
    ob.number("waist_distance_mm", m.waist_distance_mm, Range::positive());
    ob.number("waist_fwhm_um", m.waist_fwhm_um, Range::positive());
    ob.number("divergence_mrad", m.divergence_mrad, Range::nonNegative());
    ob.number("exit_fwhm_um", m.exit_fwhm_um, Range::positive());
    ob.number("exit_ellipticity", m.exit_ellipticity, Range::closed(1.0, 100.0));
  }
}

void readHoe(Reader& r, const ojson& j, Hoe& h) {
  Reader::Obj o(r, j, "hoe", "/hoe");
  o.string("name", h.name, false);
  readPose(o, h.pose);
  o.numbers("size_mm", h.size_mm, Range::open(0.0, 1e4));
  o.number("substrate_thickness_mm", h.substrate_thickness_mm, Range::closed(0.0, 100.0), false);
  o.number("cover_index", h.cover_index, kIndex, false);
  o.number("substrate_index", h.substrate_index, kIndex, false);
}

void readLayer(Reader& r, const ojson& j, std::size_t i, HoeLayer& l) {
  const std::string path = "hoe_layers[" + std::to_string(i) + "]";
  Reader::Obj o(r, j, path, "/hoe_layers/" + std::to_string(i));
  o.string("name", l.name, false);
  o.number("thickness_um", l.thickness_um, Range::positive());
  if (l.thickness_um > 10000.0) r.error(o.at("thickness_um"), "must be <= 10000, got " + formatNumber(l.thickness_um));
  o.number("offset_um", l.offset_um, Range::closed(-1e5, 1e5), false);
  o.number("n0", l.n0, kIndex);
  o.number("n1", l.n1, Range::nonNegative());
  if (l.n1 >= l.n0) r.error(o.at("n1"), "must be < n0 (" + formatNumber(l.n0) + "), got " + formatNumber(l.n1));
  o.number("absorption_per_mm", l.absorption_per_mm, Range::nonNegative(), false);
  o.number("shrinkage_percent", l.shrinkage_percent, Range::open(-50.0, 50.0), false);
  o.number("recording_n0_delta", l.recording_n0_delta, Range::closed(-0.5, 0.5), false);
  if (const ojson* rec = o.object("recording")) {
    Reader::Obj orc(r, *rec, o.at("recording"), o.pointer() + "/recording");
    auto& c = l.recording;
    orc.number("wavelength_nm", c.wavelength_nm, kWavelength);
    orc.numbers("reference_point_mm", c.reference_point_mm, kCoord);
    orc.numbers("signal_point_mm", c.signal_point_mm, kCoord);
    orc.boolean("phase_conjugate", c.phase_conjugate, false);
    if (c.reference_point_mm == c.signal_point_mm)
      r.error(orc.at("signal_point_mm"), "must differ from reference_point_mm (no fringes otherwise)");
  }
}

void readEye(Reader& r, const ojson& j, Eye& e) {
  Reader::Obj o(r, j, "eye", "/eye");
  o.number("eyeball_diameter_mm", e.eyeball_diameter_mm, Range::open(5.0, 50.0));
  o.number("pupil_diameter_mm", e.pupil_diameter_mm, Range::open(0.0, 15.0));
  if (e.pupil_diameter_mm >= e.eyeball_diameter_mm)
    r.error(o.at("pupil_diameter_mm"), "must be smaller than eyeball_diameter_mm");
  o.number("relief_mm", e.relief_mm, Range::positive());
  o.numbers("lateral_offset_mm", e.lateral_offset_mm, kCoord, false);
  o.numbers("gaze_deg", e.gaze_deg, Range::open(-90.0, 90.0), false);
  o.numbers("gaze_range_deg", e.gaze_range_deg, Range::open(-90.0, 90.0), false);
  if (e.gaze_range_deg[0] >= e.gaze_range_deg[1])
    r.error(o.at("gaze_range_deg"), "lower end must be below the upper end");
  o.number("fovea_radius_deg", e.fovea_radius_deg, Range::open(0.0, 45.0), false);
}

void readFovealDisplay(Reader& r, const ojson& j, FovealDisplay& f) {
  Reader::Obj o(r, j, "foveal_display", "/foveal_display");
  o.string("name", f.name, false);
  readPose(o, f.pose);
  o.numbers("size_mm", f.size_mm, Range::open(0.0, 1e4));
  o.integers("pixels", f.pixels, 1, 100000);
  o.numberList("primaries_nm", f.primaries_nm, kWavelength, false);
  if (const ojson* c = o.object("combiner")) {
    Reader::Obj oc(r, *c, o.at("combiner"), "/foveal_display/combiner");
    auto& ic = f.combiner;
    oc.string("name", ic.name, false);
    oc.number("magnification", ic.magnification, Range::positive());
    oc.number("eye_distance_mm", ic.eye_distance_mm, Range::positive());
    oc.number("image_distance_mm", ic.image_distance_mm, Range::positive());
    oc.number("mtf30_cpd_on_axis", ic.mtf30_cpd_on_axis, Range::positive(), false);
    oc.number("field_curvature_per_deg2", ic.field_curvature_per_deg2, Range::nonNegative(), false);
  }
}

void readLens(Reader& r, const ojson& j, BeamShapingLens& l) {
  Reader::Obj o(r, j, "beam_shaping_lens", "/beam_shaping_lens");
  o.boolean("enabled", l.enabled);
  o.string("name", l.name, false);
  readPose(o, l.pose);
  o.number("focal_length_mm", l.focal_length_mm, Range::closed(-1e5, 1e5));
  if (l.focal_length_mm == 0.0) r.error(o.at("focal_length_mm"), "must not be 0");
  o.number("diameter_mm", l.diameter_mm, Range::positive());
  o.number("center_thickness_mm", l.center_thickness_mm, Range::nonNegative(), false);
  o.number("index", l.index, kIndex, false);
}

void readFoveation(Reader& r, const ojson& j, Foveation& f) {
  Reader::Obj o(r, j, "foveation", "/foveation");
  o.number("blur_start_deg", f.blur_start_deg, Range::closed(0.0, 90.0));
  o.number("blend_start_deg", f.blend_start_deg, Range::closed(0.0, 90.0));
  o.number("blend_end_deg", f.blend_end_deg, Range::closed(0.0, 90.0));
  if (!(f.blur_start_deg <= f.blend_start_deg && f.blend_start_deg < f.blend_end_deg))
    r.error("foveation", "must satisfy blur_start_deg <= blend_start_deg < blend_end_deg");
}

bool isRotationAxis(const std::string& axis) { return axis == "yaw" || axis == "pitch" || axis == "roll"; }

void readStage(Reader& r, const ojson& j, std::size_t i, StageBinding& s) {
  const std::string path = "stages[" + std::to_string(i) + "]";
  Reader::Obj o(r, j, path, "/stages/" + std::to_string(i));
  o.string("element", s.element, true, {"hoe", "foveal_display", "projector", "beam_shaping_lens", "camera"});
  o.string("axis", s.axis, true, {"x", "y", "z", "yaw", "pitch", "roll"});
  o.string("controller", s.controller, true, {"KDC101", "TDC001", "KBD101", "K10CR1"});
  o.string("stage_model", s.stage_model, true, {"MTS25-Z8", "Z825B", "DDSM50", "K10CR1"});
  o.string("serial", s.serial, false);
  o.integer("channel", s.channel, 1, 4, false);
  const std::string unit = isRotationAxis(s.axis) ? "_deg" : "_mm";
  o.numbers("soft_limits" + unit, s.soft_limits, kCoord);
  if (s.soft_limits[0] >= s.soft_limits[1])
    r.error(o.at("soft_limits" + unit), "lower limit must be below the upper limit");
  o.number("home_offset" + unit, s.home_offset, kCoord, false);
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
    o.integer("version", version, 1, 1000000);
    if (version > Scene::kFormatVersion) {
      r.error("version", "file is version " + std::to_string(version) + ", this studio reads up to version " +
                             std::to_string(Scene::kFormatVersion) + " (update the studio)");
      return result;
    }
    o.string("name", scene.name, false);
    if (const ojson* n = o.get("notes", false)) scene.notes = *n;
    if (const ojson* p = o.object("projector")) readProjector(r, *p, scene.projector);
    if (const ojson* h = o.object("hoe")) readHoe(r, *h, scene.hoe);
    if (const ojson* layers = o.array("hoe_layers")) {
      if (layers->empty()) r.error("hoe_layers", "must contain at least one layer");
      for (std::size_t i = 0; i < layers->size(); ++i) {
        HoeLayer layer;
        if (!(*layers)[i].is_object()) {
          r.error("hoe_layers[" + std::to_string(i) + "]", "must be an object, got " + Reader::typeName((*layers)[i]));
          continue;
        }
        readLayer(r, (*layers)[i], i, layer);
        scene.hoe_layers.push_back(layer);
      }
    }
    if (const ojson* e = o.object("eye")) readEye(r, *e, scene.eye);
    if (const ojson* f = o.object("foveal_display")) readFovealDisplay(r, *f, scene.foveal_display);
    if (const ojson* l = o.object("beam_shaping_lens", false)) readLens(r, *l, scene.lens);
    if (const ojson* f = o.object("foveation", false)) readFoveation(r, *f, scene.foveation);
    if (const ojson* st = o.array("stages", false)) {
      for (std::size_t i = 0; i < st->size(); ++i) {
        StageBinding s;
        if (!(*st)[i].is_object()) {
          r.error("stages[" + std::to_string(i) + "]", "must be an object, got " + Reader::typeName((*st)[i]));
          continue;
        }
        readStage(r, (*st)[i], i, s);
        scene.stages.push_back(s);
      }
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
ojson num(double v) { return std::isfinite(v) ? ojson(v) : ojson(nullptr); }
template <std::size_t N>
ojson nums(const std::array<double, N>& a) {
  ojson j = ojson::array();
  for (double v : a) j.push_back(num(v));
  return j;
}
ojson nums(const std::vector<double>& a) {
  ojson j = ojson::array();
  for (double v : a) j.push_back(num(v));
  return j;
}
template <std::size_t N>
ojson ints(const std::array<int, N>& a) {
  ojson j = ojson::array();
  for (int v : a) j.push_back(v);
  return j;
}

void appendUnknown(ojson& obj, const ojson& unknown, const std::string& pointer) {
  auto it = unknown.find(pointer.empty() ? "/" : pointer);
  if (it == unknown.end()) return;
  for (auto kv = it->begin(); kv != it->end(); ++kv) obj[kv.key()] = kv.value();
}

void writePose(ojson& o, const Pose& p) {
  o["position_mm"] = nums(p.position_mm);
  o["rotation_deg"] = nums(p.rotation_deg);
}

}  // namespace

std::string serializeScene(const Scene& s) {
  const ojson& u = s.unknown;
  ojson root = ojson::object();
  root["format"] = "fovea-scene";
  root["version"] = Scene::kFormatVersion;
  root["name"] = s.name;
  if (!s.notes.is_null()) root["notes"] = s.notes;

  ojson p;
  p["name"] = s.projector.name;
  writePose(p, s.projector.pose);
  p["pixels"] = ints(s.projector.pixels);
  p["fov_deg"] = nums(s.projector.fov_deg);
  p["wavelengths_nm"] = nums(s.projector.wavelengths_nm);
  p["exit_pupil_diameter_mm"] = num(s.projector.exit_pupil_diameter_mm);
  {
    const auto& m = s.projector.pixel_beam;
    ojson b;
    b["waist_distance_mm"] = num(m.waist_distance_mm);
    b["waist_fwhm_um"] = num(m.waist_fwhm_um);
    b["divergence_mrad"] = num(m.divergence_mrad);
    b["exit_fwhm_um"] = num(m.exit_fwhm_um);
    b["exit_ellipticity"] = num(m.exit_ellipticity);
    appendUnknown(b, u, "/projector/pixel_beam");
    p["pixel_beam"] = b;
  }
  appendUnknown(p, u, "/projector");
  root["projector"] = p;

  ojson h;
  h["name"] = s.hoe.name;
  writePose(h, s.hoe.pose);
  h["size_mm"] = nums(s.hoe.size_mm);
  h["substrate_thickness_mm"] = num(s.hoe.substrate_thickness_mm);
  h["cover_index"] = num(s.hoe.cover_index);
  h["substrate_index"] = num(s.hoe.substrate_index);
  appendUnknown(h, u, "/hoe");
  root["hoe"] = h;

  ojson layers = ojson::array();
  for (std::size_t i = 0; i < s.hoe_layers.size(); ++i) {
    const auto& l = s.hoe_layers[i];
    const std::string ptr = "/hoe_layers/" + std::to_string(i);
    ojson o;
    o["name"] = l.name;
    o["thickness_um"] = num(l.thickness_um);
    o["offset_um"] = num(l.offset_um);
    o["n0"] = num(l.n0);
    o["n1"] = num(l.n1);
    o["absorption_per_mm"] = num(l.absorption_per_mm);
    o["shrinkage_percent"] = num(l.shrinkage_percent);
    o["recording_n0_delta"] = num(l.recording_n0_delta);
    ojson rec;
    rec["wavelength_nm"] = num(l.recording.wavelength_nm);
    rec["reference_point_mm"] = nums(l.recording.reference_point_mm);
    rec["signal_point_mm"] = nums(l.recording.signal_point_mm);
    rec["phase_conjugate"] = l.recording.phase_conjugate;
    appendUnknown(rec, u, ptr + "/recording");
    o["recording"] = rec;
    appendUnknown(o, u, ptr);
    layers.push_back(o);
  }
  root["hoe_layers"] = layers;

  ojson e;
  e["eyeball_diameter_mm"] = num(s.eye.eyeball_diameter_mm);
  e["pupil_diameter_mm"] = num(s.eye.pupil_diameter_mm);
  e["relief_mm"] = num(s.eye.relief_mm);
  e["lateral_offset_mm"] = nums(s.eye.lateral_offset_mm);
  e["gaze_deg"] = nums(s.eye.gaze_deg);
  e["gaze_range_deg"] = nums(s.eye.gaze_range_deg);
  e["fovea_radius_deg"] = num(s.eye.fovea_radius_deg);
  appendUnknown(e, u, "/eye");
  root["eye"] = e;

  ojson f;
  f["name"] = s.foveal_display.name;
  writePose(f, s.foveal_display.pose);
  f["size_mm"] = nums(s.foveal_display.size_mm);
  f["pixels"] = ints(s.foveal_display.pixels);
  f["primaries_nm"] = nums(s.foveal_display.primaries_nm);
  {
    const auto& ic = s.foveal_display.combiner;
    ojson c;
    c["name"] = ic.name;
    c["magnification"] = num(ic.magnification);
    c["eye_distance_mm"] = num(ic.eye_distance_mm);
    c["image_distance_mm"] = num(ic.image_distance_mm);
    c["mtf30_cpd_on_axis"] = num(ic.mtf30_cpd_on_axis);
    c["field_curvature_per_deg2"] = num(ic.field_curvature_per_deg2);
    appendUnknown(c, u, "/foveal_display/combiner");
    f["combiner"] = c;
  }
  appendUnknown(f, u, "/foveal_display");
  root["foveal_display"] = f;

  ojson l;
  l["enabled"] = s.lens.enabled;
  l["name"] = s.lens.name;
  writePose(l, s.lens.pose);
  l["focal_length_mm"] = num(s.lens.focal_length_mm);
  l["diameter_mm"] = num(s.lens.diameter_mm);
  l["center_thickness_mm"] = num(s.lens.center_thickness_mm);
  l["index"] = num(s.lens.index);
  appendUnknown(l, u, "/beam_shaping_lens");
  root["beam_shaping_lens"] = l;

  ojson fv;
  fv["blur_start_deg"] = num(s.foveation.blur_start_deg);
  fv["blend_start_deg"] = num(s.foveation.blend_start_deg);
  fv["blend_end_deg"] = num(s.foveation.blend_end_deg);
  appendUnknown(fv, u, "/foveation");
  root["foveation"] = fv;

  ojson stages = ojson::array();
  for (std::size_t i = 0; i < s.stages.size(); ++i) {
    const auto& st = s.stages[i];
    const std::string unit = isRotationAxis(st.axis) ? "_deg" : "_mm";
    ojson o;
    o["element"] = st.element;
    o["axis"] = st.axis;
    o["controller"] = st.controller;
    o["stage_model"] = st.stage_model;
    o["serial"] = st.serial;
    o["channel"] = st.channel;
    o["soft_limits" + unit] = nums(st.soft_limits);
    o["home_offset" + unit] = num(st.home_offset);
    appendUnknown(o, u, "/stages/" + std::to_string(i));
    stages.push_back(o);
  }
  root["stages"] = stages;
  appendUnknown(root, u, "/");
  return root.dump(2) + "\n";
}

void writeFileAtomic(const std::filesystem::path& path, std::string_view text,
                     const std::function<void()>& beforeRename) {
  namespace fs = std::filesystem;
  const fs::path target = saveTarget(path);  // through symlinks: replace the link's target, not the link
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code dir_ec;
  if (fs::is_directory(target, dir_ec)) throw SceneIoError(path.string() + ": is a directory, not a file");
  std::string tmpl = saveTemporaryTemplate(target);
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw SceneIoError(path.string() + ": cannot create a temporary file in " + dir.string() + ": " +
                                 std::strerror(errno));
  ::flock(fd, LOCK_EX);  // marks the temporary file as in use (removeStaleSaveTemporaries)
  const std::string tmp(name.data());
  auto fail = [&](const std::string& why) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw SceneIoError(path.string() + ": save failed (" + why + "); the existing file is unchanged");
  };
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(std::string("write: ") + std::strerror(errno));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail(std::string("fsync: ") + std::strerror(errno));
  // Keep the target's permissions when replacing it (mkstemp creates 0600).
  std::error_code ec;
  const auto st = fs::status(target, ec);
  ::fchmod(fd, ec || !fs::exists(st) ? 0644 : static_cast<mode_t>(st.permissions()) & 0777);
  if (::close(fd) != 0) {
    ::unlink(tmp.c_str());
    throw SceneIoError(path.string() + ": save failed (close: " + std::strerror(errno) +
                       "); the existing file is unchanged");
  }
  try {
    if (beforeRename) beforeRename();
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
  if (::rename(tmp.c_str(), target.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw SceneIoError(path.string() + ": save failed (rename: " + why + "); the existing file is unchanged");
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
  return o.str();
}

}  // namespace fovea
