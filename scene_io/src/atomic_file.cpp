#include "scene_io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

#include "scene_io/file_error.h"

namespace trs {
namespace {

std::string errno_text() { return std::strerror(errno); }

/// mkstemp creates files readable by the owner only; an output should get the permissions any
/// other new file would get (0666 less the umask).
mode_t default_file_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path destination) : destination_(std::move(destination)) {
  std::error_code ec;
  const auto status = std::filesystem::status(destination_, ec);  // follows links
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    open_stream();
    return;
  }
  const bool link = std::filesystem::is_symlink(std::filesystem::symlink_status(destination_, ec));
  open_temporary(link && std::filesystem::exists(status)
                     ? std::filesystem::canonical(destination_, ec)
                     : destination_);
}

void AtomicFile::open_temporary(const std::filesystem::path& target) {
  target_ = target;
  const auto directory =
      target_.has_parent_path() ? target_.parent_path() : std::filesystem::path(".");
  // Hidden, and named after the destination, so that a leftover (a killed process cannot clean
  // up) is recognisable.
  std::string hidden_name = ".";
  hidden_name += target_.filename().string();
  hidden_name += ".tmp-XXXXXX";
  const std::string pattern = (directory / hidden_name).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  fd_ = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd_ < 0) {
    throw FileError(destination_, "cannot create a temporary file in " + directory.string() + ": " +
                                      errno_text());
  }
  temporary_ = name.data();
  if (::fchmod(fd_, default_file_mode()) != 0) {
    const std::string problem = "cannot set permissions: " + errno_text();
    discard();
    throw FileError(destination_, problem);
  }
}

void AtomicFile::open_stream() {
  fd_ = ::open(destination_.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) throw FileError(destination_, "cannot open for writing: " + errno_text());
}

AtomicFile::~AtomicFile() {
  if (!committed_) discard();
}

void AtomicFile::write(const void* data, std::size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd_, bytes, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw FileError(destination_, "cannot write: " + errno_text());
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
}

void AtomicFile::commit() {
  // close() is where some file systems (NFS) report a failed write.
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw FileError(destination_, "cannot write: " + errno_text());
  if (!temporary_.empty() && std::rename(temporary_.c_str(), target_.c_str()) != 0) {
    throw FileError(destination_, "cannot replace it: " + errno_text());
  }
  committed_ = true;
}

void AtomicFile::discard() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
}

}  // namespace trs
