// fovea-cli grating: diffraction of one planar volume grating (contract: docs/physics.md), single shot
// or --batch JSONL. The physics lives in model/physics; this file parses, validates and
// dispatches to a grating model by name (--model). To add a model, append it to models().
#include <fstream>
#include <iostream>
#include <memory>

#include "app/cli/cli_common.h"
#include "model/physics/grating_request.h"

namespace fovea::cli {
namespace {

// A grating model answers one validated request with at least the contract's keys
// {"efficiency","type","nu","xi","diffracted_deg"}. It may throw std::exception for a
// request it cannot evaluate (the batch reports it for that line).
struct GratingModel {
  const char* name;
  nlohmann::json (*evaluate)(const GratingRequest&);
};
const std::vector<GratingModel>& models() {
  static const std::vector<GratingModel> m{{"kogelnik", &kogelnikGratingJson}};
  return m;
}
const GratingModel* findModel(const std::string& name) {
  for (const auto& m : models())
    if (name == m.name) return &m;
  return nullptr;
}
std::string modelNames() {
  std::string s;
  for (const auto& m : models()) s += (s.empty() ? "" : ", ") + std::string(m.name);
  return s;
}

struct GratingArgs {
  double n0 = 0, n1 = 0, thickness_um = 0, period_nm = 0, slant_deg = 0, probe_deg = 0, wavelength_nm = 0;
  double absorption_per_mm = 0.0;
  std::string polarization = "s";
  std::string model = "kogelnik";
  std::string batch;
  bool json = false;
};

nlohmann::json evaluateLine(const std::string& line, const std::string& default_model) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(line);
  } catch (const std::exception& e) {
    return {{"error", std::string("not valid JSON: ") + e.what()}};
  }
  if (j.is_object() && !j.contains("model")) j["model"] = default_model;
  auto parsed = gratingRequestFromJson(j);
  if (auto* e = std::get_if<GratingArgError>(&parsed)) return {{"error", e->message}};
  const auto& req = std::get<GratingRequest>(parsed);
  const GratingModel* m = findModel(req.model);
  if (!m) return {{"error", "model: unknown grating model '" + req.model + "' (known: " + modelNames() + ")"}};
  try {
    return m->evaluate(req);
  } catch (const std::exception& e) {
    return {{"error", e.what()}};
  }
}

void runBatch(const GratingArgs& a) {
  std::ifstream file;
  std::istream* in = &std::cin;
  if (a.batch != "-") {
    file.open(a.batch);
    if (!file) inputError("--batch: cannot read '" + a.batch + "'");
    in = &file;
  }
  std::string line;
  while (std::getline(*in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank lines carry no request
    printJson(evaluateLine(line, a.model), true);
  }
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "grating", "Kogelnik coupled-wave diffraction of a planar volume grating (x-z plane, z = film normal)");
  auto a = std::make_shared<GratingArgs>();
  cmd->add_option("--n0", a->n0, "mean refractive index");
  cmd->add_option("--n1", a->n1, "index modulation amplitude");
  cmd->add_option("--thickness-um", a->thickness_um, "film thickness (µm)");
  cmd->add_option("--period-nm", a->period_nm, "fringe period Lambda (nm)");
  cmd->add_option("--slant-deg", a->slant_deg, "angle of K from the film normal (90 = unslanted transmission)");
  cmd->add_option("--probe-deg", a->probe_deg, "probe angle inside the medium from the normal");
  cmd->add_option("--wavelength-nm", a->wavelength_nm, "vacuum wavelength (nm)");
  cmd->add_option("--polarization", a->polarization, "s (default), p or unpolarized");
  cmd->add_option("--absorption-per-mm", a->absorption_per_mm, "intensity absorption coefficient of the film (1/mm)");
  cmd->add_option("--model", a->model, "grating model: kogelnik (default)");
  cmd->add_option("--batch", a->batch, "JSONL file ('-' = stdin): one request per line -> one JSON line each");
  cmd->add_flag("--json", a->json, "print {\"efficiency\",\"type\",\"nu\",\"xi\",\"diffracted_deg\",…}");
  cmd->callback([cmd, a] {
    if (!findModel(a->model))
      usageError("--model: unknown grating model '" + a->model + "' (known: " + modelNames() + ")");
    if (!a->batch.empty()) return runBatch(*a);
    for (const char* flag :
         {"--n0", "--n1", "--thickness-um", "--period-nm", "--slant-deg", "--probe-deg", "--wavelength-nm"})
      if (cmd->count(flag) == 0) usageError(std::string(flag) + ": required (or use --batch)");
    GratingRequest r;
    r.grating.film.n0 = a->n0;
    r.grating.film.n1 = a->n1;
    r.grating.film.thickness_um = a->thickness_um;
    r.grating.period_nm = a->period_nm;
    r.grating.slant_deg = a->slant_deg;
    r.grating.probe_deg = a->probe_deg;
    r.grating.wavelength_nm = a->wavelength_nm;
    r.absorption_per_mm = a->absorption_per_mm;
    r.model = a->model;
    const auto pol = parsePolarization(a->polarization);
    if (!pol) usageError("--polarization: unknown polarisation '" + a->polarization + "' (s, p or unpolarized)");
    r.grating.polarization = *pol;
    if (auto e = validateGratingRequest(r, true)) usageError(e->message);
    const nlohmann::json out = findModel(r.model)->evaluate(r);
    if (a->json) return printJson(out);
    std::cout << out["type"].get<std::string>() << " grating: efficiency " << out["efficiency"] << ", nu " << out["nu"]
              << ", xi " << out["xi"] << ", diffracted " << out["diffracted_deg"].dump() << " deg\n";
  });
}

const Registrar reg{"grating", &install};

}  // namespace
}  // namespace fovea::cli
