// fovea-cli merge PARTS... --json: combines the parts of a sharded tolerance run
// (`fovea-cli tolerance ... --shard K/N --json`) into the document one unsharded run prints.
#include <fstream>
#include <iostream>
#include <memory>

#include "app/cli/cli_common.h"
#include "model/analysis/tolerance_run.h"
#include "model/io/json_input.h"

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
      try {
        docs.push_back(readJsonFile(p));
      } catch (const std::exception& e) {
        inputError(std::string("merge: ") + e.what() + " (an unfinished part?)");
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
