// fovea-cli grating: diffraction of one planar volume grating (contract: docs/physics.md), single shot
// or --batch JSONL. The physics lives in model/physics (Kogelnik) and model/rigorous (RCWA);
// this file parses, validates and dispatches to a grating model by name (--model). To add a
// model, append it to models().
//
// --batch: every input line, blank ones included, gives exactly one output line — the answer,
// or {"error": "line N: …", "line": N} — and the exit status is 1 when any line failed.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <variant>

#include "app/cli/cli_common.h"
#include "model/io/json_input.h"
#include "model/physics/grating_request.h"
#include "model/rigorous/rcwa_grating_request.h"

namespace fovea::cli {
namespace cmd_grating {  // one per command file: fovea-cli compiles in unity batches
namespace {

// A grating model answers one validated request with at least the contract's keys
// {"efficiency","type","nu","xi","diffracted_deg"}. It may throw std::exception for a
// request it cannot evaluate (the batch reports it for that line).
struct GratingModel {
  const char* name;
  nlohmann::json (*evaluate)(const GratingRequest&);
};
const std::vector<GratingModel>& models() {
  static const std::vector<GratingModel> m{{"kogelnik", &kogelnikGratingJson}, {"rcwa", &rigorous::rcwaGratingJson}};
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
  int orders = 0, slices = 0;
  std::string polarization = "s";
  std::string model = "kogelnik";
  std::string batch;
  bool json = false;
  bool error_map_requests = false;
};

// A --batch line: at most 1 MiB (a request is ~200 bytes) and the common nesting limit.
constexpr JsonLimits kLineLimits{64, 1u << 20};

// The answer to one request line, or the reason it has none (without the "line N: " prefix).
std::variant<nlohmann::json, std::string> answerLine(const std::string& line, const std::string& default_model) {
  if (line.find_first_not_of(" \t\r") == std::string::npos) return std::string("blank line (expected a JSON object)");
  auto parsed = parseJsonText(line, kLineLimits);
  if (const auto* e = std::get_if<JsonInputError>(&parsed)) return describeInLine(*e);
  nlohmann::json& j = std::get<nlohmann::json>(parsed);
  if (j.is_object() && !j.contains("model")) j["model"] = default_model;
  auto request = gratingRequestFromJson(j);
  if (auto* e = std::get_if<GratingArgError>(&request)) return e->message;
  const auto& req = std::get<GratingRequest>(request);
  const GratingModel* m = findModel(req.model);
  if (!m) return "model: unknown grating model '" + printableExcerpt(req.model) + "' (known: " + modelNames() + ")";
  if ((req.orders || req.slices) && req.model != "rcwa")
    return std::string(req.orders ? "orders" : "slices") + ": only the rcwa model has orders and slices";
  try {
    return m->evaluate(req);
  } catch (const std::exception& e) {
    return printableExcerpt(e.what(), 400);
  }
}

// Reads one line of at most `max` bytes (the rest of a longer line is skipped); false at the end.
bool readLine(std::istream& in, std::string& line, std::size_t max, bool& too_long) {
  line.clear();
  too_long = false;
  std::streambuf* sb = in.rdbuf();
  bool any = false;
  for (int c = sb->sbumpc(); c != std::char_traits<char>::eof(); c = sb->sbumpc()) {
    any = true;
    if (c == '\n') return true;
    if (line.size() < max)
      line += char(c);
    else
      too_long = true;
  }
  return any;
}

void runBatch(const GratingArgs& a) {
  std::ifstream file;
  std::istream* in = &std::cin;
  if (a.batch != "-") {
    std::error_code ec;
    if (std::filesystem::is_directory(a.batch, ec))
      inputError("--batch: '" + a.batch + "' is a directory, not a file of JSON lines");
    file.open(a.batch, std::ios::binary);
    if (!file) inputError("--batch: cannot read '" + a.batch + "'");
    in = &file;
  }
  std::string line;
  bool too_long = false;
  long n = 0, failed = 0;
  while (readLine(*in, line, kLineLimits.max_bytes, too_long)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    auto answer = too_long ? std::string("too long: more than " + std::to_string(kLineLimits.max_bytes) + " bytes")
                           : answerLine(line, a.model);
    if (auto* reason = std::get_if<std::string>(&answer)) {
      ++failed;
      printJson({{"error", "line " + std::to_string(n) + ": " + *reason}, {"line", n}}, true);
    } else {
      printJson(std::get<nlohmann::json>(answer), true);
    }
  }
  if (failed > 0) inputError("--batch: " + std::to_string(failed) + " of " + std::to_string(n) + " line(s) failed");
}

void printErrorMapRequests() {
  for (const nlohmann::json& j : rigorous::errorMapRequests()) printJson(j, true);
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
  cmd->add_option("--model", a->model, "grating model: kogelnik (default) or rcwa (rigorous coupled waves)");
  cmd->add_option("--orders", a->orders, "rcwa: Fourier orders -N..N (default: converged automatically)");
  cmd->add_option("--slices", a->slices, "rcwa: staircase slices M (default: converged automatically)");
  cmd->add_flag("--error-map-requests", a->error_map_requests,
                "print the --batch lines of the Kogelnik-vs-RCWA error map of docs/benchmarks.md");
  cmd->add_option("--batch", a->batch, "JSONL file ('-' = stdin): one request per line -> one JSON line each");
  cmd->add_flag("--json", a->json, "print {\"efficiency\",\"type\",\"nu\",\"xi\",\"diffracted_deg\",…}");
  cmd->callback([cmd, a] {
    if (!findModel(a->model))
      usageError("--model: unknown grating model '" + a->model + "' (known: " + modelNames() + ")");
    if (a->error_map_requests) return printErrorMapRequests();
    if (a->model != "rcwa")
      for (const char* flag : {"--orders", "--slices"})
        if (cmd->count(flag) > 0) usageError(std::string(flag) + ": only the rcwa model has orders and slices");
    if (!a->batch.empty()) {
      if (cmd->count("--orders") + cmd->count("--slices") > 0)
        usageError("--orders/--slices: give them per line (\"orders\", \"slices\") with --batch");
      return runBatch(*a);
    }
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
    if (cmd->count("--orders") > 0) r.orders = a->orders;
    if (cmd->count("--slices") > 0) r.slices = a->slices;
    const auto pol = parsePolarization(a->polarization);
    if (!pol) usageError("--polarization: unknown polarisation '" + a->polarization + "' (s, p or unpolarized)");
    r.grating.polarization = *pol;
    if (auto e = validateGratingRequest(r, true)) usageError(e->message);
    nlohmann::json out;
    try {
      out = findModel(r.model)->evaluate(r);
    } catch (const std::exception& e) {
      inputError(printableExcerpt(e.what(), 400));
    }
    if (a->json) return printJson(out);
    std::cout << out["type"].get<std::string>() << " grating: efficiency " << out["efficiency"] << ", nu " << out["nu"]
              << ", xi " << out["xi"] << ", diffracted " << out["diffracted_deg"].dump() << " deg\n";
  });
}

const Registrar reg{"grating", &install};

}  // namespace
}  // namespace cmd_grating
}  // namespace fovea::cli
