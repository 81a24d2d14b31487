// fovea-cli merge PARTS... --json: combines the parts of a sharded tolerance run
// (`fovea-cli tolerance ... --shard K/N --json`) into the document one unsharded run prints.
#include <fstream>
#include <iostream>
#include <memory>

#include "app/cli/cli_common.h"
#include "model/analysis/tolerance_run.h"

namespace fovea::cli {

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
      std::ifstream f(p, std::ios::binary);
      if (!f) inputError("merge: cannot read " + p);
      try {
        docs.push_back(nlohmann::json::parse(f));
      } catch (const nlohmann::json::parse_error& e) {
        inputError("merge: " + p + ": not JSON (an unfinished part?): " + e.what());
      }
    }
    nlohmann::json r;
    try {
      r = mergeToleranceParts(docs);
    } catch (const std::exception& e) {
      inputError(e.what());
    }
    if (*json) {
      printJson(r);
      return;
    }
    std::cout << "merged " << docs.size() << " parts: yield " << r["yield"]["value"].get<double>() * 100 << " % over "
              << r["yield"]["trials"] << " trials\n";
  });
}

const Registrar reg{"merge", &install};

}  // namespace
}  // namespace fovea::cli
