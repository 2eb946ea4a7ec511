// `hba simulate`: not implemented yet.
#include "commands.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

void registerSimulateCommand(CLI::App& app) {
  auto* command = app.add_subcommand("simulate", "(not implemented yet)");
  command->callback([] { throw Error("hba simulate is not implemented yet"); });
}

}  // namespace hba::cli
