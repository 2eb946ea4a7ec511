#include "log_file.hpp"

#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/basic_file_sink.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "hba/core/error.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace fs = std::filesystem;

namespace {

std::mutex failure_mutex;
std::optional<std::string> failure;

// A file sink that remembers a failed write instead of letting spdlog print
// it to stderr once and carry on as if the log were complete.
class CheckedFileSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit CheckedFileSink(const std::string& path) : file_(path, false) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& message) override {
    guard([&] { file_.log(message); });
  }
  void set_pattern_(const std::string& pattern) override { file_.set_pattern(pattern); }
  void set_formatter_(std::unique_ptr<spdlog::formatter> formatter) override {
    file_.set_formatter(std::move(formatter));
  }
  void flush_() override {
    guard([&] { file_.flush(); });
  }

 private:
  template <typename Write>
  void guard(Write write) {
    try {
      write();
    } catch (const spdlog::spdlog_ex& e) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = e.what();
    }
  }
  spdlog::sinks::basic_file_sink_st file_;
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
  try {
    return std::make_shared<CheckedFileSink>(path);
  } catch (const spdlog::spdlog_ex& e) {
    failAt(path, std::string("--log-file: cannot write the log file: ") + e.what());
  }
}

std::optional<std::string> logFileFailure() {
  const std::lock_guard<std::mutex> lock(failure_mutex);
  return failure;
}

}  // namespace hba::cli
