#pragma once
// The one error type of the tools. Every failure is about some file (an input that is missing or
// malformed, an output that cannot be written), and a user fixing it needs to know which one, so
// the message is always "FILE: problem" and the command line prints it as is.

#include <filesystem>
#include <stdexcept>
#include <string>

namespace trs {

class FileError : public std::runtime_error {
 public:
  FileError(const std::filesystem::path& file, const std::string& problem)
      : std::runtime_error(file.string() + ": " + problem), file_(file) {}

  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
};

}  // namespace trs
