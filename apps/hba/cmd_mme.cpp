// `hba mme`: not implemented yet.
#include "commands.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

void registerMmeCommand(CLI::App& app) {
  auto* command = app.add_subcommand("mme", "(not implemented yet)");
  command->callback([] { throw Error("hba mme is not implemented yet"); });
}

}  // namespace hba::cli
