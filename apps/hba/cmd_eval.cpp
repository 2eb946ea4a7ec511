// `hba eval`: not implemented yet.
#include "commands.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

void registerEvalCommand(CLI::App& app) {
  auto* command = app.add_subcommand("eval", "(not implemented yet)");
  command->callback([] { throw Error("hba eval is not implemented yet"); });
}

}  // namespace hba::cli
