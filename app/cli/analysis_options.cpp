#include "app/cli/analysis_options.h"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "app/cli/cli_common.h"

namespace fovea::cli {

using analysis::AnalysisDefinition;
using analysis::OptionGroup;
using analysis::ParameterKind;
using analysis::ParameterSpec;

namespace {
std::string defaultText(const ParameterSpec& spec) {
  if (spec.default_value.is_null()) return spec.unset_meaning.empty() ? "none" : spec.unset_meaning;
  if (spec.default_value.is_string()) return spec.default_value.get<std::string>();
  std::ostringstream s;
  s << std::setprecision(10) << spec.default_value.get<double>();
  return s.str();
}

// The problem of one command-line text for `spec`, or nothing (value set in `out`).
std::optional<std::string> textProblem(const ParameterSpec& spec, const std::string& text, nlohmann::json& out) {
  if (auto e = analysis::parseValueText(spec, text, out)) return e;
  return analysis::validateValue(spec, out);
}

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) items.push_back(item);
  if (!text.empty() && text.back() == ',') items.emplace_back();
  return items;
}
}  // namespace

std::string optionHelp(const ParameterSpec& spec) {
  std::string h = spec.help + " (";
  if (!spec.unit.empty()) h += spec.unit + ", ";
  h += "default " + defaultText(spec);
  if (spec.kind == ParameterKind::Number || spec.kind == ParameterKind::Integer) h += "; " + analysis::rangeText(spec);
  if (spec.kind == ParameterKind::Choice) {
    std::string all;
    for (const auto& c : spec.choices) all += (all.empty() ? "" : "|") + c;
    h += "; " + all;
  }
  return h + ")";
}

AnalysisOptions::AnalysisOptions(CLI::App* cmd, const AnalysisDefinition& def) : cmd_(cmd), def_(def) {
  for (const OptionGroup& g : def.option_groups) {
    std::string help = g.help + ":";
    for (const auto& m : g.members) help += " " + m + " " + optionHelp(*def.parameter(m)) + ";";
    help += g.repeatable ? " repeat it for several results" : "";
    std::string type;
    for (const auto& m : g.members) type += (type.empty() ? "" : ",") + std::string(type.empty() ? "" : "[") + m;
    type += std::string(g.members.size() - 1, ']');
    auto* o = cmd->add_option("--" + g.flag, groups_[g.flag], help)->type_name(type);
    if (!g.repeatable) o->expected(1);
    o->allow_extra_args(false);
  }
  for (const ParameterSpec& p : def.parameters) {
    if (def.groupOf(p.name)) continue;
    cmd->add_option("--" + p.name, scalars_[p.name], optionHelp(p))
        ->type_name(p.kind == ParameterKind::Integer  ? "INT"
                    : p.kind == ParameterKind::Number ? "NUMBER"
                                                      : "TEXT");
  }
}

nlohmann::json AnalysisOptions::collect(const std::string& occurrence_flag, std::size_t occurrence) const {
  nlohmann::json values = analysis::defaultValues(def_);
  std::vector<std::string> problems;
  for (const auto& [name, text] : scalars_) {
    if (cmd_->count("--" + name) == 0) continue;
    const ParameterSpec& spec = *def_.parameter(name);
    if (auto e = textProblem(spec, text, values[name])) problems.push_back("--" + name + ": " + *e);
  }
  for (const OptionGroup& g : def_.option_groups) {
    const auto& given = groups_.at(g.flag);
    if (given.empty()) continue;
    const std::string& text = g.flag == occurrence_flag ? given.at(occurrence) : given.front();
    const auto items = splitCommas(text);
    if (items.empty() || items.size() > g.members.size()) {
      problems.push_back("--" + g.flag + ": expected 1 to " + std::to_string(g.members.size()) +
                         " comma-separated numbers, got '" + text + "'");
      continue;
    }
    for (std::size_t i = 0; i < g.members.size(); ++i) {
      const ParameterSpec& spec = *def_.parameter(g.members[i]);
      nlohmann::json& v = values[spec.name];
      v = 0.0;  // trailing members left out are 0
      if (i < items.size())
        if (auto e = textProblem(spec, items[i], v)) problems.push_back("--" + g.flag + ": " + spec.name + " " + *e);
    }
  }
  if (problems.empty())
    for (const auto& p : analysis::validateValues(def_, values)) {
      const OptionGroup* g = def_.groupOf(p.parameter);
      problems.push_back(g ? "--" + g->flag + ": " + p.parameter + " " + p.message : p.text("--"));
    }
  if (!problems.empty()) {
    std::string all;
    for (const auto& p : problems) all += (all.empty() ? "" : "\n") + p;
    usageError(all);
  }
  return values;
}

nlohmann::json AnalysisOptions::values() const {
  return collect({}, 0);
}

std::vector<nlohmann::json> AnalysisOptions::valuesPerOccurrence(const std::string& flag) const {
  const auto& given = groups_.at(flag);
  if (given.empty()) return {collect({}, 0)};
  std::vector<nlohmann::json> out;
  for (std::size_t i = 0; i < given.size(); ++i) out.push_back(collect(flag, i));
  return out;
}

std::shared_ptr<AnalysisOptions> addAnalysisOptions(CLI::App* cmd, const std::string& id) {
  const AnalysisDefinition* def = analysis::findAnalysisDefinition(id);
  if (!def) throw std::logic_error("no registered analysis '" + id + "'");
  return std::make_shared<AnalysisOptions>(cmd, *def);
}

namespace {
template <class T>
CLI::Option* addChecked(CLI::App* cmd, const std::string& flag, T& target, const ParameterSpec& spec) {
  auto check = [spec](std::string& text) -> std::string {
    nlohmann::json v;
    if (auto e = textProblem(spec, text, v)) return *e;
    return {};
  };
  return cmd->add_option(flag, target, optionHelp(spec))->check(CLI::Validator(check, ""));
}
}  // namespace

CLI::Option* addCheckedOption(CLI::App* cmd, const std::string& flag, double& target, const ParameterSpec& spec) {
  return addChecked(cmd, flag, target, spec);
}
CLI::Option* addCheckedOption(CLI::App* cmd, const std::string& flag, int& target, const ParameterSpec& spec) {
  return addChecked(cmd, flag, target, spec);
}

}  // namespace fovea::cli
