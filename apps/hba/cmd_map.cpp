// `hba map`: not implemented yet.
#include "commands.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

void registerMapCommand(CLI::App& app) {
  auto* command = app.add_subcommand("map", "(not implemented yet)");
  command->callback([] { throw Error("hba map is not implemented yet"); });
}

}  // namespace hba::cli
