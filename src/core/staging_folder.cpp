#include "core/staging_folder.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <system_error>

#include "core/path_inside.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"

namespace hba {
namespace fs = std::filesystem;

namespace {

fs::path besideWithSuffix(const fs::path& destination, const std::string& suffix) {
  return destination.parent_path() /
         ("." + destination.filename().string() + suffix + std::to_string(::getpid()));
}

// Staging folders (".NAME.partial-PID") and replaced outputs (".NAME.old-PID")
// of processes that no longer exist: killed outright (SIGKILL, power loss),
// they could not clean up.
void removeAbandonedStaging(const fs::path& destination) {
  const std::string base = "." + destination.filename().string();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(destination.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    for (const char* suffix : {".partial-", ".old-"}) {
      const std::string prefix = base + suffix;
      if (name.rfind(prefix, 0) != 0) continue;
      const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
      if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
        std::error_code ignored;
        fs::remove_all(entry.path(), ignored);
      }
    }
  }
}

// "7 files, 1.2 MiB": what replacing `folder` removes.
std::string contentSummary(const fs::path& folder) {
  std::size_t files = 0;
  std::uintmax_t bytes = 0;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(folder, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_directory(ec) || it->path().filename() == kOutputMarker) continue;
    ++files;
    const std::uintmax_t size = it->file_size(ec);
    if (!ec) bytes += size;
    ec.clear();
  }
  char text[64];
  std::snprintf(text, sizeof text, "%zu files, %.1f MiB", files,
                static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

// A non-empty destination may be replaced only with --force, and only if an
// earlier hba run wrote it (its marker): --force never deletes a user's files.
std::string checkReplaceable(const fs::path& destination, bool force) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(destination, ec))) return "";
  if (fs::is_symlink(fs::symlink_status(destination, ec))) {
    failAt(destination, "is a symbolic link; name the folder itself (hba replaces outputs whole)");
  }
  if (!fs::is_directory(destination, ec)) failAt(destination, "exists and is not a folder");
  if (fs::is_empty(destination, ec)) return "";
  if (!force) failAt(destination, "the output folder is not empty (use --force to replace it)");
  if (!fs::is_regular_file(destination / kOutputMarker, ec)) {
    failAt(destination, std::string("holds files hba did not write (no ") + kOutputMarker +
                            " marker): --force replaces only an earlier hba output or an empty folder; "
                            "remove it yourself or choose another output");
  }
  return "an earlier hba output (" + contentSummary(destination) + ")";
}

}  // namespace

// Folders no run may replace, whatever --force says: the file system's
// root, the home folder, and the current folder or any folder holding it
// (replacing it would pull the folder from under the user's shell).
void refuseProtectedFolder(const fs::path& folder) {
  const fs::path destination = fs::absolute(folder).lexically_normal();
  std::error_code ec;
  if (destination == destination.root_path())
    failAt(destination, "is the root folder; choose a folder to create");
  if (const char* home = std::getenv("HOME"); home && *home && fs::equivalent(destination, home, ec)) {
    failAt(destination, "is your home folder; choose a folder to create inside it");
  }
  const fs::path cwd = fs::current_path(ec);
  if (!ec && isSameOrInside(cwd, destination)) {
    failAt(destination, cwd == fs::weakly_canonical(destination, ec)
                            ? "is the current folder; choose a folder to create (e.g. -o out)"
                            : "holds the current folder " + cwd.string() + "; choose a folder to create");
  }
}

StagingFolder::StagingFolder(fs::path destination, bool force, const std::string& writer)
    : destination_(fs::absolute(std::move(destination)).lexically_normal()) {
  if (destination_.filename().empty()) destination_ = destination_.parent_path();
  refuseProtectedFolder(destination_);
  replaces_ = checkReplaceable(destination_, force);
  // Like mkdir -p: `-o results/run1` creates results/ too.
  std::error_code ec;
  fs::create_directories(destination_.parent_path(), ec);
  if (!fs::is_directory(destination_.parent_path(), ec)) {
    failAt(destination_, "cannot create the parent folder" + (ec ? ": " + ec.message() : std::string()));
  }
  lock_ = std::make_unique<OutputLock>(destination_);
  // Checked again under the lock: another run may have filled it meanwhile.
  replaces_ = checkReplaceable(destination_, force);
  removeAbandonedStaging(destination_);
  staging_ = besideWithSuffix(destination_, ".partial-");
  {
    // Registered and made under a deferral: an interrupt in between waits,
    // then removes the folder made (else it came after the removal).
    const InterruptDeferral defer;
    remove_on_interrupt_ = std::make_unique<RemoveOnInterrupt>(staging_, destination_);
    fs::remove_all(staging_, ec);
    if (!fs::create_directory(staging_, ec) || ec) {
      failAt(staging_, "cannot create the staging folder: " + ec.message());
    }
    interruptPointForTests("staging-made");
  }
  try {
    writeFileAtomically(
        staging_ / kOutputMarker,
        [&](std::ostream& out) {
          out << "Written by " << writer << ". `--force` may replace this folder whole; without this file it "
              << "would refuse to.\n";
        },
        false);
  } catch (...) {  // a full disk: no destructor runs for a half-made object
    fs::remove_all(staging_, ec);
    throw;
  }
}

StagingFolder::~StagingFolder() {
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_, ec);
  remove_on_interrupt_.reset();
  lock_.reset();
}

void StagingFolder::commit() {
  std::error_code ec;
  fs::path old;
  std::optional<RemoveOnInterrupt> old_on_interrupt;
  {
    // An interrupt waits for the swap: it finds the earlier output or the
    // new one in place, never neither.
    const InterruptDeferral deferral;
    interruptPointForTests("swap-begin");
    if (fs::exists(destination_, ec)) {
      old = besideWithSuffix(destination_, ".old-");
      fs::remove_all(old, ec);
      old_on_interrupt.emplace(old);
      fs::rename(destination_, old, ec);
      if (ec) failAt(destination_, "cannot move the old output folder aside: " + ec.message());
      interruptPointForTests("swap-middle");
    }
    fs::rename(staging_, destination_, ec);
    if (ec) {
      std::error_code restore_ec;
      if (!old.empty()) fs::rename(old, destination_, restore_ec);
      failAt(destination_, "cannot move the finished dataset into place: " + ec.message());
    }
    committed_ = true;
    remove_on_interrupt_.reset();
    noteOutputInPlace(destination_);
    interruptPointForTests("swap-end");
  }
  // An interrupt from here on finishes removing the earlier output.
  interruptPointForTests("old-removal");
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace hba
