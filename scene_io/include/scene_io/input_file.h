#pragma once
// A first check of an input file, before a loader reads it: loaders report a missing file in their
// own words (or not at all), this says "no such file" the same way for every format.

#include <filesystem>

namespace trs {

/// Throws FileError unless `file` is a regular file that this process can open for reading.
void check_input_file(const std::filesystem::path& file);

}  // namespace trs
