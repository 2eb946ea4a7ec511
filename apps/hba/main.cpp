// hba: hierarchical LiDAR bundle adjustment from the command line.
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <memory>

#include "commands.hpp"
#include "number_checks.hpp"
#include "hba/core/error.hpp"
#include "hba/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"hba: turns a drifting LiDAR sequence into a globally consistent map\n"
               "(Hierarchical LiDAR Bundle Adjustment, Liu et al., RA-L 2023)"};
  app.set_version_flag("--version", std::string(HBA_VERSION));
  app.require_subcommand(1);
  app.fallthrough();

  int threads = 0;
  bool verbose = false;
  bool quiet = false;
  app.add_option("-j,--threads", threads, "Worker threads (0 = all cores)")
      ->check(hba::cli::nonNegative());
  app.add_flag("-v,--verbose", verbose, "Print debug messages");
  app.add_flag("-q,--quiet", quiet, "Print warnings and errors only");

  hba::cli::registerInfoCommand(app);
  hba::cli::registerSimulateCommand(app);
  hba::cli::registerOptimizeCommand(app);
  hba::cli::registerEvalCommand(app);
  hba::cli::registerMmeCommand(app);
  hba::cli::registerMapCommand(app);
  hba::cli::registerRenderCommand(app);

  // Threads and log level must be set before any subcommand callback runs.
  std::unique_ptr<tbb::global_control> thread_limit;
  app.parse_complete_callback([&] {
    spdlog::set_pattern("%^[%l]%$ %v");
    spdlog::set_level(verbose ? spdlog::level::debug
                              : quiet ? spdlog::level::warn : spdlog::level::info);
    if (threads > 0) {
      thread_limit = std::make_unique<tbb::global_control>(
          tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    }
  });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const hba::Error& e) {
    spdlog::error("{}", e.what());
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("unexpected failure: {}", e.what());
    return 1;
  }
  return 0;
}
