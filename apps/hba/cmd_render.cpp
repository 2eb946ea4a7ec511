// `hba render`: not implemented yet.
#include "commands.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

void registerRenderCommand(CLI::App& app) {
  auto* command = app.add_subcommand("render", "(not implemented yet)");
  command->callback([] { throw Error("hba render is not implemented yet"); });
}

}  // namespace hba::cli
