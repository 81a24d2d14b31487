// fovea-cli merge PARTS... --json: combines the parts of a sharded run into the document one
// unsharded run prints; the kind comes from the parts: tolerance (`fovea-cli tolerance ...
// --shard K/N --json`, fovea-tolerance-part) or sweep (`fovea-cli sweep ... --shard K/N --json`,
// fovea-sweep-part: the eye-box borders are bisected here, on the scene the parts carry).
#include <fstream>
#include <iostream>
#include <memory>

#include "app/cli/cli_common.h"
#include "model/analysis/sweep_shards.h"
#include "model/analysis/tolerance_run.h"
#include "model/io/json_input.h"

namespace fovea::cli {

namespace cmd_merge {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("merge", "Merge the parts of a sharded run (tolerance --shard K/N) into one result");
  auto parts = std::make_shared<std::vector<std::string>>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("PARTS", *parts, "part files (JSON), one per shard, any order")->required();
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=] {
    std::vector<nlohmann::json> docs;
    for (const auto& p : *parts) {
      try {
        docs.push_back(readJsonFile(p));
      } catch (const std::exception& e) {
        inputError(std::string("merge: ") + e.what() + " (an unfinished part?)");
      }
    }
    const std::string kind = docs[0].is_object() ? docs[0].value("format", std::string()) : std::string();
    for (std::size_t i = 1; i < docs.size(); ++i)
      if (!docs[i].is_object() || docs[i].value("format", std::string()) != kind)
        inputError("merge: part " + std::to_string(i + 1) + " is not a " + kind + " like part 1 (" + (*parts)[i] + ")");
    const bool sweep = kind == "fovea-sweep-part";
    nlohmann::json r;
    try {
      if (sweep) {
        Progress progress("merge");
        StudyControl control;
        control.on_progress = [&progress](double f) { progress.update(f); };
        const auto merged = analysis::mergeSweepParts(docs, control, *parts);
        if (!merged) inputError("merge did not complete");
        r = *merged;
        r["cached"] = false;  // as `fovea-cli sweep` prints a computed sweep
      } else if (kind == "fovea-tolerance-part") {
        r = mergeToleranceParts(docs, *parts);
      } else {
        inputError("merge: part 1 is neither a fovea-tolerance-part nor a fovea-sweep-part (" + (*parts)[0] + ")");
      }
    } catch (const CliError&) {
      throw;
    } catch (const std::invalid_argument& e) {
      inputError(e.what());
    } catch (const std::runtime_error& e) {
      inputError(e.what());
    }
    if (*json) {
      printJson(r);
      return;
    }
    if (sweep)
      std::cout << "merged " << docs.size() << " parts: " << r["samples"].size() << " gazes, eye box "
                << r["eyebox_mm"].get<double>() << " mm\n";
    else
      std::cout << "merged " << docs.size() << " parts: yield " << r["yield"]["value"].get<double>() * 100 << " % over "
                << r["yield"]["trials"] << " trials\n";
  });
}

const Registrar reg{"merge", &install};

}  // namespace
}  // namespace cmd_merge
}  // namespace fovea::cli
