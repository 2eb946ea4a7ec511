// `hba info`: not implemented yet.
#include "commands.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

void registerInfoCommand(CLI::App& app) {
  auto* command = app.add_subcommand("info", "(not implemented yet)");
  command->callback([] { throw Error("hba info is not implemented yet"); });
}

}  // namespace hba::cli
