#pragma once
// The check of a flag that names a file to read: CLI11's ExistingFile lets a
// FIFO through (the read then hangs) and calls a symbolic link loop "does not
// exist"; this one says what is there, in the readers' words.
#include <CLI/CLI.hpp>
#include <string>

#include "core/input_file.hpp"
#include "hba/core/error.hpp"

namespace hba::cli {

inline CLI::Validator inputFile() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          requireRegularFile(text);
        } catch (const Error& e) {
          return e.what();
        }
        return "";
      },
      "FILE");
}

}  // namespace hba::cli
