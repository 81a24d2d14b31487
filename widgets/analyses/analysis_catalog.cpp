#include "widgets/analyses/analysis_catalog.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "model/scene/scene_io.h"

namespace fovea::widgets {

namespace {

using Kind = AnalysisParameter::Kind;
using analysis::ParameterKind;

QString q(const std::string& s) {
  return QString::fromStdString(s);
}

QVariant toVariant(const nlohmann::json& v) {
  if (v.is_number_integer()) return QVariant(v.get<int>());
  if (v.is_number()) return QVariant(v.get<double>());
  if (v.is_string()) return QVariant(q(v.get<std::string>()));
  return {};
}

// The form's spin boxes need finite bounds; "any finite number" shows as +-1e9.
double shownBound(double x) {
  return std::clamp(x, -1e9, 1e9);
}

AnalysisParameter parameterOf(const analysis::ParameterSpec& p) {
  AnalysisParameter a;
  a.key = q(p.name);
  a.label = q(p.label);
  a.unit = q(p.unit);
  a.kind = p.kind == ParameterKind::Number     ? Kind::Number
           : p.kind == ParameterKind::Integer  ? Kind::Integer
           : p.kind == ParameterKind::Choice   ? Kind::Choice
           : p.kind == ParameterKind::FilePath ? Kind::FilePath
                                               : Kind::Text;
  a.defaultValue = toVariant(p.default_value);
  a.minimum = shownBound(p.minimum);
  a.maximum = shownBound(p.maximum);
  if (p.minimum_exclusive) a.minimum = shownBound(p.minimum) + std::pow(10.0, -p.decimals);
  a.decimals = p.decimals;
  for (const auto& c : p.choices) a.choices << q(c);
  a.help = q(p.help);
  a.unsetMeaning = q(p.unset_meaning);
  return a;
}

QList<AnalysisSpec> buildCatalog() {
  QList<AnalysisSpec> c;
  for (const analysis::AnalysisDefinition& d : analysis::analysisRegistry()) {
    AnalysisSpec s;
    s.id = q(d.id);
    s.title = q(d.title);
    s.description = q(d.description);
    for (const auto& p : d.parameters) s.parameters << parameterOf(p);
    for (const auto& p : d.plots) s.plots << q(p);
    s.hasCliTwin = d.cli_twin;
    s.definition = &d;
    c << s;
  }
  return c;
}

QString problemsText(const std::vector<analysis::ParameterProblem>& problems, QStringList* list = nullptr) {
  QStringList all;
  for (const auto& p : problems) all << q(p.text());
  if (list) *list = all;
  return all.join("; ");
}

}  // namespace

const QList<AnalysisSpec>& analysisCatalog() {
  static const QList<AnalysisSpec> catalog = buildCatalog();
  return catalog;
}

const AnalysisSpec* findAnalysis(const QString& id) {
  for (const AnalysisSpec& s : analysisCatalog())
    if (s.id == id) return &s;
  return nullptr;
}

AnalysisParams defaultParameters(const AnalysisSpec& spec, int raysOverride) {
  AnalysisParams p = fromParameterValues(analysis::defaultValues(*spec.definition));
  if (raysOverride > 0 && p.contains("rays")) p["rays"] = raysOverride;
  return p;
}

nlohmann::json parameterValues(const AnalysisSpec& spec, const AnalysisParams& params) {
  nlohmann::json j = nlohmann::json::object();
  for (auto it = params.begin(); it != params.end(); ++it) {
    const QVariant& v = it.value();
    const std::string key = it.key().toStdString();
    const analysis::ParameterSpec* p = spec.definition->parameter(key);
    const bool numeric = p && (p->kind == ParameterKind::Number || p->kind == ParameterKind::Integer);
    if (!v.isValid() || v.isNull()) {
      j[key] = nullptr;
    } else if (v.typeId() == QMetaType::Double || v.typeId() == QMetaType::Float) {
      j[key] = v.toDouble();
    } else if (v.typeId() == QMetaType::Int || v.typeId() == QMetaType::LongLong) {
      j[key] = v.toLongLong();
    } else if (numeric) {
      // Text from an editable field: empty = unset, else the number it reads as (the
      // validator refuses what is not one, naming the parameter).
      const QString t = v.toString().trimmed();
      bool ok = false;
      const double x = t.toDouble(&ok);
      if (t.isEmpty())
        j[key] = nullptr;
      else if (ok)
        j[key] = x;
      else
        j[key] = t.toStdString();
    } else {
      j[key] = v.toString().toStdString();
    }
  }
  return j;
}

AnalysisParams fromParameterValues(const nlohmann::json& values) {
  AnalysisParams p;
  for (const auto& [k, v] : values.items()) p.insert(q(k), toVariant(v));
  return p;
}

QStringList validateParameters(const AnalysisSpec& spec, AnalysisParams& params) {
  nlohmann::json values = parameterValues(spec, params);
  QStringList problems;
  problemsText(analysis::validateValues(*spec.definition, values), &problems);
  if (problems.isEmpty()) params = fromParameterValues(values);
  return problems;
}

QString cliUnavailableReason(const AnalysisSpec& spec, const AnalysisParams& params) {
  if (!spec.definition->cli_unavailable) return {};
  nlohmann::json values = parameterValues(spec, params);
  analysis::validateValues(*spec.definition, values);
  const auto why = spec.definition->cli_unavailable(values);
  return why ? q(*why) : QString();
}

QString cliCommandLine(const AnalysisSpec& spec, const AnalysisParams& params, const QString& scenePath) {
  const analysis::AnalysisDefinition& def = *spec.definition;
  if (!def.cli_twin) return {};
  if (def.takes_scene && scenePath.isEmpty()) return {};
  nlohmann::json values = parameterValues(spec, params);
  analysis::validateValues(def, values);  // fills defaults; an invalid value is shown as it is
  if (def.cli_unavailable && def.cli_unavailable(values)) return {};
  auto shown = [&](const std::string& name) {
    const nlohmann::json& v = values[name];
    if (v.is_string()) return q(v.get<std::string>());
    return v.is_number_integer() ? QString::number(v.get<long long>()) : QString::number(v.get<double>(), 'g', 10);
  };
  auto quoted = [](const QString& v) {
    return v.contains(' ') || v.contains('[') || v.isEmpty() ? QString('"' + v + '"') : v;
  };
  QStringList a{"fovea-cli", spec.id};
  if (def.takes_scene) a << quoted(scenePath);
  std::vector<const analysis::OptionGroup*> written;
  for (const analysis::ParameterSpec& p : def.parameters) {
    if (p.studio_only) continue;
    if (const analysis::OptionGroup* g = def.groupOf(p.name)) {
      if (std::find(written.begin(), written.end(), g) != written.end()) continue;
      written.push_back(g);
      bool any = false;
      QStringList items;
      for (const auto& m : g->members) {
        any |= !values[m].is_null();
        items << (values[m].is_null() ? QStringLiteral("0") : shown(m));
      }
      if (any) a << "--" + q(g->flag) << items.join(',');
      continue;
    }
    if (values[p.name].is_null()) continue;  // unset: the command's default means the same
    a << "--" + q(p.name) << quoted(shown(p.name));
  }
  a << "--json";
  return a.join(' ');
}

std::optional<nlohmann::json> runAnalysis(const QString& id, const Scene& scene, const AnalysisParams& params,
                                          const StudyControl& control) {
  const AnalysisSpec* spec = findAnalysis(id);
  if (!spec) throw std::invalid_argument("unknown analysis '" + id.toStdString() + "'");
  const analysis::AnalysisDefinition& def = *spec->definition;
  nlohmann::json values = parameterValues(*spec, params);
  const auto problems = analysis::validateValues(def, values);
  if (!problems.empty()) throw std::invalid_argument(problemsText(problems).toStdString());
  if (control.cancelled()) return std::nullopt;

  std::string key;
  if (def.cached) {
    key = StudyCache::makeKey("studio:" + def.id, values, serializeScene(scene));
    if (auto hit = StudyCache::global().find(key)) {
      (*hit)["cached"] = true;
      if (control.on_progress) control.on_progress(1.0);
      return hit;
    }
  }
  std::optional<nlohmann::json> out = def.run(scene, values, control);
  if (!out || control.cancelled()) return std::nullopt;
  if (!key.empty()) StudyCache::global().store(key, *out);
  (*out)["cached"] = false;
  if (control.on_progress) control.on_progress(1.0);
  return out;
}

}  // namespace fovea::widgets
