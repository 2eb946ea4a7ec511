// hba: hierarchical LiDAR bundle adjustment from the command line.
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "hba/core/error.hpp"
#include "hba/core/remove_on_interrupt.hpp"
#include "hba/version.hpp"
#include "number_checks.hpp"
#include "process_group.hpp"
#include "progress_display.hpp"
#include "usage_errors.hpp"
#include "version_text.hpp"

namespace {

// Logs go to stderr (results to stdout), and to --log-file with times and
// every debug message, whatever -q says.
void setUpLogging(bool verbose, bool quiet, const std::string& log_file) {
  auto console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  console->set_pattern("%^[%l]%$ %v");
  console->set_level(verbose ? spdlog::level::debug : quiet ? spdlog::level::warn : spdlog::level::info);
  std::vector<spdlog::sink_ptr> sinks{console};
  if (!log_file.empty()) {
    try {
      auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(log_file, false);
      file->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
      file->set_level(spdlog::level::debug);
      sinks.push_back(file);
    } catch (const spdlog::spdlog_ex& e) {
      throw hba::Error(log_file + ": cannot write the log file: " + e.what());
    }
  }
  auto logger = std::make_shared<spdlog::logger>("hba", sinks.begin(), sinks.end());
  logger->set_level(spdlog::level::debug);
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

// The tool's work once MPI (under mpirun) has started; the exit code.
int run(int argc, char** argv) {
  const hba::dist::Group& group = hba::cli::processGroup();
  CLI::App app{
      "hba: turns a drifting LiDAR sequence into a globally consistent map\n"
      "(Hierarchical LiDAR Bundle Adjustment, Liu et al., RA-L 2023)"};
  app.name("hba");
  app.set_version_flag("--version", hba::cli::versionText());
  app.require_subcommand(1);
  app.fallthrough();

  int threads = 0;
  bool verbose = false;
  bool quiet = false;
  std::string log_file;
  // More threads than 4096 is no machine hba runs on.
  app.add_option("-j,--threads", threads, "Worker threads (0 = all cores)")
      ->check(hba::cli::numberIn({1, 4096, false, false, "all cores"}, hba::NumberKind::Integer));
  app.add_flag("-v,--verbose", verbose, "Print debug messages");
  app.add_flag("-q,--quiet", quiet, "Print warnings and errors only");
  app.add_option("--log-file", log_file, "Also write every message, with times, to this file");
  app.footer(
      "Exit codes: 0 success, 1 failure (bad input, a run that could not finish), 2 usage error.\n"
      "Logs go to stderr, results to stdout. Docs: README.md and docs/.");

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
    // Under mpirun the members log alike: the first speaks for all, the
    // others report their errors only.
    setUpLogging(verbose, quiet, log_file);
    if (!group.root()) spdlog::default_logger()->sinks().front()->set_level(spdlog::level::err);
    if (group.size() > 1 && !app.got_subcommand("optimize")) {
      throw hba::Error("under mpirun only `hba optimize` runs (" + std::to_string(group.size()) +
                       " processes would each do the same work and write the same files)");
    }
    hba::cli::installProgressDisplay(!quiet && ::isatty(STDERR_FILENO) != 0);
    if (threads > 0) {
      thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                           static_cast<std::size_t>(threads));
    }
  });

  setUpLogging(false, false, "");  // until the flags are known
  if (argc == 1) {                 // `hba` alone: what it can do
    std::cout << app.help();
    return hba::cli::kExitSuccess;
  }
  if (const auto message = hba::cli::unknownCommand(app, argc, argv)) {
    spdlog::error("{}", *message);
    return hba::cli::kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return hba::cli::reportParseError(app, e, argc, argv);
  } catch (const hba::ValueError& e) {  // a setting or a flag's value: usage
    spdlog::error("{}", e.what());
    return hba::cli::kExitUsage;
  } catch (const hba::Error& e) {
    spdlog::error("{}", e.what());
    return hba::cli::kExitFailure;
  } catch (const std::exception& e) {
    spdlog::error("unexpected failure: {}", e.what());
    return hba::cli::kExitFailure;
  }
  return hba::cli::kExitSuccess;
}

}  // namespace

int main(int argc, char** argv) {
  // Before any thread starts: Ctrl-C then removes unfinished outputs.
  hba::startInterruptWatcher();
  try {
    hba::cli::startProcessGroup(argc, argv);  // MPI, under mpirun
  } catch (const hba::Error& e) {
    setUpLogging(false, false, "");
    spdlog::error("{}", e.what());
    return hba::cli::kExitFailure;
  }
  // Under mpirun a member that fails ends every member (no one waits).
  return hba::cli::endProcessGroup(run(argc, argv));
}
