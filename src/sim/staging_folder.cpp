#include "staging_folder.hpp"

#include <unistd.h>

#include <system_error>

#include "hba/core/error.hpp"

namespace hba::sim {
namespace fs = std::filesystem;

namespace {

fs::path besideWithSuffix(const fs::path& destination, const std::string& suffix) {
  return destination.parent_path() /
         ("." + destination.filename().string() + suffix + std::to_string(::getpid()));
}

}  // namespace

StagingFolder::StagingFolder(fs::path destination, bool force)
    : destination_(fs::absolute(std::move(destination)).lexically_normal()) {
  if (destination_.filename().empty()) destination_ = destination_.parent_path();
  std::error_code ec;
  if (fs::exists(destination_, ec)) {
    if (!fs::is_directory(destination_, ec)) failAt(destination_, "exists and is not a folder");
    if (!force && !fs::is_empty(destination_, ec)) {
      failAt(destination_, "the output folder is not empty (use --force to replace it)");
    }
  }
  if (!fs::is_directory(destination_.parent_path(), ec)) {
    failAt(destination_, "the parent folder does not exist");
  }
  staging_ = besideWithSuffix(destination_, ".partial-");
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec) {
    failAt(staging_, "cannot create the staging folder: " + ec.message());
  }
}

StagingFolder::~StagingFolder() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

void StagingFolder::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(destination_, ec)) {
    old = besideWithSuffix(destination_, ".old-");
    fs::remove_all(old, ec);
    fs::rename(destination_, old, ec);
    if (ec) failAt(destination_, "cannot move the old output folder aside: " + ec.message());
  }
  fs::rename(staging_, destination_, ec);
  if (ec) {
    std::error_code restore_ec;
    if (!old.empty()) fs::rename(old, destination_, restore_ec);
    failAt(destination_, "cannot move the finished dataset into place: " + ec.message());
  }
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace hba::sim
