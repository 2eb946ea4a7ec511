#pragma once
// Warnings about input files hba reads anyway (a LAS header that counts 0
// points before its records, a scan with no points): logged once per file
// however often the file is read, and at most kNamedFilesPerProblem files of
// a folder named per problem, then one line saying more there have it, so a
// folder of thousands of such files gives a few lines, not thousands.
#include <cstddef>
#include <filesystem>
#include <string>

namespace hba::io {

inline constexpr std::size_t kNamedFilesPerProblem = 3;

// Logs "<path>: <sentence>" as a warning (spdlog) unless this file was
// already warned about for `problem` (a short name of the kind of problem).
// Thread-safe.
void warnAboutFile(const std::filesystem::path& path, const std::string& problem,
                   const std::string& sentence);

// For a trait every file of a folder a tool writes shares (a header another
// writer fills in its own way): logs "<path>: <sentence>" for the first file
// of its folder only, adding that the folder's other files are read alike.
// Thread-safe.
void warnOncePerFolder(const std::filesystem::path& path, const std::string& problem,
                       const std::string& sentence);

}  // namespace hba::io
