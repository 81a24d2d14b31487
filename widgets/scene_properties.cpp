#include "widgets/scene_properties.h"

#include <QLocale>

#include "model/scene/scene_io.h"
#include "viz/scene_elements.h"

namespace fovea::widgets {

namespace {

using Kind = PropertySpec::Kind;

// Builds specs for one element; `path` prefixes keys ("eye", "hoe_layers[1]").
class Specs {
 public:
  explicit Specs(QString path) : path_(std::move(path)) {}
  std::vector<PropertySpec> out;
  void group(const QString& g) { group_ = g; }

  void number(const QString& key, const QString& label, const QString& unit, const QString& range,
              std::function<double&(Scene&)> ref) {
    add(
        key, label, unit, range, Kind::Number, [ref](const Scene& s) { return QVariant(ref(const_cast<Scene&>(s))); },
        [ref](Scene& s, const QVariant& v) { ref(s) = v.toDouble(); });
  }
  void integer(const QString& key, const QString& label, const QString& unit, const QString& range,
               std::function<int&(Scene&)> ref) {
    add(
        key, label, unit, range, Kind::Integer, [ref](const Scene& s) { return QVariant(ref(const_cast<Scene&>(s))); },
        [ref](Scene& s, const QVariant& v) { ref(s) = v.toInt(); });
  }
  void boolean(const QString& key, const QString& label, std::function<bool&(Scene&)> ref) {
    add(
        key, label, {}, {}, Kind::Bool, [ref](const Scene& s) { return QVariant(ref(const_cast<Scene&>(s))); },
        [ref](Scene& s, const QVariant& v) { ref(s) = v.toBool(); });
  }
  void text(const QString& key, const QString& label, std::function<std::string&(Scene&)> ref,
            const QStringList& choices = {}) {
    add(
        key, label, {}, {}, choices.isEmpty() ? Kind::Text : Kind::Choice,
        [ref](const Scene& s) { return QVariant(QString::fromStdString(ref(const_cast<Scene&>(s)))); },
        [ref](Scene& s, const QVariant& v) { ref(s) = v.toString().toStdString(); });
    out.back().choices = choices;
  }
  void list(const QString& key, const QString& label, const QString& unit, const QString& range,
            std::function<std::vector<double>&(Scene&)> ref) {
    add(
        key, label, unit, range, Kind::NumberList,
        [ref](const Scene& s) {
          QVariantList l;
          for (double d : ref(const_cast<Scene&>(s))) l << d;
          return QVariant(l);
        },
        [ref](Scene& s, const QVariant& v) {
          std::vector<double> d;
          for (const auto& x : v.toList()) d.push_back(x.toDouble());
          ref(s) = d;
        });
  }
  template <std::size_t N>
  void vector(const QString& key, const QStringList& labels, const QString& unit, const QString& range,
              std::function<std::array<double, N>&(Scene&)> ref) {
    for (std::size_t i = 0; i < N; ++i)
      number(QStringLiteral("%1[%2]").arg(key).arg(i), labels[static_cast<int>(i)], unit, range,
             [ref, i](Scene& s) -> double& { return ref(s)[i]; });
  }
  template <std::size_t N>
  void ints(const QString& key, const QStringList& labels, const QString& unit, const QString& range,
            std::function<std::array<int, N>&(Scene&)> ref) {
    for (std::size_t i = 0; i < N; ++i)
      integer(QStringLiteral("%1[%2]").arg(key).arg(i), labels[static_cast<int>(i)], unit, range,
              [ref, i](Scene& s) -> int& { return ref(s)[i]; });
  }
  void pose(std::function<Pose&(Scene&)> ref) {
    group("Pose");
    vector<3>("position_mm", {"Position x", "Position y", "Position z"}, "mm", "[-1e5, 1e5]",
              [ref](Scene& s) -> Vec3mm& { return ref(s).position_mm; });
    vector<3>("rotation_deg", {"Yaw", "Pitch", "Roll"}, "deg", "[-360, 360]",
              [ref](Scene& s) -> std::array<double, 3>& { return ref(s).rotation_deg; });
  }

 private:
  void add(const QString& key, const QString& label, const QString& unit, const QString& range, Kind kind,
           std::function<QVariant(const Scene&)> get, std::function<void(Scene&, const QVariant&)> set) {
    PropertySpec p;
    p.key = path_ + "." + key;
    p.group = group_;
    p.label = label;
    p.unit = unit;
    p.range = range;
    p.kind = kind;
    p.get = std::move(get);
    p.set = std::move(set);
    out.push_back(std::move(p));
  }
  QString path_;
  QString group_;
};

const QString kPos = "> 0", kNonNeg = ">= 0", kIdx = "[1, 4]", kCoord = "[-1e5, 1e5]", kWl = "(200, 2000)";

std::vector<PropertySpec> projector() {
  Specs s("projector");
  s.group("Identity");
  s.text("name", "Name", [](Scene& x) -> std::string& { return x.projector.name; });
  s.pose([](Scene& x) -> Pose& { return x.projector.pose; });
  s.group("Image");
  s.ints<2>("pixels", {"Pixels horizontal", "Pixels vertical"}, "px", "[1, 100000]",
            [](Scene& x) -> std::array<int, 2>& { return x.projector.pixels; });
  s.vector<2>("fov_deg", {"FOV horizontal", "FOV vertical"}, "deg", "(0, 180)",
              [](Scene& x) -> std::array<double, 2>& { return x.projector.fov_deg; });
  s.list("wavelengths_nm", "Wavelengths", "nm", kWl,
         [](Scene& x) -> std::vector<double>& { return x.projector.wavelengths_nm; });
  s.number("exit_pupil_diameter_mm", "Exit pupil diameter", "mm", kPos,
           [](Scene& x) -> double& { return x.projector.exit_pupil_diameter_mm; });
  s.group("Pixel beam");
  auto& b = s;
  b.number("pixel_beam.waist_distance_mm", "Waist distance", "mm", kPos,
           [](Scene& x) -> double& { return x.projector.pixel_beam.waist_distance_mm; });
  b.number("pixel_beam.waist_fwhm_um", "Waist FWHM", "um", kPos,
           [](Scene& x) -> double& { return x.projector.pixel_beam.waist_fwhm_um; });
  b.number("pixel_beam.divergence_mrad", "Divergence (full, FWHM)", "mrad", kNonNeg,
           [](Scene& x) -> double& { return x.projector.pixel_beam.divergence_mrad; });
  b.number("pixel_beam.exit_fwhm_um", "Exit FWHM (long axis)", "um", kPos,
           [](Scene& x) -> double& { return x.projector.pixel_beam.exit_fwhm_um; });
  b.number("pixel_beam.exit_ellipticity", "Exit ellipticity", "", "[1, 100]",
           [](Scene& x) -> double& { return x.projector.pixel_beam.exit_ellipticity; });
  return std::move(s.out);
}

std::vector<PropertySpec> hoe() {
  Specs s("hoe");
  s.group("Identity");
  s.text("name", "Name", [](Scene& x) -> std::string& { return x.hoe.name; });
  s.pose([](Scene& x) -> Pose& { return x.hoe.pose; });
  s.group("Plate");
  s.vector<2>("size_mm", {"Width", "Height"}, "mm", "(0, 1e4)",
              [](Scene& x) -> std::array<double, 2>& { return x.hoe.size_mm; });
  s.number("substrate_thickness_mm", "Substrate thickness", "mm", "[0, 100]",
           [](Scene& x) -> double& { return x.hoe.substrate_thickness_mm; });
  s.number("cover_index", "Cover index (eye side)", "", kIdx, [](Scene& x) -> double& { return x.hoe.cover_index; });
  s.number("substrate_index", "Substrate index (world side)", "", kIdx,
           [](Scene& x) -> double& { return x.hoe.substrate_index; });
  return std::move(s.out);
}

std::vector<PropertySpec> layer(std::size_t i) {
  Specs s(viz::hoeLayerId(static_cast<int>(i)));
  auto L = [i](Scene& x) -> HoeLayer& { return x.hoe_layers.at(i); };
  s.group("Film");
  s.text("name", "Name", [L](Scene& x) -> std::string& { return L(x).name; });
  s.number("thickness_um", "Thickness", "um", "(0, 10000]", [L](Scene& x) -> double& { return L(x).thickness_um; });
  s.number("offset_um", "Offset along normal", "um", "[-1e5, 1e5]",
           [L](Scene& x) -> double& { return L(x).offset_um; });
  s.number("n0", "Mean index n0", "", kIdx, [L](Scene& x) -> double& { return L(x).n0; });
  s.number("n1", "Index modulation n1", "", "[0, n0)", [L](Scene& x) -> double& { return L(x).n1; });
  s.number("absorption_per_mm", "Absorption", "1/mm", kNonNeg,
           [L](Scene& x) -> double& { return L(x).absorption_per_mm; });
  s.number("shrinkage_percent", "Shrinkage", "%", "(-50, 50)",
           [L](Scene& x) -> double& { return L(x).shrinkage_percent; });
  s.number("recording_n0_delta", "n0 change since recording", "", "[-0.5, 0.5]",
           [L](Scene& x) -> double& { return L(x).recording_n0_delta; });
  s.group("Recording");
  s.number("recording.wavelength_nm", "Recording wavelength", "nm", kWl,
           [L](Scene& x) -> double& { return L(x).recording.wavelength_nm; });
  s.vector<3>("recording.reference_point_mm", {"Reference x", "Reference y", "Reference z"}, "mm", kCoord,
              [L](Scene& x) -> Vec3mm& { return L(x).recording.reference_point_mm; });
  s.vector<3>("recording.signal_point_mm", {"Signal focus x", "Signal focus y", "Signal focus z"}, "mm", kCoord,
              [L](Scene& x) -> Vec3mm& { return L(x).recording.signal_point_mm; });
  s.boolean("recording.phase_conjugate", "Phase-conjugate recording",
            [L](Scene& x) -> bool& { return L(x).recording.phase_conjugate; });
  return std::move(s.out);
}

std::vector<PropertySpec> eye() {
  Specs s("eye");
  s.group("Anatomy");
  s.number("eyeball_diameter_mm", "Eyeball diameter", "mm", "(5, 50)",
           [](Scene& x) -> double& { return x.eye.eyeball_diameter_mm; });
  s.number("pupil_diameter_mm", "Pupil diameter", "mm", "(0, 15)",
           [](Scene& x) -> double& { return x.eye.pupil_diameter_mm; });
  s.number("fovea_radius_deg", "Foveal radius", "deg", "(0, 45)",
           [](Scene& x) -> double& { return x.eye.fovea_radius_deg; });
  s.group("Placement");
  s.number("relief_mm", "Eye relief", "mm", kPos, [](Scene& x) -> double& { return x.eye.relief_mm; });
  s.vector<2>("lateral_offset_mm", {"Lateral offset x", "Lateral offset y"}, "mm", kCoord,
              [](Scene& x) -> std::array<double, 2>& { return x.eye.lateral_offset_mm; });
  s.group("Gaze");
  s.vector<2>("gaze_deg", {"Gaze yaw", "Gaze pitch"}, "deg", "(-90, 90)",
              [](Scene& x) -> std::array<double, 2>& { return x.eye.gaze_deg; });
  s.vector<2>("gaze_range_deg", {"Gaze range from", "Gaze range to"}, "deg", "(-90, 90)",
              [](Scene& x) -> std::array<double, 2>& { return x.eye.gaze_range_deg; });
  return std::move(s.out);
}

std::vector<PropertySpec> fovealDisplay() {
  Specs s("foveal_display");
  s.group("Identity");
  s.text("name", "Name", [](Scene& x) -> std::string& { return x.foveal_display.name; });
  s.pose([](Scene& x) -> Pose& { return x.foveal_display.pose; });
  s.group("Panel");
  s.vector<2>("size_mm", {"Active width", "Active height"}, "mm", "(0, 1e4)",
              [](Scene& x) -> std::array<double, 2>& { return x.foveal_display.size_mm; });
  s.ints<2>("pixels", {"Pixels horizontal", "Pixels vertical"}, "px", "[1, 100000]",
            [](Scene& x) -> std::array<int, 2>& { return x.foveal_display.pixels; });
  s.list("primaries_nm", "Primaries", "nm", kWl,
         [](Scene& x) -> std::vector<double>& { return x.foveal_display.primaries_nm; });
  s.group("Image combiner");
  auto C = [](Scene& x) -> ImageCombiner& { return x.foveal_display.combiner; };
  s.text("combiner.name", "Combiner name", [C](Scene& x) -> std::string& { return C(x).name; });
  s.number("combiner.magnification", "Magnification", "x", kPos,
           [C](Scene& x) -> double& { return C(x).magnification; });
  s.number("combiner.eye_distance_mm", "Distance to pupil", "mm", kPos,
           [C](Scene& x) -> double& { return C(x).eye_distance_mm; });
  s.number("combiner.image_distance_mm", "Virtual image distance", "mm", kPos,
           [C](Scene& x) -> double& { return C(x).image_distance_mm; });
  s.number("combiner.mtf30_cpd_on_axis", "MTF30 on axis", "cyc/deg", kPos,
           [C](Scene& x) -> double& { return C(x).mtf30_cpd_on_axis; });
  s.number("combiner.field_curvature_per_deg2", "Field curvature", "1/deg^2", kNonNeg,
           [C](Scene& x) -> double& { return C(x).field_curvature_per_deg2; });
  return std::move(s.out);
}

std::vector<PropertySpec> lens() {
  Specs s("beam_shaping_lens");
  s.group("Identity");
  s.boolean("enabled", "In the beam path", [](Scene& x) -> bool& { return x.lens.enabled; });
  s.text("name", "Name", [](Scene& x) -> std::string& { return x.lens.name; });
  s.pose([](Scene& x) -> Pose& { return x.lens.pose; });
  s.group("Optics");
  s.number("focal_length_mm", "Focal length", "mm", "[-1e5, 1e5], != 0",
           [](Scene& x) -> double& { return x.lens.focal_length_mm; });
  s.number("diameter_mm", "Diameter", "mm", kPos, [](Scene& x) -> double& { return x.lens.diameter_mm; });
  s.number("center_thickness_mm", "Centre thickness", "mm", kNonNeg,
           [](Scene& x) -> double& { return x.lens.center_thickness_mm; });
  s.number("index", "Refractive index", "", kIdx, [](Scene& x) -> double& { return x.lens.index; });
  return std::move(s.out);
}

std::vector<PropertySpec> foveation() {
  Specs s("foveation");
  s.group("Blend (blur start <= blend start < blend end)");
  s.number("blur_start_deg", "Blur starts", "deg", "[0, 90]",
           [](Scene& x) -> double& { return x.foveation.blur_start_deg; });
  s.number("blend_start_deg", "Blend starts", "deg", "[0, 90]",
           [](Scene& x) -> double& { return x.foveation.blend_start_deg; });
  s.number("blend_end_deg", "Blend ends", "deg", "[0, 90]",
           [](Scene& x) -> double& { return x.foveation.blend_end_deg; });
  return std::move(s.out);
}

std::vector<PropertySpec> stage(const Scene& scene, std::size_t i) {
  Specs s(viz::stageId(static_cast<int>(i)));
  auto S = [i](Scene& x) -> StageBinding& { return x.stages.at(i); };
  const auto& axis = scene.stages[i].axis;
  const bool rotation = axis == "yaw" || axis == "pitch" || axis == "roll";
  const QString unit = rotation ? "deg" : "mm", suffix = rotation ? "_deg" : "_mm";
  s.group("Binding");
  s.text("element", "Element", [S](Scene& x) -> std::string& { return S(x).element; },
         {"hoe", "foveal_display", "projector", "beam_shaping_lens", "camera"});
  s.text("axis", "Axis", [S](Scene& x) -> std::string& { return S(x).axis; }, {"x", "y", "z", "yaw", "pitch", "roll"});
  s.group("Hardware");
  s.text("controller", "Controller", [S](Scene& x) -> std::string& { return S(x).controller; },
         {"KDC101", "TDC001", "KBD101", "K10CR1"});
  s.text("stage_model", "Stage", [S](Scene& x) -> std::string& { return S(x).stage_model; },
         {"MTS25-Z8", "Z825B", "DDSM50", "K10CR1"});
  s.text("serial", "Serial number", [S](Scene& x) -> std::string& { return S(x).serial; });
  s.integer("channel", "Channel", "", "[1, 4]", [S](Scene& x) -> int& { return S(x).channel; });
  s.group("Travel");
  s.vector<2>("soft_limits" + suffix, {"Soft limit low", "Soft limit high"}, unit, kCoord,
              [S](Scene& x) -> std::array<double, 2>& { return S(x).soft_limits; });
  s.number("home_offset" + suffix, "Home offset", unit, kCoord, [S](Scene& x) -> double& { return S(x).home_offset; });
  return std::move(s.out);
}

}  // namespace

std::vector<PropertySpec> propertiesOf(const Scene& scene, const QString& id) {
  if (id == "projector") return projector();
  if (id == "hoe") return hoe();
  if (id == "eye") return eye();
  if (id == "foveal_display") return fovealDisplay();
  if (id == "beam_shaping_lens") return lens();
  if (id == "foveation") return foveation();
  if (int i = viz::indexedElement(id, "hoe_layers"); i >= 0 && i < static_cast<int>(scene.hoe_layers.size()))
    return layer(static_cast<std::size_t>(i));
  if (int i = viz::indexedElement(id, "stages"); i >= 0 && i < static_cast<int>(scene.stages.size()))
    return stage(scene, static_cast<std::size_t>(i));
  return {};
}

QString formatValue(const PropertySpec& spec, const QVariant& value) {
  switch (spec.kind) {
    case Kind::Number:
      return QString::fromStdString(formatNumber(value.toDouble()));
    case Kind::Integer:
      return QString::number(value.toInt());
    case Kind::Bool:
      return value.toBool() ? "true" : "false";
    case Kind::NumberList: {
      QStringList parts;
      for (const auto& v : value.toList()) parts << QString::fromStdString(formatNumber(v.toDouble()));
      return parts.join(", ");
    }
    case Kind::Text:
    case Kind::Choice:
      return value.toString();
  }
  return {};
}

QVariant parseValue(const PropertySpec& spec, const QString& raw, QString* error) {
  const QString text = raw.trimmed();
  const QLocale c = QLocale::c();
  bool ok = false;
  switch (spec.kind) {
    case Kind::Number: {
      const double d = c.toDouble(text, &ok);
      if (!ok) {
        *error = QStringLiteral("%1: not a number: \"%2\"").arg(spec.key, text);
        return {};
      }
      return d;
    }
    case Kind::Integer: {
      const int i = c.toInt(text, &ok);
      if (!ok) {
        *error = QStringLiteral("%1: not an integer: \"%2\"").arg(spec.key, text);
        return {};
      }
      return i;
    }
    case Kind::NumberList: {
      QVariantList list;
      for (const QString& part : text.split(',', Qt::SkipEmptyParts)) {
        const double d = c.toDouble(part.trimmed(), &ok);
        if (!ok) {
          *error = QStringLiteral("%1: not a number: \"%2\"").arg(spec.key, part.trimmed());
          return {};
        }
        list << d;
      }
      return list;
    }
    case Kind::Bool:
      return text == "true";
    case Kind::Text:
    case Kind::Choice:
      return text;
  }
  return {};
}

}  // namespace fovea::widgets
