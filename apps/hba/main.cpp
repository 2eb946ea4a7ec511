// hba: hierarchical LiDAR bundle adjustment from the command line.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "core/remove_on_interrupt.hpp"
#include "hba/core/error.hpp"
#include "hba/settings/settings.hpp"
#include "hba/version.hpp"
#include "log_file.hpp"
#include "number_checks.hpp"
#include "output_dir.hpp"
#include "process_group.hpp"
#include "progress_display.hpp"
#include "usage_errors.hpp"
#include "version_text.hpp"

namespace {

// Logs go to stderr (results to stdout), and to --log-file with times and
// every debug message, whatever -q says. `command` is the chosen command,
// whose inputs and outputs the log file must not be.
void setUpLogging(bool verbose, bool quiet, const std::string& log_file, const CLI::App* command = nullptr) {
  auto console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  console->set_pattern("%^[%l]%$ %v");
  console->set_level(verbose ? spdlog::level::debug : quiet ? spdlog::level::warn : spdlog::level::info);
  std::vector<spdlog::sink_ptr> sinks{console};
  if (!log_file.empty() && command) {
    auto file = hba::cli::openLogFile(log_file, *command);
    file->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
    file->set_level(spdlog::level::debug);
    sinks.push_back(file);
  }
  auto logger = std::make_shared<spdlog::logger>("hba", sinks.begin(), sinks.end());
  logger->set_level(spdlog::level::debug);
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

// Results go to stdout: one that could not be written (a full disk,
// /dev/full, a closed stdout) fails the run instead of exiting 0, and so
// does a log file that lost a message.
int checkWritten(int exit_code) {
  if (exit_code != hba::cli::kExitSuccess) return exit_code;
  errno = 0;
  std::cout.flush();  // through stdout's buffer: the failing write may happen here
  const int cout_err = errno;
  errno = 0;
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || !std::cout;
  if (failed) {
    const int err = errno != 0 ? errno : cout_err != 0 ? cout_err : EIO;
    spdlog::error("cannot write the results to standard output: {}",
                  err == ENOSPC ? "no space left on device (disk full)" : std::strerror(err));
    return hba::cli::kExitFailure;
  }
  if (const auto failure = hba::cli::logFileFailure()) {
    spdlog::error("the log file is incomplete: {}", *failure);
    return hba::cli::kExitFailure;
  }
  return exit_code;
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
  app.add_option("-j,--threads", threads, "Worker threads (0 = all cores)")
      ->check(
          hba::cli::numberIn({1, hba::kMostThreads, false, false, "all cores"}, hba::NumberKind::Integer));
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
  hba::cli::registerExtractCommand(app);
  hba::cli::registerViewCommand(app);

  // Threads and log level must be set before any subcommand callback runs.
  std::unique_ptr<tbb::global_control> thread_limit;
  app.parse_complete_callback([&] {
    // What the run reads, so that no output (nor the log) can replace it.
    const CLI::App* command = app.get_subcommands().empty() ? nullptr : app.get_subcommands().front();
    if (command) hba::cli::recordRunInputs(*command);
    // Under mpirun the members log alike: the first speaks for all, the
    // others report their errors only.
    setUpLogging(verbose, quiet, group.root() ? log_file : std::string(), command);
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
    hba::waitIfInterrupted();  // a file removed by the interrupt is not the input's fault
    spdlog::error("{}", e.what());
    return hba::cli::kExitFailure;
  } catch (const std::exception& e) {
    hba::waitIfInterrupted();
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
  const int exit_code = hba::cli::endProcessGroup(checkWritten(run(argc, argv)));
  // An interrupt being handled ends the process itself; a later one finds
  // every output complete and is ignored.
  hba::closeInterruptWindow();
  return exit_code;
}
