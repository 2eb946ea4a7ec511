#pragma once
// hba reports bad input and failed I/O with exceptions of type hba::Error,
// whose message names the file and the problem. The command-line tool
// prints the message and exits non-zero.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace hba {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A value the caller chose (a flag, a setting in a --config file) outside
// what it may be, or a settings file that cannot be read as settings: the
// caller's mistake, not the data's. The command-line tool exits 2 for it.
class ValueError : public Error {
 public:
  using Error::Error;
};

// "<path>: <problem>", the one format every reader and writer uses.
[[noreturn]] void failAt(const std::filesystem::path& path, const std::string& problem);

}  // namespace hba
