#pragma once
// An output file that appears complete or not at all. Data goes to a temporary file next to the
// destination (same directory, so the final rename is atomic and never crosses file systems);
// commit() renames it over the destination. Until then the destination, if it exists, is left
// untouched, and a failure or exception anywhere (the destructor runs) removes the temporary.
// No fsync: this protects against failed runs, not against power loss, and syncing gigabytes of
// samples would dominate the run time.
//
// A destination that is a symbolic link has its target replaced, the link kept. One that exists
// but is not a regular file (/dev/null, a FIFO, /dev/stdout) is written directly: renaming over
// it would replace a device with a file, and a stream cannot be made atomic anyway.

#include <cstddef>
#include <filesystem>
#include <string_view>

namespace trs {

class AtomicFile {
 public:
  /// Creates the temporary file; throws FileError (naming `destination`) if it cannot.
  explicit AtomicFile(std::filesystem::path destination);
  ~AtomicFile();

  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends bytes; throws FileError on failure (disk full, I/O error).
  void write(const void* data, std::size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }

  /// Closes the temporary and renames it to the destination; throws FileError on failure.
  void commit();

 private:
  void open_temporary(const std::filesystem::path& target);
  void open_stream();
  void discard() noexcept;

  std::filesystem::path destination_;  ///< as given, for messages
  std::filesystem::path target_;       ///< the file that commit() replaces
  std::filesystem::path temporary_;    ///< empty when writing a stream directly
  int fd_ = -1;
  bool committed_ = false;
};

}  // namespace trs
