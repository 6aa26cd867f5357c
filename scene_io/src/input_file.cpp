#include "scene_io/input_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "scene_io/file_error.h"

namespace trs {

void check_input_file(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (status.type() == std::filesystem::file_type::not_found) throw FileError(file, "no such file");
  if (ec) throw FileError(file, "cannot access: " + ec.message());
  if (std::filesystem::is_directory(status)) throw FileError(file, "is a directory, not a file");
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw FileError(file, std::string("cannot open: ") + std::strerror(errno));
  ::close(fd);
}

void check_image_size(const std::filesystem::path& file, int width, int height) {
  if (width <= kMaxImageSide && height <= kMaxImageSide) return;
  throw FileError(file, "image is " + std::to_string(width) + " x " + std::to_string(height) +
                            " texels, more than the 16384 x 16384 an input image may have");
}

}  // namespace trs
