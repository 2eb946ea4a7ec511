// `hba optimize`: not implemented yet.
#include "commands.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

void registerOptimizeCommand(CLI::App& app) {
  auto* command = app.add_subcommand("optimize", "(not implemented yet)");
  command->callback([] { throw Error("hba optimize is not implemented yet"); });
}

}  // namespace hba::cli
