#pragma once
// Opening what hba reads. A path must name a regular file (after symbolic
// links) before it is opened: a FIFO named like a scan would block open() and
// read() forever, a device never ends, and a loop of links is no "missing
// file". Every reader of scans, trajectories, stamps, loops, priors, settings
// and calibration goes through here, so each refuses them with one wording.
//
// "/dev/stdin" and the like are accepted when they lead to a regular file
// (`< poses.txt`) and refused when they lead to a pipe or a terminal: hba
// reads some files twice (the pose format is detected, then the poses read).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace hba {

// Throws hba::Error "<path>: <problem>" unless `path` is a regular file:
// "no such file", "is a broken symbolic link (to T)", "is a symbolic link
// loop", "is a folder, not a file", "is not a regular file (a FIFO)" (or a
// socket, a character or block device), "cannot be examined: <reason>".
void requireRegularFile(const std::filesystem::path& path);

// False when nothing at all is at `path`; true when a regular file is; throws
// as requireRegularFile for anything else (a FIFO, a folder, a broken link):
// for optional files found by name (times.txt, calib.txt, gt.txt).
bool regularFileIsPresent(const std::filesystem::path& path);

// Throws hba::Error unless `path` is a folder (after symbolic links):
// "<what> not found", "is a symbolic link loop", "is not a folder (expected
// a <what>)".
void requireFolder(const std::filesystem::path& path, const std::string& what);

// A regular file open for reading; closed when the object dies.
class InputFile {
 public:
  // Throws hba::Error naming the file when it is not a regular file or cannot
  // be opened. The type is checked again on the open file, so a file swapped
  // for a FIFO in between is refused too.
  explicit InputFile(const std::filesystem::path& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // The size when opened (the file may still change while it is read).
  std::uint64_t size() const { return size_; }
  // Reads up to `bytes`; fewer only at the end of the file. Throws hba::Error
  // naming the file when a read fails.
  std::size_t read(char* into, std::size_t bytes);

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

// The whole file as text, without a leading UTF-8 byte order mark (Windows
// editors write one; it is invisible, and "1" after it is not a number).
std::string readTextFile(const std::filesystem::path& path);

// `text` without a leading UTF-8 byte order mark (EF BB BF).
std::string_view withoutByteOrderMark(std::string_view text);

}  // namespace hba
