#include "log_file.hpp"

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "hba/core/error.hpp"
#include "hba/version.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace fs = std::filesystem;

namespace {

std::mutex failure_mutex;
std::optional<std::string> failure;

std::string describeWriteError(int err) {
  if (err == ENOSPC) return "no space left on device (disk full)";
  if (err == EDQUOT) return "disk quota exceeded";
  return std::strerror(err != 0 ? err : EIO);
}

// Appends each message to the file and flushes it at once: a write that
// fails (a full disk) is remembered, with the file and the cause, so the run
// fails at the end instead of exiting 0 with a log that lost lines. (spdlog's
// file sink leaves debug lines in the stdio buffer, where a full disk is
// noticed only when the file is closed, and then by no one.)
class CheckedFileSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit CheckedFileSink(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "ab")) {
    if (!file_) failAt(path, "--log-file: cannot open the log file: " + describeWriteError(errno));
  }
  ~CheckedFileSink() override {
    if (file_) std::fclose(file_);
  }
  CheckedFileSink(const CheckedFileSink&) = delete;
  CheckedFileSink& operator=(const CheckedFileSink&) = delete;

 protected:
  void sink_it_(const spdlog::details::log_msg& message) override {
    spdlog::memory_buf_t line;
    formatter_->format(message, line);
    errno = 0;
    if (std::fwrite(line.data(), 1, line.size(), file_) != line.size()) return remember(errno);
    flush_();
  }
  void flush_() override {
    errno = 0;
    if (std::fflush(file_) != 0) remember(errno);
  }

 private:
  void remember(int err) {
    const std::lock_guard<std::mutex> lock(failure_mutex);
    if (!failure) failure = path_ + ": --log-file: cannot write the log: " + describeWriteError(err);
  }
  std::string path_;
  std::FILE* file_;
};

// hba's own log lines start "[2026-11-26 ...": a non-empty file that does
// not is something else (a trajectory, a report), which must not be appended to.
bool looksLikeHbaLog(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char head[6] = {};
  in.read(head, sizeof head);
  if (in.gcount() == 0) return true;  // empty
  if (in.gcount() < 6 || head[0] != '[' || head[5] != '-') return false;
  for (int i = 1; i < 5; ++i) {
    if (!std::isdigit(static_cast<unsigned char>(head[i]))) return false;
  }
  return true;
}

void checkLogPath(const fs::path& path, const CLI::App& command) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) failAt(path, "--log-file: is a folder; name the log file");
  if (fs::exists(status) && !fs::is_regular_file(status)) failAt(path, "--log-file: is not a regular file");
  for (const fs::path& input : runInputs()) {
    if (fs::equivalent(path, input, ec))
      failAt(path, "--log-file: is an input of this run; log to another file");
    if (isSameOrInside(path, input)) {
      failAt(path, "--log-file: is inside " + input.string() +
                       ", an input of this run (hba never writes into its input); log to another file");
    }
  }
  for (const fs::path& output : namedOutputs(command)) {
    if (isSameOrInside(path, output)) {
      failAt(path, "--log-file: is the output " + output.string() +
                       " or inside it, which this run writes whole; put the log beside it");
    }
  }
  const fs::path parent = fs::absolute(path).parent_path();
  if (!fs::is_directory(parent, ec))
    failAt(path, "--log-file: the folder " + parent.string() + " does not exist");
  if (fs::exists(status) && !looksLikeHbaLog(path)) {
    failAt(path,
           "--log-file: exists and is not an hba log (its first line is not '[YYYY-MM-DD ...'); hba appends "
           "only to its own logs: choose another file");
  }
}

}  // namespace

spdlog::sink_ptr openLogFile(const std::string& path, const CLI::App& command) {
  checkLogPath(path, command);
  auto sink = std::make_shared<CheckedFileSink>(path);
  // Its first line says which run wrote what follows; written at once, so a
  // log that cannot be written (a full disk) fails the run before any work,
  // even a command that would log nothing more.
  sink->set_pattern(kLogFilePattern);
  const std::string first =
      "hba " HBA_VERSION " " + command.get_name() + ", pid " + std::to_string(::getpid());
  sink->log(spdlog::details::log_msg("hba", spdlog::level::info, first));
  if (const auto failed = logFileFailure()) throw Error(*failed);
  return sink;
}

std::optional<std::string> logFileFailure() {
  spdlog::default_logger()->flush();  // the last lines too
  const std::lock_guard<std::mutex> lock(failure_mutex);
  return failure;
}

}  // namespace hba::cli
