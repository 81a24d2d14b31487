// fovea-cli: the headless twin of every studio capability, JSON out.
#include <algorithm>
#include <iostream>

#include "app/cli/cli_common.h"
#include "fovea/version.h"
#include "model/io/output_file.h"
#include "model/memory_policy.h"

int main(int argc, char** argv) {
  fovea::keepFreedMemoryForReuse();  // large buffers reused between renders (model/memory_policy.h)
  CLI::App app{"fovea-cli: headless Foveated AR Studio (JSON output)", "fovea-cli"};
  app.set_version_flag("--version", FOVEA_VERSION_STRING);
  app.require_subcommand(1);
  auto& commands = fovea::cli::registry();
  std::sort(commands.begin(), commands.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (auto& [name, install] : commands) install(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "fovea-cli: " << e.what() << "\n";
    return 2;  // invalid arguments
  } catch (const fovea::cli::CliError& e) {
    std::cerr << "fovea-cli: " << e.what() << "\n";
    return e.code();
  } catch (const std::exception& e) {
    std::cerr << "fovea-cli: error: " << e.what() << "\n";
    return 1;
  }
  // Output nobody could read is not a success: a full disk, `> /dev/full`, a closed pipe.
  if (const auto why = fovea::checkStdout()) {
    std::cerr << "fovea-cli: " << *why << "\n";
    return 1;
  }
  return 0;
}
