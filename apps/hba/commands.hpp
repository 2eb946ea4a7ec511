#pragma once
// Each subcommand of the `hba` tool lives in its own file and registers
// itself here. A command's callback throws hba::Error on bad input; main()
// turns that into a message and a non-zero exit.
#include <CLI/CLI.hpp>

namespace hba::cli {

void registerInfoCommand(CLI::App& app);
void registerSimulateCommand(CLI::App& app);
void registerOptimizeCommand(CLI::App& app);
void registerEvalCommand(CLI::App& app);
void registerMmeCommand(CLI::App& app);
void registerMapCommand(CLI::App& app);
void registerRenderCommand(CLI::App& app);
void registerExtractCommand(CLI::App& app);
void registerViewCommand(CLI::App& app);

}  // namespace hba::cli
