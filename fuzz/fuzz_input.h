#pragma once
// What the fuzz targets share. The loaders take paths, as users' files come, so each input is
// written to a file with the extension that picks the parser. A parser may refuse an input with
// any exception the tools report as an error (they catch std::exception, print it and exit 1);
// a crash, a sanitizer report, a hang or running out of memory is a failure.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

namespace trs_fuzz {

/// Writes the input to this process's file of that extension and returns its path.
inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const auto path =
      std::filesystem::temp_directory_path() / ("trs-fuzz-" + std::to_string(::getpid()) + extension);
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                std::streamsize(size));
  return path;
}

/// Runs `parse` on the input written as a file of `extension`; a refusal is a fine outcome.
template <class Parse>
int parse_as_file(const std::uint8_t* data, std::size_t size, const std::string& extension, Parse&& parse) {
  const auto path = write_input(data, size, extension);
  try {
    parse(path);
  } catch (const std::exception&) {
  }
  return 0;
}

}  // namespace trs_fuzz
